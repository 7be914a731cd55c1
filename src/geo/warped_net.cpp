// A raster resampled onto the net, in phases that pass plain values: the
// raster checked and placed (raster_source.h), the cells and where the net
// goes (raster_footprint.h), the net laid out, the warp, the heights and the
// nodes without data (raster_heights.h).
#include "geo/warped_net.h"

#include <algorithm>
#include <new>
#include <vector>

#include <cpl_conv.h>
#include <cpl_error.h>
#include <cpl_string.h>
#include <fmt/format.h>

#include "geo/raster.h"
#include "geo/raster_heights.h"
#include "geo/raster_mosaic.h"
#include "geo/raster_warp.h"
#include "scene/enum_names.h"

namespace relief::geo {

namespace {

// The scene's resampling; by default, onto a net relief made coarser than
// the cells (one for the still, not for every cell), the average of the cells
// each node stands for, as gdal_translate -r average makes an overview.
scene::Resample resampleFor(const scene::SamplesSpec& samples, const scene::NetSpec& netSpec, const ControlNet& net,
                            double cellM) {
    const bool netChosen = netSpec.spacingM <= 0 && !netSpec.locs.has("net.rows") && !netSpec.locs.has("net.cols");
    if (samples.locs.has("samples.resample") || !netChosen || std::max(net.dx, net.dy) < 1.5 * cellM)
        return samples.resample;
    return scene::Resample::Average;
}

// The net laid over the extent and described (what was read and how), without heights.
std::optional<ControlNet> laidOutNet(GDALDatasetH src, const RasterPlace& place, const NetExtent& extent,
                                     const scene::SamplesSpec& samples, const scene::NetSpec& netSpec,
                                     Diagnostics& diags, const NetBudget& budget) {
    ControlNet net;
    net.frame = extent.frame;
    net.sampleCount = static_cast<size_t>(place.width) * place.height;
    net.attribution = rasterCredit(src);
    if (!layoutNet(netSpec, extent.box, extent.cellM, net, diags, budget)) return std::nullopt;
    net.spacingReason = netSpacingReason(netSpec, net, extent.cellM, budget.stillWidthPx);
    net.resample = resampleFor(samples, netSpec, net, extent.cellM);
    const char* crsName = OSRGetName(place.crs.srs.get());
    net.raster = fmt::format("{} x {} cells, band {}, {}, {}", place.width, place.height, samples.band,
                             crsName ? crsName : "unnamed CRS", scene::nameOf(net.resample));
    return net;
}

// The heights warped onto the net, row 0 north (kNetNoData where there are
// none), and the net as the raster they were warped into, which the filling
// of the nodes without data works on.
struct WarpedHeights {
    Dataset netRaster;
    std::vector<double> z;
};

// The cells averaged `factor` by `factor` (the last row and column of
// blocks may be narrower), by GDAL's RasterIO as gdal_translate -outsize -r
// average does, reading the file once and its overviews when it has them: a
// raster in memory, its cells `scale` of the source's.
struct AveragedCells {
    Dataset raster;
    double scaleX = 1, scaleY = 1;
};
std::optional<AveragedCells> averagedCells(const HeightBand& band, const RasterPlace& place, int factor) {
    const int w = (place.width + factor - 1) / factor, h = (place.height + factor - 1) / factor;
    AveragedCells out{memRaster(w, h, 1, GDT_Float64), double(w) / place.width, double(h) / place.height};
    std::vector<double> cells;
    try {
        cells.resize(static_cast<size_t>(w) * h);
    } catch (const std::bad_alloc&) {
        return std::nullopt;
    }
    GDALRasterIOExtraArg arg;
    INIT_RASTERIO_EXTRA_ARG(arg);
    arg.eResampleAlg = GRIORA_Average;
    if (!out.raster || GDALRasterIOEx(band.band, GF_Read, 0, 0, place.width, place.height, cells.data(), w, h,
                                      GDT_Float64, 0, 0, &arg) != CE_None)
        return std::nullopt;
    GDALRasterBandH averaged = GDALGetRasterBand(out.raster.get(), 1);
    GDALSetRasterNoDataValue(averaged, band.noData);
    if (GDALRasterIO(averaged, GF_Write, 0, 0, w, h, cells.data(), w, h, GDT_Float64, 0, 0) != CE_None)
        return std::nullopt;
    return out;
}

std::optional<WarpedHeights> warpHeights(const Dataset& src, const RasterPlace& place, const HeightBand& band,
                                         const ControlNet& net, scene::Resample resample, Diagnostics& diags,
                                         const GridProgressFn& progress, const SourceLoc& fileLoc,
                                         const AveragedCells* averaged = nullptr) {
    const int rows = net.rows(), cols = net.cols();
    WarpedHeights out{memRaster(cols, rows, 1, GDT_Float64), {}};
    if (!out.netRaster) {
        diags.error(fileLoc, fmt::format("there is no memory for a net of {} x {} nodes: give net.spacing_m (a "
                                         "coarser net), or lower limits.max_memory_mb to what this machine has",
                                         rows, cols));
        return std::nullopt;
    }
    GDALRasterBandH netBand = GDALGetRasterBand(out.netRaster.get(), 1);
    GDALSetRasterNoDataValue(netBand, kNetNoData);
    GDALWarpOptions* wo = averaged ? warpOptions(averaged->raster.get(), out.netRaster.get(), {1})
                                   : warpOptions(src.get(), out.netRaster.get(), {band.number});
    wo->eWorkingDataType = GDT_Float64;
    wo->eResampleAlg = gdalResampling(resample);
    wo->padfSrcNoDataReal = static_cast<double*>(CPLMalloc(sizeof(double)));
    wo->padfSrcNoDataReal[0] = band.noData;
    wo->padfDstNoDataReal = static_cast<double*>(CPLMalloc(sizeof(double)));
    wo->padfDstNoDataReal[0] = kNetNoData;
    wo->papszWarpOptions = CSLSetNameValue(wo->papszWarpOptions, "INIT_DEST", "NO_DATA");
    // The exact chain costs two projections per net node; GDAL's approximating
    // transformer interpolates it linearly along each row of the net wherever
    // that stays within kMaxErrorPixels of it (checked at the row's ends and
    // middle, and recursively), as gdalwarp does by default with 0.125 raster
    // cells. Within 0.001 cells it is 8x faster on a 1000 x 1000 DEM
    // (0.07 s against 0.59 s) and changes no height by more than 0.7 mm there.
    constexpr double kMaxErrorCells = 0.001;
    NetToRaster chain = netToRaster(net, place);
    if (averaged) chain.scaleX = averaged->scaleX, chain.scaleY = averaged->scaleY;
    if (warpOntoNet(wo, chain, kMaxErrorCells, progress) != CE_None) {
        diags.error(fileLoc, fmt::format("GDAL could not resample the raster onto the net: {}",
                                         CPLGetLastErrorMsg()));
        return std::nullopt;
    }
    out.z.resize(static_cast<size_t>(rows) * cols);
    if (GDALRasterIO(netBand, GF_Read, 0, 0, cols, rows, out.z.data(), cols, rows, GDT_Float64, 0, 0) != CE_None) {
        diags.error(fileLoc, "reading the resampled net back failed");
        return std::nullopt;
    }
    return out;
}

}  // namespace

std::optional<ControlNet> warpedNet(const Dataset& src, const scene::SamplesSpec& samples,
                                    const scene::FrameSpec& frameSpec, const scene::NetSpec& netSpec,
                                    std::optional<PixelBox> footprint, Diagnostics& diags,
                                    const GridProgressFn& progress, const NetBudget& budget) {
    const SourceLoc fileLoc{samples.pathAsWritten, 0, 0};
    const auto place = placeOfDem(src.get(), samples, netSpec, budget, diags);
    if (!place) return std::nullopt;
    const HeightBand band = heightBand(src.get(), samples.band);
    const auto box = defaultPixelBox(band, *place, footprint, netSpec, fileLoc, diags);
    if (!box) return std::nullopt;
    const auto extent = netExtent(*place, *box, frameSpec, netSpec, fileLoc, diags);
    if (!extent) return std::nullopt;
    auto net = laidOutNet(src.get(), *place, *extent, samples, netSpec, diags, budget);
    if (!net) return std::nullopt;
    // A net relief made coarser than the cells: the cells averaged to about
    // the net's spacing first, then warped bilinearly, which costs reading
    // the file once where the warper's own average weighs every cell of
    // every node's footprint through the projections (2.7x gdal_translate's
    // time on 53 M cells).
    std::optional<AveragedCells> averaged;
    if (const int factor = static_cast<int>(std::min(net->dx, net->dy) / extent->cellM);
        net->resample != samples.resample && factor >= 2) {
        averaged = averagedCells(band, *place, factor);
        if (!averaged) {
            diags.error(fileLoc, fmt::format("GDAL could not average the raster's cells to the net's spacing: {}",
                                             CPLGetLastErrorMsg()));
            return std::nullopt;
        }
    }
    auto warped = warpHeights(src, *place, band, *net, averaged ? scene::Resample::Bilinear : net->resample, diags,
                              progress, fileLoc, averaged ? &*averaged : nullptr);
    if (!warped) return std::nullopt;
    const double scale = metresPerBandUnit(band, samples, diags);
    if (!checkElevations(warped->z, scale, *net, *place, band, samples, diags) ||
        !resolveNodata(warped->z, GDALGetRasterBand(warped->netRaster.get(), 1), *net, samples, netSpec, diags))
        return std::nullopt;
    setNodeHeights(*net, warped->z, scale);
    return net;
}

std::optional<ControlNet> rasterNet(const scene::SamplesSpec& samples, const scene::FrameSpec& frameSpec,
                                    const scene::NetSpec& netSpec, Diagnostics& diags,
                                    const GridProgressFn& progress, const NetBudget& budget) {
    if (!samples.tiles.empty()) {
        const Dataset mosaic = mosaicOf(samples.tiles, samples.locs.at("samples.path"), diags);
        if (!mosaic) return std::nullopt;
        return warpedNet(mosaic, samples, frameSpec, netSpec, std::nullopt, diags, progress, budget);
    }
    std::string problem;
    const Dataset src = openRaster(samples.path, problem);
    if (!src) {
        diags.error({samples.pathAsWritten, 0, 0},
                    problem.empty() ? std::string("GDAL cannot read this raster (a truncated or damaged file?)")
                                    : fmt::format("samples.path: relief does not read this raster: {} (what a scene's "
                                                  "raster may bring with it: docs/security.md)",
                                                  problem));
        return std::nullopt;
    }
    return warpedNet(src, samples, frameSpec, netSpec, std::nullopt, diags, progress, budget);
}

}  // namespace relief::geo
