#include "geo/normalize.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <GeographicLib/Geodesic.hpp>
#include <GeographicLib/LocalCartesian.hpp>
#include <GeographicLib/UTMUPS.hpp>
#include <cpl_conv.h>
#include <cpl_error.h>
#include <gdal_alg.h>
#include <gdalgrid.h>
#include <nanoflann.hpp>
#include <fmt/format.h>

#include "core/number_format.h"
#include "geo/crs_frame.h"
#include "geo/linear_gridding.h"

namespace relief::geo {

using GeographicLib::GeographicErr;
using GeographicLib::UTMUPS;

double centreLongitude(std::vector<double> lons) {
    if (lons.empty()) return 0;
    for (double& l : lons) l = std::remainder(l, 360.0);  // -180..180
    std::sort(lons.begin(), lons.end());
    // Longitudes lie on a circle: the smallest arc that holds them all is the
    // circle less its widest gap (which, for data across the antimeridian, is
    // not the one between -180 and 180).
    size_t widest = lons.size() - 1;  // the gap from the last back round to the first
    double gap = lons.front() + 360 - lons.back();
    for (size_t i = 0; i + 1 < lons.size(); ++i)
        if (lons[i + 1] - lons[i] > gap) gap = lons[i + 1] - lons[i], widest = i;
    const double start = lons[(widest + 1) % lons.size()];
    const double arc = 360 - gap;
    return std::remainder(start + 0.5 * arc, 360.0);
}

std::optional<Frame> chooseFrame(const scene::FrameSpec& spec,
                                 const std::vector<GeoSample>& samples, Diagnostics& diags) {
    double latMin = 90, latMax = -90;
    std::vector<double> lons;
    lons.reserve(samples.size());
    for (const auto& s : samples) {
        latMin = std::min(latMin, s.latDeg);
        latMax = std::max(latMax, s.latDeg);
        lons.push_back(s.lonDeg);
    }
    const double latC = 0.5 * (latMin + latMax);
    const double lonC = centreLongitude(std::move(lons));
    Frame f;
    f.kind = spec.kind;
    if (f.kind == scene::FrameKind::Raster) {
        diags.error(spec.locs.at("frame.kind"),
                    "frame.kind = \"raster\" is the CRS of a raster DEM, and these samples are scattered points: "
                    "use \"utm\" or \"local\"");
        return std::nullopt;
    }
    if (f.kind == scene::FrameKind::Local) {
        f.originLatDeg = latC;
        f.originLonDeg = lonC;
        return f;
    }
    if (spec.utmZone == "auto") {
        f.utmZone = UTMUPS::StandardZone(latC, lonC);
        f.northp = latC >= 0;
        return f;
    }
    try {
        UTMUPS::DecodeZone(spec.utmZone, f.utmZone, f.northp);
    } catch (const GeographicErr&) {
        diags.error(spec.locs.at("frame.zone"),
                    fmt::format("frame.zone = \"{}\" is not a UTM zone; write a number 1-60 and "
                                "a hemisphere, e.g. \"60S\", or \"auto\"",
                                spec.utmZone));
        return std::nullopt;
    }
    return f;
}

std::vector<FramePoint> projectSamples(const Frame& frame, const std::vector<GeoSample>& samples,
                                       Diagnostics& diags) {
    std::vector<FramePoint> out;
    out.reserve(samples.size());
    int reported = 0;
    // A point the frame cannot hold (the readers let through no such sample;
    // this guards every other caller) is refused at its row, not drawn at NaN.
    auto keep = [&](const GeoSample& s, const FramePoint& fp) {
        if (std::isfinite(fp.p.x) && std::isfinite(fp.p.y) && std::isfinite(fp.p.z)) return out.push_back(fp);
        if (++reported <= 20)
            diags.error(s.loc, fmt::format("lat {}° lon {}° elev {} m projects to a point that is not finite in {}",
                                           formatShortest(s.latDeg), formatShortest(s.lonDeg),
                                           formatShortest(s.elevM), frame.describe()));
    };
    if (frame.kind == scene::FrameKind::Local) {
        const GeographicLib::LocalCartesian lc(frame.originLatDeg, frame.originLonDeg, 0.0);
        for (const auto& s : samples) {
            FramePoint fp{{}, s.loc};
            lc.Forward(s.latDeg, s.lonDeg, s.elevM, fp.p.x, fp.p.y, fp.p.z);
            keep(s, fp);
        }
        return out;
    }
    if (frame.kind == scene::FrameKind::Raster) {
        for (const auto& s : samples) {
            FramePoint fp{{0, 0, s.elevM}, s.loc};
            if (!lonLatToCrsFrame(frame, s.lonDeg, s.latDeg, fp.p.x, fp.p.y))
                fp.p.x = std::numeric_limits<double>::quiet_NaN();
            keep(s, fp);
        }
        return out;
    }
    for (const auto& s : samples) {
        FramePoint fp{{}, s.loc};
        try {
            int zone = 0;
            bool northp = false;
            double gamma, k;
            UTMUPS::Forward(s.latDeg, s.lonDeg, zone, northp, fp.p.x, fp.p.y, gamma, k,
                            frame.utmZone);
            if (northp != frame.northp)  // keep one hemisphere's false northing for all
                fp.p.y += frame.northp ? -UTMUPS::UTMShift() : UTMUPS::UTMShift();
        } catch (const GeographicErr& e) {
            if (++reported <= 20)
                diags.error(s.loc, fmt::format("lat {}° lon {}° cannot be projected into {} ({}); "
                                               "use frame.kind = \"local\" or another zone",
                                               formatShortest(s.latDeg), formatShortest(s.lonDeg),
                                               frame.describe(), e.what()));
            continue;
        }
        fp.p.z = s.elevM;
        keep(s, fp);
    }
    return out;
}

std::optional<GeoPoint> reverse(const Frame& frame, const Vec3& p) {
    try {
        GeoPoint g;
        if (frame.kind == scene::FrameKind::Local) {
            const GeographicLib::LocalCartesian lc(frame.originLatDeg, frame.originLonDeg, 0.0);
            lc.Reverse(p.x, p.y, p.z, g.latDeg, g.lonDeg, g.heightM);
            return g;
        }
        g.heightM = p.z;
        if (frame.kind == scene::FrameKind::Raster) {
            if (!crsFrameToLonLat(frame, p.x, p.y, g.lonDeg, g.latDeg)) return std::nullopt;
            return g;
        }
        double gamma, k;
        UTMUPS::Reverse(frame.utmZone, frame.northp, p.x, p.y, g.latDeg, g.lonDeg, gamma, k);
        return g;
    } catch (const GeographicErr&) {
        return std::nullopt;
    }
}

namespace {

// The bearing of the frame's y axis at (x, y): of the geodesic between the
// points 5 m south and north of it on the grid, the mean of its azimuths at
// its ends (its azimuth at its middle, to second order): what GeographicLib's
// gamma is for UTM, for any CRS.
double gridNorthBearingDeg(const Frame& frame, double x, double y) {
    const auto south = reverse(frame, {x, y - 5, 0}), north = reverse(frame, {x, y + 5, 0});
    if (!south || !north) return 0;
    double azimuth0, azimuth1;
    GeographicLib::Geodesic::WGS84().Inverse(south->latDeg, south->lonDeg, north->latDeg, north->lonDeg, azimuth0,
                                             azimuth1);
    return 0.5 * (azimuth0 + azimuth1);
}

}  // namespace

double gridConvergenceDeg(const Frame& frame, double x, double y) {
    if (frame.kind == scene::FrameKind::Local) return 0;
    if (frame.kind == scene::FrameKind::Raster) return gridNorthBearingDeg(frame, x, y);
    try {
        double lat, lon, gamma, k;
        UTMUPS::Reverse(frame.utmZone, frame.northp, x, y, lat, lon, gamma, k);
        return gamma;
    } catch (const GeographicErr&) {
        return 0;
    }
}

std::optional<Vec3> forward(const Frame& frame, const GeoPoint& point) {
    Diagnostics ignored;
    const auto projected = projectSamples(frame, {GeoSample{point.lonDeg, point.latDeg, point.heightM, {}}}, ignored);
    if (projected.empty()) return std::nullopt;
    return projected[0].p;
}

namespace {

// One GDALGridCreate call. GDAL registers pixel centres, so the nodes
// x0 + i*dx are the centres of a raster spanning [x0 - dx/2, x0 + (n-1/2)dx];
// GDAL's row 0 is at the smallest y, like ours.
int CPL_STDCALL reportGridProgress(double fraction, const char*, void* fn) {
    (*static_cast<const GridProgressFn*>(fn))(fraction);
    return TRUE;
}

bool gdalGrid(const char* algorithmAndOptions, const std::vector<double>& xs,
              const std::vector<double>& ys, const std::vector<double>& zs,
              const ControlNet& net, std::vector<double>& out, std::string& error,
              const GridProgressFn& progress) {
    GDALGridAlgorithm algorithm;
    void* options = nullptr;
    if (ParseAlgorithmAndOptions(algorithmAndOptions, &algorithm, &options) != CE_None) {
        error = CPLGetLastErrorMsg();
        return false;
    }
    const int rows = net.grid.rows, cols = net.grid.cols;
    out.assign(static_cast<size_t>(rows) * cols, 0.0);
    CPLPushErrorHandler(CPLQuietErrorHandler);
    // GDAL's SSE/AVX inverse-distance kernels work in float32, which rounds UTM
    // northings (~6e6 m) to half a metre; the double-precision path is exact.
    CPLSetThreadLocalConfigOption("GDAL_USE_AVX", "NO");
    CPLSetThreadLocalConfigOption("GDAL_USE_SSE", "NO");
    const CPLErr err = GDALGridCreate(
        algorithm, options, static_cast<GUInt32>(xs.size()), xs.data(), ys.data(), zs.data(),
        net.x0 - 0.5 * net.dx, net.x0 + (cols - 0.5) * net.dx, net.y0 - 0.5 * net.dy,
        net.y0 + (rows - 0.5) * net.dy, static_cast<GUInt32>(cols), static_cast<GUInt32>(rows),
        GDT_Float64, out.data(), progress ? reportGridProgress : nullptr,
        const_cast<GridProgressFn*>(&progress));
    if (err != CE_None) error = CPLGetLastErrorMsg();
    CPLSetThreadLocalConfigOption("GDAL_USE_AVX", nullptr);
    CPLSetThreadLocalConfigOption("GDAL_USE_SSE", nullptr);
    CPLPopErrorHandler();
    CPLFree(options);
    return err == CE_None;
}

constexpr double kNoData = -1.0e30;

// The samples' (x, y) as nanoflann's dataset.
struct SampleCloud {
    const std::vector<double>& xs;
    const std::vector<double>& ys;
    size_t kdtree_get_point_count() const { return xs.size(); }
    double kdtree_get_pt(size_t i, size_t dim) const { return dim == 0 ? xs[i] : ys[i]; }
    template <class Box>
    bool kdtree_get_bbox(Box&) const { return false; }
};
using SampleTree =
    nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<double, SampleCloud>, SampleCloud, 2, size_t>;

// The height of the nearest sample at each of `nodes` (indices into the net,
// row-major), through a k-d tree: a query per node, not a pass over every
// sample per node (which is what GDAL's nearest neighbour with radius 0 does:
// minutes for a net of a million nodes). A node equally far from several
// samples takes the first of them, as GDAL's search does, and the nodes sit
// where GDAL places them, so the result is GDAL's, faster.
void fillFromNearestSample(const std::vector<double>& xs, const std::vector<double>& ys,
                           const std::vector<double>& zs, const ControlNet& net,
                           const std::vector<size_t>& nodes, std::vector<double>& z) {
    if (nodes.empty()) return;
    const SampleCloud cloud{xs, ys};
    SampleTree tree(2, cloud, nanoflann::KDTreeSingleIndexAdaptorParams(16));
    const int cols = net.grid.cols, rows = net.grid.rows;
    const double xmin = net.x0 - 0.5 * net.dx, xmax = net.x0 + (cols - 0.5) * net.dx;
    const double ymin = net.y0 - 0.5 * net.dy, ymax = net.y0 + (rows - 0.5) * net.dy;
    const double deltaX = (xmax - xmin) / cols, deltaY = (ymax - ymin) / rows;
    std::vector<std::pair<size_t, double>> tied;
    nanoflann::SearchParams all;
    all.sorted = false;
    for (size_t node : nodes) {
        const double q[2] = {xmin + (static_cast<double>(node % cols) + 0.5) * deltaX,
                             ymin + (static_cast<double>(node / cols) + 0.5) * deltaY};
        size_t nearest = 0;
        double d2 = 0;
        tree.knnSearch(q, 1, &nearest, &d2);
        // Every sample at that distance (rarely more than one): the first wins.
        tied.clear();
        tree.radiusSearch(q, d2 * (1 + 1e-12) + 1e-300, tied, all);
        for (const auto& [index, dist] : tied)
            if (dist < d2 || (dist == d2 && index < nearest)) nearest = index, d2 = dist;
        z[node] = zs[nearest];
    }
}

}  // namespace

std::optional<FrameBox> frameBoxInside(const Frame& frame, const LonLatBox& w) {
    double west = -1e300, east = 1e300, south = -1e300, north = 1e300;
    constexpr int kEdgePoints = 64;
    for (int i = 0; i <= kEdgePoints; ++i) {
        const double f = static_cast<double>(i) / kEdgePoints;
        const double lon = w.west + f * (w.east - w.west), lat = w.south + f * (w.north - w.south);
        const auto onWest = forward(frame, {w.west, lat, 0}), onEast = forward(frame, {w.east, lat, 0});
        const auto onSouth = forward(frame, {lon, w.south, 0}), onNorth = forward(frame, {lon, w.north, 0});
        if (!onWest || !onEast || !onSouth || !onNorth) return std::nullopt;
        west = std::max(west, onWest->x), east = std::min(east, onEast->x);
        south = std::max(south, onSouth->y), north = std::min(north, onNorth->y);
    }
    if (!(east > west && north > south)) return std::nullopt;
    return FrameBox{west, south, east, north};
}

namespace {

// About one pixel of a still `widthPx` wide that shows the extent across it,
// rounded up to two significant digits (a spacing worth writing down); 0 without a still.
// About one pixel of the still on the ground, rounded up to two figures: the
// extent's longer side over the still's width, or where the eye comes nearest.
double stillSpacingM(double width, double height, const NetBudget& budget) {
    if (budget.stillWidthPx <= 0) return 0;
    const double pixel = budget.nearestPixelM ? budget.nearestPixelM(std::max(width, height))
                                              : std::max(width, height) / budget.stillWidthPx;
    if (!(pixel > 0)) return 0;
    const double unit = std::pow(10.0, std::floor(std::log10(pixel)) - 1);
    return std::ceil(pixel / unit - 1e-9) * unit;
}

}  // namespace

bool layoutNet(const scene::NetSpec& spec, FrameBox dataBox, double defaultSpacingM, GeoGrid& net, Diagnostics& diags,
               const NetBudget& budget) {
    if (spec.extentLonLat) {
        const auto box = frameBoxInside(net.frame, *spec.extentLonLat);
        if (!box) {
            diags.error(spec.locs.at("net.extent_lonlat"),
                        fmt::format("net.extent_lonlat does not fit in {}: choose a smaller window or "
                                    "frame.kind = \"local\"",
                                    net.frame.describe()));
            return false;
        }
        dataBox = *box;
    }
    const FrameBox& e = spec.extentM ? *spec.extentM : dataBox;
    const double xmin = e.west, ymin = e.south, xmax = e.east, ymax = e.north;
    const double width = xmax - xmin, height = ymax - ymin;
    int rows = spec.rows, cols = spec.cols;
    const bool countsGiven = spec.locs.has("net.rows") || spec.locs.has("net.cols");
    double spacing = spec.spacingM > 0 ? spec.spacingM : countsGiven ? 0 : defaultSpacingM;
    // Data with a spacing of their own (a raster, a lattice) finer than the still shows: a coarser net.
    // (At least twice as fine: a net a few per cent coarser than the cells would lose them for nothing.)
    if (const double still = stillSpacingM(width, height, budget);
        spacing > 0 && spec.spacingM <= 0 && still >= 2 * spacing)
        spacing = still;
    if (spacing > 0) {
        // The largest net with this spacing inside the extent, centred in it.
        // Within a millionth of a node: an extent of whole cells far from the origin rounds a little short.
        const double across = std::floor(width / spacing + 1e-6) + 1, up = std::floor(height / spacing + 1e-6) + 1;
        const bool given = spec.spacingM > 0;  // else the data's own spacing: no key of the scene to blame
        const std::string spacingSaid = given ? fmt::format("net.spacing_m = {} m", formatShortest(spacing))
                                              : fmt::format("a net at the data's own spacing, {} m,", formatShortest(spacing));
        if (!(across >= 4 && up >= 4)) {
            diags.error(spec.locs.at(given ? "net.spacing_m" : "net"),
                        fmt::format("{} gives only {:.0f} x {:.0f} nodes over the {} x {} m extent; at least "
                                    "4 x 4 are needed: {}",
                                    spacingSaid, up, across, formatShortest(width), formatShortest(height),
                                    given ? "use a smaller spacing" : "give a smaller net.spacing_m"));
            return false;
        }
        if (across * up > budget.maxNodes) {
            diags.error(spec.locs.at(given ? "net.spacing_m" : "net"),
                        fmt::format("{} gives {:.0f} x {:.0f} nodes over the {} x {} m extent, more than "
                                    "{:.3g} allowed by {}: {}",
                                    spacingSaid, up, across, formatShortest(width), formatShortest(height),
                                    budget.maxNodes, budget.why,
                                    given ? "use a larger spacing" : "give net.spacing_m (larger) or net.rows and net.cols"));
            return false;
        }
        cols = static_cast<int>(across);
        rows = static_cast<int>(up);
        net.dx = net.dy = spacing;
        net.x0 = xmin + 0.5 * (width - (cols - 1) * net.dx);
        net.y0 = ymin + 0.5 * (height - (rows - 1) * net.dy);
    } else {
        if (double(rows) * double(cols) > budget.maxNodes) {
            diags.error(spec.locs.at(spec.locs.has("net.rows") ? "net.rows" : "net.cols"),
                        fmt::format("net.rows = {} and net.cols = {} give {:.3g} nodes, more than {:.3g} allowed by "
                                    "{}: use fewer rows and columns",
                                    rows, cols, double(rows) * double(cols), budget.maxNodes, budget.why));
            return false;
        }
        net.dx = width / (cols - 1);
        net.dy = height / (rows - 1);
        net.x0 = xmin;
        net.y0 = ymin;
    }
    net.grid.rows = rows;
    net.grid.cols = cols;
    return !budget.fits || budget.fits(net, diags);
}

std::string netSpacingReason(const scene::NetSpec& spec, const GeoGrid& net, double dataSpacingM, const NetBudget& budget) {
    if (spec.spacingM > 0) return "net.spacing_m";
    if (spec.locs.has("net.rows") || spec.locs.has("net.cols")) return "net.rows and net.cols";
    if (dataSpacingM > 0 && net.dx > dataSpacingM * (1 + 1e-9))
        return fmt::format("about one pixel of the {} px wide still{}, coarser than the data's {:.3g} m, which it "
                           "cannot show",
                           budget.stillWidthPx, budget.nearestPixelM ? " where the eye comes nearest the ground" : "",
                           dataSpacingM);
    return "the data's own spacing";
}

std::optional<ControlNet> gridSamples(const scene::NetSpec& spec, const std::string& samplesName,
                                      const Frame& frame, const std::vector<FramePoint>& points,
                                      Diagnostics& diags, const GridProgressFn& progress, const NetBudget& budget) {
    const std::string& csv = samplesName;
    if (points.size() < 4) {
        diags.error({csv, 0, 0}, fmt::format("only {} distinct sample point(s); at least 4 are "
                                             "needed to build a surface",
                                             points.size()));
        return std::nullopt;
    }
    ControlNet net;
    net.frame = frame;
    net.sampleCount = points.size();
    double xmin = 1e300, xmax = -1e300, ymin = 1e300, ymax = -1e300;
    for (const auto& fp : points) {
        xmin = std::min(xmin, fp.p.x), xmax = std::max(xmax, fp.p.x);
        ymin = std::min(ymin, fp.p.y), ymax = std::max(ymax, fp.p.y);
    }
    if (!layoutNet(spec, FrameBox{xmin, ymin, xmax, ymax}, 0, net, diags, budget)) return std::nullopt;
    net.spacingReason = spec.spacingM > 0 ? "net.spacing_m" : "net.rows and net.cols (64 x 64 when not given)";
    if (budget.beforeReading && !budget.beforeReading(net)) return std::nullopt;
    const int rows = net.grid.rows, cols = net.grid.cols;

    std::vector<double> xs, ys, zs;
    xs.reserve(points.size()), ys.reserve(points.size()), zs.reserve(points.size());
    for (const auto& fp : points) {
        xs.push_back(fp.p.x);
        ys.push_back(fp.p.y);
        zs.push_back(fp.p.z);
    }
    std::vector<double> z(static_cast<size_t>(rows) * cols, kNoData);
    std::string error;
    const scene::Gridding gridding =
        spec.gridding == scene::Gridding::Fit && spec.linearBeforeFit ? scene::Gridding::Linear : spec.gridding;
    switch (gridding) {
        case scene::Gridding::Linear: {
            const GridLayout layout{net.x0 - 0.5 * net.dx, net.x0 + (cols - 0.5) * net.dx,
                                    net.y0 - 0.5 * net.dy, net.y0 + (rows - 0.5) * net.dy, cols, rows};
            error = gridLinear(xs, ys, zs, layout, kNoData, z, nullptr, 0, progress);
            break;
        }
        case scene::Gridding::InverseDistance: {
            const std::string algorithm = fmt::format("invdist:power=2:smoothing=0:nodata={}", kNoData);
            gdalGrid(algorithm.c_str(), xs, ys, zs, net, z, error, progress);
            break;
        }
        // Every node from the k-d tree below. The fit replaces every height; until then the net
        // serves only to choose the depth for the still, for which the nearest sample is enough,
        // and a k-d tree of 770,000 samples takes a fraction of a second where their triangulation
        // takes ten.
        case scene::Gridding::Nearest:
        case scene::Gridding::Fit: break;
    }
    if (!error.empty()) {
        diags.error({csv, 0, 0}, fmt::format("GDAL gridding failed: {}", error));
        return std::nullopt;
    }
    // Nodes without a value (outside the samples' convex hull, for linear
    // gridding; every node, for nearest): the nearest sample.
    std::vector<size_t> empty;
    for (size_t i = 0; i < z.size(); ++i)
        if (z[i] <= kNoData * 0.5) empty.push_back(i);
    fillFromNearestSample(xs, ys, zs, net, empty, z);
    if (progress) progress(1.0);
    if (spec.gridding == scene::Gridding::Linear || spec.gridding == scene::Gridding::InverseDistance)
        net.filledOutsideHull = empty.size();

    net.grid.points.resize(z.size());
    for (int r = 0; r < rows; ++r)
        for (int c = 0; c < cols; ++c)
            net.grid.at(r, c) = {net.x0 + c * net.dx, net.y0 + r * net.dy,
                                 z[static_cast<size_t>(r) * cols + c]};
    // The highest sample on the net (an extent may leave the highest of all off it); none: the highest node.
    const double west = std::min(net.x0, net.xMax()), east = std::max(net.x0, net.xMax());
    const double south = std::min(net.y0, net.yMax()), north = std::max(net.y0, net.yMax());
    for (const auto& fp : points)
        if (fp.p.x >= west && fp.p.x <= east && fp.p.y >= south && fp.p.y <= north &&
            (!net.highestSample || fp.p.z > net.highestSample->z))
            net.highestSample = fp.p;
    if (spec.gridding == scene::Gridding::Fit) {
        auto samples = std::make_shared<std::vector<Vec3>>();
        samples->reserve(points.size());
        for (const auto& fp : points) samples->push_back(fp.p);
        net.fitSamples = std::move(samples);
    }
    return net;
}

std::optional<ControlNet> normalize(const scene::FrameSpec& frameSpec, const scene::NetSpec& net,
                                    const std::string& samplesName,
                                    const std::vector<GeoSample>& samples, Diagnostics& diags,
                                    const GridProgressFn& progress, const NetBudget& budget) {
    auto frame = chooseFrame(frameSpec, samples, diags);
    if (!frame) return std::nullopt;
    auto points = projectSamples(*frame, samples, diags);
    if (diags.hasErrors()) return std::nullopt;
    return gridSamples(net, samplesName, *frame, points, diags, progress, budget);
}

std::string netToCsv(const GeoGrid& net) {
    std::string out = "x,y,z\n";
    char buf[100];
    for (const Vec3& p : net.grid.points) {
        char* e = writeFixed(buf, p.x, 4);
        *e++ = ',';
        e = writeFixed(e, p.y, 4);
        *e++ = ',';
        e = writeFixed(e, p.z, 4);
        *e++ = '\n';
        out.append(buf, e);
    }
    return out;
}

std::string netToAsciiGrid(const GeoGrid& net) {
    const int rows = net.grid.rows, cols = net.grid.cols;
    std::string out = fmt::format(
        "ncols {}\nnrows {}\nxllcenter {}\nyllcenter {}\ncellsize {}\nNODATA_value -9999\n", cols,
        rows, formatShortest(net.x0), formatShortest(net.y0), formatShortest(net.dx));
    char buf[40];
    for (int r = rows - 1; r >= 0; --r) {
        for (int c = 0; c < cols; ++c) {
            char* e = writeFixed(buf, net.grid.at(r, c).z, 4);
            *e++ = c + 1 < cols ? ' ' : '\n';
            out.append(buf, e);
        }
    }
    return out;
}

}  // namespace relief::geo
