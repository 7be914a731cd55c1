#include "geo/raster_footprint.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include <cpl_error.h>
#include <fmt/format.h>

#include <GeographicLib/Geodesic.hpp>

#include "core/number_format.h"
#include "geo/crs_frame.h"
#include "geo/normalize.h"

namespace relief::geo {

namespace {

// Whether the scan for the data's box costs little: a raster of at most 1e8
// cells, or one with an overview (which GDAL then reads instead) of at most
// 4e6. A larger raster's default box is all of it.
bool dataBoxAffordable(GDALRasterBandH band, double cells) {
    if (cells <= 1e8) return true;
    for (int i = 0; i < GDALGetOverviewCount(band); ++i) {
        GDALRasterBandH o = GDALGetOverview(band, i);
        if (o && double(GDALGetRasterBandXSize(o)) * GDALGetRasterBandYSize(o) <= 4e6) return true;
    }
    return false;
}

// The box of cells that holds every cell with data, so that a raster with a
// nodata border (a region, a coastline tile) defaults to its data, not to its
// border. Read at most kScan cells across, and widened by one read cell;
// nullopt when no read cell has data.
std::optional<PixelBox> dataBox(GDALRasterBandH band, int width, int height, double noData) {
    constexpr int kScan = 1024;
    const int bw = std::min(width, kScan), bh = std::min(height, kScan);
    std::vector<double> cells(static_cast<size_t>(bw) * bh);
    CPLPushErrorHandler(CPLQuietErrorHandler);
    const CPLErr err = GDALRasterIO(band, GF_Read, 0, 0, width, height, cells.data(), bw, bh, GDT_Float64, 0, 0);
    CPLPopErrorHandler();
    if (err != CE_None) return PixelBox{0, 0, double(width), double(height)};  // the warper will say why
    int c0 = bw, c1 = -1, r0 = bh, r1 = -1;
    for (int r = 0; r < bh; ++r)
        for (int c = 0; c < bw; ++c) {
            const double v = cells[static_cast<size_t>(r) * bw + c];
            if (std::isnan(v) || v == noData) continue;
            c0 = std::min(c0, c), c1 = std::max(c1, c), r0 = std::min(r0, r), r1 = std::max(r1, r);
        }
    if (c1 < 0) return std::nullopt;
    const double sx = double(width) / bw, sy = double(height) / bh;
    const int grow = bw < width || bh < height ? 1 : 0;
    return PixelBox{std::max(0.0, (c0 - grow) * sx), std::max(0.0, (r0 - grow) * sy),
                    std::min(double(width), (c1 + 1 + grow) * sx), std::min(double(height), (r1 + 1 + grow) * sy)};
}

bool hasWindow(const scene::NetSpec& net) { return net.extentM || net.extentLonLat; }

// The box of the cells' centres: a net at the raster's own spacing then lies
// on them, and bilinear resampling has data at every node, the outermost
// ring included (on the cells' outer edges it has none, and a raster with no
// nodata would get a masked border).
PixelBox cellCentres(const PixelBox& cells) {
    const double insetX = cells.x1 - cells.x0 >= 2 ? 0.5 : 0, insetY = cells.y1 - cells.y0 >= 2 ? 0.5 : 0;
    return {cells.x0 + insetX, cells.y0 + insetY, cells.x1 - insetX, cells.y1 - insetY};
}

constexpr int kEdgePoints = 64;

// The footprint: points along the edges of `box`, in WGS84.
std::vector<GeoSample> footprintEdge(const RasterPlace& place, const PixelBox& box) {
    std::vector<GeoSample> edge;
    auto addPixel = [&](double px, double py) {
        double lon = 0, lat = 0;
        if (place.toLonLat(px, py, lon, lat) && std::fabs(lat) <= 90) edge.push_back({lon, lat, 0, {}});
    };
    const double boxW = box.x1 - box.x0, boxH = box.y1 - box.y0;
    for (int i = 0; i <= kEdgePoints; ++i) {
        const double f = static_cast<double>(i) / kEdgePoints;
        addPixel(box.x0 + f * boxW, box.y0), addPixel(box.x0 + f * boxW, box.y1);
        addPixel(box.x0, box.y0 + f * boxH), addPixel(box.x1, box.y0 + f * boxH);
    }
    return edge;
}

std::optional<Vec3> framed(const RasterPlace& place, const Frame& frame, double px, double py) {
    GeoPoint g;
    if (!place.toLonLat(px, py, g.lonDeg, g.latDeg)) return std::nullopt;
    return forward(frame, g);
}

// The largest axis-aligned box inside the footprint: the west edge's
// easternmost point, the east edge's westernmost, and so on. `outside`
// counts the edge's points that do not reach the frame.
struct InnerBox {
    double west = -1e300, east = 1e300, south = -1e300, north = 1e300;
    int outside = 0;
};
InnerBox innerBox(const RasterPlace& place, const PixelBox& box, const Frame& frame) {
    InnerBox in;
    // Which pixel edge is which: rows usually run south (negative pixel height), but may run north.
    const auto& geo = place.geo;
    const double westPx = geo[1] > 0 ? box.x0 : box.x1, eastPx = geo[1] > 0 ? box.x1 : box.x0;
    const double northPx = geo[5] < 0 ? box.y0 : box.y1, southPx = geo[5] < 0 ? box.y1 : box.y0;
    const double boxW = box.x1 - box.x0, boxH = box.y1 - box.y0;
    for (int i = 0; i <= kEdgePoints; ++i) {
        const double f = static_cast<double>(i) / kEdgePoints;
        const auto w = framed(place, frame, westPx, box.y0 + f * boxH),
                   e = framed(place, frame, eastPx, box.y0 + f * boxH);
        const auto s = framed(place, frame, box.x0 + f * boxW, southPx),
                   n = framed(place, frame, box.x0 + f * boxW, northPx);
        in.outside += !w + !e + !s + !n;
        if (w) in.west = std::max(in.west, w->x);
        if (e) in.east = std::min(in.east, e->x);
        if (s) in.south = std::max(in.south, s->y);
        if (n) in.north = std::min(in.north, n->y);
    }
    return in;
}

void reportTooWide(const std::vector<GeoSample>& edge, const Frame& frame, const SourceLoc& fileLoc,
                   Diagnostics& diags) {
    double lonMin = 180, lonMax = -180, latMin = 90, latMax = -90;
    for (const auto& g : edge)
        lonMin = std::min(lonMin, g.lonDeg), lonMax = std::max(lonMax, g.lonDeg),
        latMin = std::min(latMin, g.latDeg), latMax = std::max(latMax, g.latDeg);
    diags.error(fileLoc, fmt::format("the raster spans lon {:.2f}..{:.2f}, lat {:.2f}..{:.2f}, more than {} "
                                     "can hold: choose a window of it with net.extent_m, or "
                                     "frame.kind = \"local\"",
                                     lonMin, lonMax, latMin, latMax, frame.describe()));
}

// The raster's cell on the ground (metres), at the centre of `box` or of the
// scene's window; 0 when it cannot be carried to the frame.
double groundCell(const RasterPlace& place, const PixelBox& box, const Frame& frame, const scene::NetSpec& net) {
    double px = 0.5 * (box.x0 + box.x1), py = 0.5 * (box.y0 + box.y1);
    // The window's centre, where it can be carried to the raster's cells (else the box's).
    std::optional<GeoPoint> centre;
    if (const auto& w = net.extentLonLat)
        centre = GeoPoint{0.5 * (w->west + w->east), 0.5 * (w->south + w->north), 0};
    else if (const auto& e = net.extentM)
        centre = reverse(frame, {0.5 * (e->west + e->east), 0.5 * (e->south + e->north), 0});
    if (centre) place.toPixel(centre->lonDeg, centre->latDeg, px, py);
    const auto c0 = framed(place, frame, px, py), c1 = framed(place, frame, px + 1, py),
               c2 = framed(place, frame, px, py + 1);
    if (c0 && c1 && c2) return std::min(length(*c1 - *c0), length(*c2 - *c0));
    return 0;
}

// How far the raster's CRS is from true scale over `box`: the largest
// |k - 1| of a cell's step east and north, on the ground (WGS84 geodesics)
// against the CRS, at the box's corners and centre; 1 when PROJ cannot say.
double scaleError(const RasterPlace& place, const PixelBox& box) {
    const double xs[] = {box.x0, 0.5 * (box.x0 + box.x1), box.x1}, ys[] = {box.y0, 0.5 * (box.y0 + box.y1), box.y1};
    const auto& geodesic = GeographicLib::Geodesic::WGS84();
    auto stepScale = [&](double px, double py, double dpx, double dpy) {
        double lon0, lat0, lon1, lat1, metres;
        if (!place.toLonLat(px, py, lon0, lat0) || !place.toLonLat(px + dpx, py + dpy, lon1, lat1)) return 2.0;
        geodesic.Inverse(lat0, lon0, lat1, lon1, metres);
        return metres / std::hypot(dpx * place.geo[1], dpy * place.geo[5]);
    };
    double worst = 0;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            if ((i == 1) == (j == 1))  // the corners and the centre
                worst = std::max({worst, std::fabs(stepScale(xs[i], ys[j], 1, 0) - 1),
                                  std::fabs(stepScale(xs[i], ys[j], 0, 1) - 1)});
    return std::min(worst, 1.0);
}

// The raster's own CRS for the frame: when the scene asks for it (an error
// when the CRS cannot be one), or, when `byDefault` and the scene names no
// frame, when the CRS is projected in metres and within kOwnCrsScaleError of
// true scale over the box (a national grid or UTM, not Web Mercator away from
// the equator). Nullopt: another frame.
struct OwnCrs {
    std::optional<Frame> frame;
    bool failed = false;
};
OwnCrs ownCrsFrame(const RasterPlace& place, const PixelBox& box, const scene::FrameSpec& spec, bool byDefault,
                   Diagnostics& diags) {
    OGRSpatialReferenceH srs = place.crs.srs.get();
    if (spec.kind == scene::FrameKind::Raster) {
        if (Frame own = projectedInMetres(srs) ? crsFrame(srs) : Frame{}; !own.crsWkt.empty()) {
            if (const double off = scaleError(place, box); off > kOwnCrsScaleError)
                diags.warning(spec.locs.at("frame.kind"),
                              fmt::format("{} is {:.1f} % off true scale over the data: lengths, the scale bar and "
                                          "the slopes are off by as much; \"utm\" is true to scale",
                                          own.crsName, 100 * off));
            return {std::move(own)};
        }
        diags.error(spec.locs.at("frame.kind"),
                    fmt::format("frame.kind = \"raster\" needs a raster in a projected CRS in metres, and {} is "
                                "not one: use \"utm\" or \"local\"",
                                crsNameOf(srs, "the raster's CRS")));
        return {std::nullopt, true};
    }
    const bool frameNamed = spec.locs.has("frame.kind") || spec.locs.has("frame.zone");
    if (!byDefault || frameNamed || !projectedInMetres(srs) || scaleError(place, box) > kOwnCrsScaleError) return {};
    Frame own = crsFrame(srs);
    if (own.crsWkt.empty()) return {};  // GDAL cannot write it as WKT2: PROJ could not carry it back
    return {std::move(own)};
}

// The edges of a box of cell centres moved out to the nearest centres (a
// box from a sparse scan of a large raster falls between them), so that a
// net at the cells' own spacing lies on them; within the `count` cells.
std::array<double, 2> onCentres(double lo, double hi, int count) {
    if (hi - lo < 1) return {lo, hi};
    return {std::max(0.5, std::floor(lo - 0.5 + 1e-9) + 0.5), std::min(count - 0.5, std::ceil(hi - 0.5 - 1e-9) + 0.5)};
}

// The box of `cellBox`'s cells in the raster's own CRS, and its cell there.
NetExtent extentInOwnCrs(const RasterPlace& place, const PixelBox& cellBox, Frame frame) {
    const auto& g = place.geo;
    const auto [px0, px1] = onCentres(cellBox.x0, cellBox.x1, place.width);
    const auto [py0, py1] = onCentres(cellBox.y0, cellBox.y1, place.height);
    const double xa = g[0] + px0 * g[1], xb = g[0] + px1 * g[1];
    const double ya = g[3] + py0 * g[5], yb = g[3] + py1 * g[5];
    return {std::move(frame), FrameBox{std::min(xa, xb), std::min(ya, yb), std::max(xa, xb), std::max(ya, yb)},
            std::min(std::fabs(g[1]), std::fabs(g[5]))};
}

}  // namespace

bool defaultIsDataBox(const HeightBand& band, const RasterPlace& place, std::optional<PixelBox> footprint,
                      const scene::NetSpec& net) {
    return !footprint && !hasWindow(net) && dataBoxAffordable(band.band, place.cells());
}

PixelBox allCellCentres(const RasterPlace& place) {
    return cellCentres({0, 0, double(place.width), double(place.height)});
}

std::optional<PixelBox> centresWithData(GDALRasterBandH cells, double scaleX, double scaleY, double offsetX,
                                        double offsetY, const HeightBand& band, const SourceLoc& fileLoc,
                                        Diagnostics& diags) {
    const auto data = dataBox(cells, GDALGetRasterBandXSize(cells), GDALGetRasterBandYSize(cells), band.noData);
    if (!data) {
        diags.error(fileLoc, fmt::format("every cell of band {} is nodata ({}): check the band and the "
                                         "raster's nodata value",
                                         band.number, band.hasNoData ? formatShortest(band.declaredNoData) : "NaN"));
        return std::nullopt;
    }
    return cellCentres({offsetX + data->x0 / scaleX, offsetY + data->y0 / scaleY, offsetX + data->x1 / scaleX,
                        offsetY + data->y1 / scaleY});
}

std::optional<PixelBox> defaultPixelBox(const HeightBand& band, const RasterPlace& place,
                                        std::optional<PixelBox> footprint, const scene::NetSpec& net,
                                        const SourceLoc& fileLoc, Diagnostics& diags) {
    if (footprint) return footprint;
    if (!defaultIsDataBox(band, place, footprint, net)) return allCellCentres(place);
    return centresWithData(band.band, 1, 1, 0, 0, band, fileLoc, diags);
}

std::optional<NetExtent> netExtent(const RasterPlace& place, const PixelBox& box, const scene::FrameSpec& frameSpec,
                                   const scene::NetSpec& net, bool ownCrsByDefault, const SourceLoc& fileLoc,
                                   Diagnostics& diags) {
    auto own = ownCrsFrame(place, box, frameSpec, ownCrsByDefault, diags);
    if (own.failed) return std::nullopt;
    if (own.frame) return extentInOwnCrs(place, box, std::move(*own.frame));
    std::vector<GeoSample> edge = footprintEdge(place, box);
    if (edge.size() < 4) {
        diags.error(fileLoc, "the raster's corners cannot be carried to latitude and longitude: check its CRS");
        return std::nullopt;
    }
    if (net.extentLonLat) {  // the frame of the window, not of the whole raster
        const auto& w = *net.extentLonLat;
        edge = {{w.west, w.south, 0, {}}, {w.east, w.south, 0, {}}, {w.west, w.north, 0, {}}, {w.east, w.north, 0, {}}};
    }
    auto frame = chooseFrame(frameSpec, edge, diags);
    if (!frame) return std::nullopt;
    InnerBox in = innerBox(place, box, *frame);
    if (in.outside > 0 && !hasWindow(net) && !frameSpec.locs.has("frame.kind")) {
        // More than a UTM zone holds, and the scene chose no frame: the tangent plane holds any extent.
        scene::FrameSpec local = frameSpec;
        local.kind = scene::FrameKind::Local;
        frame = chooseFrame(local, edge, diags);
        if (!frame) return std::nullopt;
        in = innerBox(place, box, *frame);
    }
    if (in.outside > 0 && !hasWindow(net)) {
        reportTooWide(edge, *frame, fileLoc, diags);
        return std::nullopt;
    }
    const double cell = groundCell(place, box, *frame, net);
    if (hasWindow(net)) in.west = in.south = 0, in.east = in.north = 1;
    if (!(in.east > in.west && in.north > in.south) || !(cell > 0)) {
        diags.error(fileLoc, fmt::format("the raster's footprint cannot be laid out in {}: check its CRS",
                                         frame->describe()));
        return std::nullopt;
    }
    return NetExtent{*frame, FrameBox{in.west, in.south, in.east, in.north}, cell};
}

}  // namespace relief::geo
