// Scattered samples that are a raster in disguise (raster.h: SampleLattice):
// found in a CRS, and resampled as the raster they are.
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <cpl_conv.h>
#include <cpl_error.h>
#include <fmt/format.h>

#include "geo/gdal_crs.h"
#include "geo/gdal_setup.h"
#include "geo/raster.h"
#include "geo/raster_warp.h"
#include "geo/warped_net.h"

namespace relief::geo {

namespace {

// The values' clusters along one axis of a lattice: the positions, sorted,
// fall into groups a spacing apart, each no wider than kTolerance of it. 1 %:
// coordinates written as 32-bit floats (matplotlib's topobathy: up to 0.3 %
// of its 2' spacing) still make a lattice, and treating a node 1 % of a cell
// off as on it moves nothing a net can show.
// Returns the first group's centre, the spacing and the count; nullopt when
// the positions are not such groups, evenly spaced.
struct Axis {
    double origin = 0, spacing = 0;
    int count = 0;
};
constexpr double kTolerance = 0.01;
std::optional<Axis> latticeAxis(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    double widest = 0;
    for (size_t i = 1; i < v.size(); ++i) widest = std::max(widest, v[i] - v[i - 1]);
    if (!(widest > 0)) return std::nullopt;
    // In a lattice the widest gap is the spacing; inside a group the gaps are rounding.
    std::vector<double> centres;
    size_t start = 0;
    for (size_t i = 1; i <= v.size(); ++i) {
        if (i < v.size() && v[i] - v[i - 1] < 0.5 * widest) continue;
        if (v[i - 1] - v[start] > kTolerance * widest) return std::nullopt;
        centres.push_back(0.5 * (v[start] + v[i - 1]));
        start = i;
    }
    if (centres.size() < 2) return std::nullopt;
    const double spacing = (centres.back() - centres.front()) / static_cast<double>(centres.size() - 1);
    for (size_t i = 1; i < centres.size(); ++i)
        if (std::fabs(centres[i] - centres[i - 1] - spacing) > kTolerance * spacing) return std::nullopt;
    return Axis{centres.front(), spacing, static_cast<int>(centres.size())};
}

// The lattice as a raster in memory: pixel edges half a spacing outside the
// samples, row 0 north; null when GDAL cannot hold it.
Dataset latticeRaster(const SampleLattice& lattice) {
    Dataset mem = memRaster(lattice.cols, lattice.rows, 1, GDT_Float64);
    Srs srs(OSRNewSpatialReference(nullptr));
    char* wkt = nullptr;
    std::string problem;
    if (!mem || !crsFromText(srs.get(), lattice.crs, problem) || OSRExportToWkt(srs.get(), &wkt) != OGRERR_NONE) {
        CPLFree(wkt);
        return Dataset();
    }
    double geo[6] = {lattice.xWest - 0.5 * lattice.dx, lattice.dx, 0, lattice.yNorth + 0.5 * lattice.dy, 0, -lattice.dy};
    GDALSetGeoTransform(mem.get(), geo);
    GDALSetProjection(mem.get(), wkt);
    CPLFree(wkt);
    GDALRasterBandH band = GDALGetRasterBand(mem.get(), 1);
    GDALSetRasterUnitType(band, "m");  // the CSV's elev column is metres
    if (GDALRasterIO(band, GF_Write, 0, 0, lattice.cols, lattice.rows, const_cast<double*>(lattice.z.data()),
                     lattice.cols, lattice.rows, GDT_Float64, 0, 0) != CE_None)
        return Dataset();
    return mem;
}


}  // namespace

std::optional<SampleLattice> findLattice(const std::vector<GeoSample>& samples, const std::string& crs) {
    if (samples.size() < 4) return std::nullopt;
    Srs target(OSRNewSpatialReference(nullptr));
    if (std::string problem; !crsFromText(target.get(), crs, problem)) return std::nullopt;
    OSRSetAxisMappingStrategy(target.get(), OAMS_TRADITIONAL_GIS_ORDER);
    Transform toTarget = wgs84Transforms(target.get()).first;
    if (!toTarget) return std::nullopt;
    std::vector<double> x(samples.size()), y(samples.size());
    for (size_t i = 0; i < samples.size(); ++i) x[i] = samples[i].lonDeg, y[i] = samples[i].latDeg;
    std::vector<int> ok(samples.size());
    CPLPushErrorHandler(CPLQuietErrorHandler);
    const bool transformed = OCTTransformEx(toTarget.get(), static_cast<int>(samples.size()), x.data(), y.data(),
                                            nullptr, ok.data());
    CPLPopErrorHandler();
    if (!transformed || std::find(ok.begin(), ok.end(), 0) != ok.end()) return std::nullopt;
    const auto ax = latticeAxis(x), ay = latticeAxis(y);
    if (!ax || !ay || static_cast<size_t>(ax->count) * ay->count != samples.size()) return std::nullopt;
    SampleLattice lattice;
    lattice.crs = crs;
    lattice.cols = ax->count;
    lattice.rows = ay->count;
    lattice.xWest = ax->origin;
    lattice.yNorth = ay->origin + (ay->count - 1) * ay->spacing;
    lattice.dx = ax->spacing;
    lattice.dy = ay->spacing;
    lattice.z.assign(samples.size(), std::nan(""));
    for (size_t i = 0; i < samples.size(); ++i) {
        const long c = std::lround((x[i] - ax->origin) / ax->spacing);
        const long r = std::lround((lattice.yNorth - y[i]) / ay->spacing);
        double& cell = lattice.z[static_cast<size_t>(r) * lattice.cols + c];
        if (!std::isnan(cell)) return std::nullopt;  // two samples on one node: not a lattice
        cell = samples[i].elevM;
    }
    return lattice;
}

std::optional<ControlNet> latticeNet(const SampleLattice& lattice, const scene::SamplesSpec& samples,
                                     const scene::FrameSpec& frameSpec, const scene::NetSpec& netSpec,
                                     Diagnostics& diags, const GridProgressFn& progress, const NetBudget& budget) {
    setUpGdal();
    const Dataset mem = latticeRaster(lattice);
    if (!mem) {
        diags.error({samples.pathAsWritten, 0, 0}, "GDAL cannot hold the lattice of samples as a raster");
        return std::nullopt;
    }
    scene::SamplesSpec asRaster = samples;
    asRaster.band = 1;
    asRaster.crs.clear();  // the raster's own, just set
    // The default extent: the box of the samples (the cells' centres), as for scattered samples.
    const PixelBox centres{0.5, 0.5, lattice.cols - 0.5, lattice.rows - 0.5};
    auto net = warpedNet(mem, asRaster, frameSpec, netSpec, centres, diags, progress, budget);
    if (net)
        net->raster = fmt::format("lattice of {} x {} samples in {}, {:.7g} x {:.7g} apart, bilinear", lattice.cols,
                                  lattice.rows, lattice.crs, lattice.dx, lattice.dy);
    return net;
}

}  // namespace relief::geo
