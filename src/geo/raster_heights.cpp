#include "geo/raster_heights.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <string>

#include <gdal_alg.h>
#include <fmt/format.h>

#include "core/number_format.h"
#include "core/text_escape.h"

namespace relief::geo {

namespace {

// Metres per unit: 1 for metres, 0.3048 for feet (1200/3937 for US survey
// feet); 0 when the unit is not a length relief knows.
double metresPerUnit(std::string unit) {
    unit = asciiLower(std::move(unit));
    if (unit == "m" || unit == "metre" || unit == "meter" || unit == "metres" || unit == "meters") return 1;
    if (unit == "ft" || unit == "foot" || unit == "feet" || unit == "international foot") return 0.3048;
    if (unit == "us-ft" || unit == "us survey foot" || unit == "ftus") return 1200.0 / 3937.0;
    return 0;
}

// Elevations = "any" still end at kAnyElevationLimitM.
struct ElevationRange {
    double lowest, highest;
    bool holds(double h) const { return h >= lowest && h <= highest; }
};
ElevationRange elevationRange(const scene::SamplesSpec& samples) {
    if (samples.earthElevations) return {scene::kLowestElevationM, scene::kHighestElevationM};
    return {-scene::kAnyElevationLimitM, scene::kAnyElevationLimitM};
}

// Where node `i` of the warped net (row 0 north) is; (0, 0) when it cannot be carried there.
GeoPoint nodePlace(const ControlNet& net, size_t i) {
    const size_t cols = static_cast<size_t>(net.cols());
    const size_t r = net.rows() - 1 - i / cols, c = i % cols;
    return reverse(net.frame, {net.x0 + c * net.dx, net.y0 + r * net.dy, 0}).value_or(GeoPoint{});
}

// The raster's cell (column and row from its north-west corner) behind a node
// at pixel (px, py) with height `h`: of the up to four cells the node mixes
// (bilinear), the first that holds a value beyond `range`, else the cell under it.
struct HeldCell {
    long x, y;
    double heightM;
};
HeldCell cellHolding(const RasterPlace& place, const HeightBand& band, double px, double py, double h,
                     double scale, const ElevationRange& range) {
    HeldCell held{static_cast<long>(std::floor(px)), static_cast<long>(std::floor(py)), h};
    for (int k = 0; k < 4; ++k) {
        const long tx = std::clamp(static_cast<long>(std::floor(px - 0.5)) + (k & 1), 0L, long{place.width - 1});
        const long ty = std::clamp(static_cast<long>(std::floor(py - 0.5)) + (k >> 1), 0L, long{place.height - 1});
        double v = 0;
        if (GDALRasterIO(band.band, GF_Read, static_cast<int>(tx), static_cast<int>(ty), 1, 1, &v, 1, 1, GDT_Float64,
                         0, 0) != CE_None || std::isnan(v) || v == band.noData)
            continue;
        if (!range.holds(scale * v)) return {tx, ty, scale * v};
    }
    return held;
}

void reportFirstEmpty(const ControlNet& net, size_t firstEmpty, size_t empty, size_t nodes,
                      const scene::SamplesSpec& samples, Diagnostics& diags) {
    const GeoPoint g = nodePlace(net, firstEmpty);
    diags.error(samples.locs.at("samples.nodata"),
                fmt::format("{} of the net's {} nodes have no data (nodata cells or outside the "
                            "raster), the first at lat {:.6f} lon {:.6f}; set nodata = \"mask\" or "
                            "\"fill\", or a smaller net.extent_m",
                            empty, nodes, g.latDeg, g.lonDeg));
}

// Masks the nodes without data; false when no cell of the net has data at all four corners.
bool maskEmptyNodes(const std::vector<double>& z, ControlNet& net) {
    const int rows = net.rows(), cols = net.cols();
    net.masked.assign(z.size(), 0);
    for (size_t i = 0; i < z.size(); ++i)
        if (!hasData(z[i])) net.masked[static_cast<size_t>(rows - 1 - i / cols) * cols + i % cols] = 1;
    for (int r = 0; r + 1 < rows; ++r)
        for (int c = 0; c + 1 < cols; ++c)
            if (!net.isMasked(r, c) && !net.isMasked(r, c + 1) && !net.isMasked(r + 1, c) &&
                !net.isMasked(r + 1, c + 1))
                return true;
    return false;
}

// Filled from the surrounding nodes (GDAL's inverse-distance search). To
// fill, far enough to reach every node; to mask, only as far as the
// refiner's stencils reach from a node with data (a few nodes), since
// nothing shows the masked nodes' heights.
bool fillEmptyNodes(std::vector<double>& z, GDALRasterBandH netBand, int rows, int cols, bool mask) {
    constexpr int kMaskFillReach = 8;
    if (GDALFillNodata(netBand, nullptr, mask ? kMaskFillReach : std::max(rows, cols), 0, 0, nullptr, nullptr,
                       nullptr) != CE_None ||
        GDALRasterIO(netBand, GF_Read, 0, 0, cols, rows, z.data(), cols, rows, GDT_Float64, 0, 0) != CE_None)
        return false;
    if (mask) {
        // Beyond the fill's reach: any finite height; the lowest with data.
        double lowest = 1e300;
        for (const double v : z)
            if (hasData(v)) lowest = std::min(lowest, v);
        for (double& v : z)
            if (!hasData(v)) v = lowest;
    }
    return true;
}

}  // namespace

double metresPerBandUnit(const HeightBand& band, const scene::SamplesSpec& samples, Diagnostics& diags) {
    const char* unitType = GDALGetRasterUnitType(band.band);
    const std::string unit = !samples.verticalUnit.empty() ? samples.verticalUnit : unitType ? unitType : "";
    const double scale = metresPerUnit(unit);
    if (scale != 0) return scale;
    diags.warning({samples.pathAsWritten, 0, 0},
                  fmt::format("the raster does not say its elevations are in metres (unit \"{}\"); "
                              "they are taken as metres: say so with vertical_unit = \"m\" "
                              "(or \"ft\", \"us-ft\") in [samples]",
                              unit));
    return 1;
}

// Elevations beyond the Earth's are a unit or a file error, named at the
// first such cell (the raster's column and row, counted from 0 at its
// north-west corner).
bool checkElevations(const std::vector<double>& z, double scale, const ControlNet& net, const RasterPlace& place,
                     const HeightBand& band, const scene::SamplesSpec& samples, Diagnostics& diags) {
    const ElevationRange range = elevationRange(samples);
    const auto beyond = std::find_if(z.begin(), z.end(), [&](double v) { return hasData(v) && !range.holds(scale * v); });
    if (beyond == z.end()) return true;
    double px = -1, py = -1;
    const GeoPoint g = nodePlace(net, static_cast<size_t>(beyond - z.begin()));
    place.toPixel(g.lonDeg, g.latDeg, px, py);
    const HeldCell cell = cellHolding(place, band, px, py, scale * *beyond, scale, range);
    const SourceLoc fileLoc{samples.pathAsWritten, 0, 0};
    if (samples.earthElevations)
        diags.error(fileLoc, fmt::format("the cell at column {}, row {} (near lat {:.6f} lon {:.6f}) holds {} m, "
                                         "beyond the Earth's ({} to {} m): check the band, its unit and its "
                                         "nodata value, or set elevations = \"any\" in [samples] for data that "
                                         "are not terrain in metres",
                                         cell.x, cell.y, g.latDeg, g.lonDeg, formatShortest(cell.heightM), range.lowest,
                                         range.highest));
    else
        diags.error(fileLoc,
                    fmt::format("the cell at column {}, row {} (near lat {:.6f} lon {:.6f}) holds {} "
                                "m, beyond the {:.0e} m any elevation may be (the surface's vertices "
                                "are single-precision): check the band, its unit and its nodata value",
                                cell.x, cell.y, g.latDeg, g.lonDeg, formatShortest(cell.heightM), range.highest));
    return false;
}

bool resolveNodata(std::vector<double>& z, GDALRasterBandH netBand, ControlNet& net,
                   const scene::SamplesSpec& samples, const scene::NetSpec& netSpec, Diagnostics& diags) {
    const SourceLoc fileLoc{samples.pathAsWritten, 0, 0};
    const size_t empty = static_cast<size_t>(std::count_if(z.begin(), z.end(), [](double v) { return !hasData(v); }));
    if (empty == 0) return true;
    if (empty == z.size()) {
        // The raster has data (dataBox), so the scene's window missed it.
        const char* key = netSpec.extentLonLat ? "net.extent_lonlat" : "net.extent_m";
        diags.error(netSpec.locs.has(key) ? netSpec.locs.at(key) : fileLoc,
                    fmt::format("no node of the net has data: every cell of {} inside {} is nodata; move the "
                                "window onto the raster's data",
                                samples.pathAsWritten, key));
        return false;
    }
    if (samples.nodata == scene::NodataPolicy::Error) {
        const auto first = std::find_if(z.begin(), z.end(), [](double v) { return !hasData(v); });
        reportFirstEmpty(net, static_cast<size_t>(first - z.begin()), empty, z.size(), samples, diags);
        return false;
    }
    const bool mask = samples.nodata == scene::NodataPolicy::Mask;
    if (mask && !maskEmptyNodes(z, net)) {
        diags.error(fileLoc, fmt::format("only {} of the net's {} nodes have data, and no cell of the net "
                                         "has data at all four corners: choose a finer net.spacing_m "
                                         "or a window with more data",
                                         z.size() - empty, z.size()));
        return false;
    }
    if (!fillEmptyNodes(z, netBand, net.rows(), net.cols(), mask)) {
        diags.error(fileLoc, "filling the nodes without data failed");
        return false;
    }
    if (!mask) net.filledNodata = empty;
    return true;
}

void setNodeHeights(ControlNet& net, const std::vector<double>& z, double scale) {
    const int rows = net.rows(), cols = net.cols();
    net.grid.points.resize(z.size());
    for (int r = 0; r < rows; ++r)
        for (int c = 0; c < cols; ++c) {
            const double h = scale * z[static_cast<size_t>(rows - 1 - r) * cols + c];
            Vec3 p{net.x0 + c * net.dx, net.y0 + r * net.dy, h};
            if (net.frame.kind == scene::FrameKind::Local) {
                // z above the tangent plane, as for samples: the height plus the Earth's curvature.
                if (const auto g = reverse(net.frame, {p.x, p.y, 0}))
                    if (const auto q = forward(net.frame, {g->lonDeg, g->latDeg, h})) p.z = q->z;
            }
            net.grid.at(r, c) = p;
        }
}

}  // namespace relief::geo
