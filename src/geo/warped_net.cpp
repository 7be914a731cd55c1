// A raster resampled onto the net, in phases that pass plain values: the
// raster checked and placed (raster_source.h), the cells and where the net
// goes (raster_footprint.h), the net laid out, the warp, the heights and the
// nodes without data (raster_heights.h).
#include "geo/warped_net.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include <cpl_conv.h>
#include <cpl_error.h>
#include <cpl_string.h>
#include <fmt/format.h>

#include "geo/cell_blocks.h"
#include "geo/crs_frame.h"
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
bool averagesWhenCoarser(const scene::SamplesSpec& samples, const scene::NetSpec& netSpec) {
    const bool netChosen = netSpec.spacingM <= 0 && !netSpec.locs.has("net.rows") && !netSpec.locs.has("net.cols");
    return netChosen && !samples.locs.has("samples.resample");
}
scene::Resample resampleFor(const scene::SamplesSpec& samples, const scene::NetSpec& netSpec, const ControlNet& net,
                            double cellM) {
    if (!averagesWhenCoarser(samples, netSpec) || std::max(net.dx, net.dy) < 1.5 * cellM) return samples.resample;
    return scene::Resample::Average;
}

// Whether nodata (and NaN) tell every cell without data: not a mask band or
// an alpha band, which GDAL's average honours and the block means do not read.
bool noDataTellsAll(const HeightBand& band) {
    const int flags = GDALGetMaskFlags(band.band);
    return (flags & (GMF_ALL_VALID | GMF_NODATA)) != 0 && (flags & (GMF_PER_DATASET | GMF_ALPHA)) == 0;
}

// An averaged net in the raster's own frame over no window of the scene's:
// onto the centres of blocks of whole cells (cell_blocks.h), k = the spacing
// in cells, rounded when relief chose the spacing for the still (up, when
// rounding down would pass the limits). The net as it was when no blocks
// fit.
void onBlocksWhenAveraged(ControlNet& net, const RasterPlace& place, const NetExtent& extent,
                          const scene::SamplesSpec& samples, const scene::NetSpec& netSpec, const NetBudget& budget) {
    if (net.frame.kind != scene::FrameKind::Raster || net.resample != scene::Resample::Average || netSpec.extentM ||
        netSpec.extentLonLat)
        return;
    const bool chosen = averagesWhenCoarser(samples, netSpec);
    const double cells = net.dx / extent.cellM;
    const double up = std::max(2.0, std::ceil(cells));
    for (const double k : {std::max(2.0, std::round(cells)), up}) {
        GeoGrid blocks = net;
        if (chosen) blocks.dx = blocks.dy = k * extent.cellM;
        if (!onBlockCentres(blocks, place, extent.box)) return;
        const bool more = double(blocks.rows()) * blocks.cols() > double(net.rows()) * net.cols();
        Diagnostics aside;
        if (more && budget.fits && !budget.fits(blocks, aside)) {
            if (chosen && k < up) continue;  // one block wider a side, fewer nodes
            return;
        }
        const int side = blockSideOf(blocks, place);
        if (blocks.dx != net.dx) net.spacingReason += fmt::format(": the mean of each block of {0} x {0} cells", side);
        static_cast<GeoGrid&>(net) = std::move(blocks);
        return;
    }
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
    net.spacingReason = netSpacingReason(netSpec, net, extent.cellM, budget);
    net.resample = resampleFor(samples, netSpec, net, extent.cellM);
    if (noDataTellsAll(heightBand(src, samples.band)))
        onBlocksWhenAveraged(net, place, extent, samples, netSpec, budget);
    net.raster = fmt::format("{} x {} cells, band {}, {}", place.width, place.height, samples.band,
                             crsNameOf(place.crs.srs.get(), "unnamed CRS"));
    return net;
}

// The heights warped onto the net, row 0 north (kNetNoData where there are
// none), and the net as the raster they were warped into, which the filling
// of the nodes without data works on.
struct WarpedHeights {
    Dataset netRaster;
    std::vector<double> z;
    bool copiedCells = false;  ///< every node a cell's centre: the cells read as they are
    int blockSide = 0;         ///< every node a block's centre: the means of blocks of this many cells a side, read
};

// The cells averaged in blocks of about `factor` by `factor` (GDAL spreads
// the raster's cells evenly over ceil(cells / factor) averages), by GDAL's
// RasterIO as gdal_translate -outsize -r average does, reading the file once
// and its overviews when it has them: a raster in memory, its cells `scale`
// of the source's.
// With `blocks`, the means of exact blocks of k x k cells instead (cell_blocks.h).
struct AveragedCells {
    Dataset raster;
    double scaleX = 1, scaleY = 1;
    int factor = 1;
    std::optional<CellBlocks> blocks;
    double offsetX() const { return blocks ? blocks->column0 : 0; }
    double offsetY() const { return blocks ? blocks->row0 : 0; }
};

// The means of `b`'s blocks, row 0 north, nodata cells left out (a block of
// them is band.noData), read a band of blocks at a time at the cells' own
// size: RasterIO's average would read the file's overviews when it has them,
// whose cells are not these blocks (gdaladdo's are the nearest cell by default).
template <class Cell>
bool readBlockMeansAs(GDALDataType type, const HeightBand& band, const CellBlocks& b, double* means) {
    // Windows of whole blocks of at most 2^19 cells (2 to 4 MB), one buffer read into again and again:
    // fresh pages cost more than the sums here.
    constexpr size_t kCellsPerRead = size_t{1} << 19;
    const int k = b.k;
    const size_t blockCells = static_cast<size_t>(k) * k;
    const int across = static_cast<int>(std::clamp<size_t>(kCellsPerRead / blockCells, 1, b.columns));
    const int down = static_cast<int>(std::clamp<size_t>(kCellsPerRead / (blockCells * across), 1, b.rows));
    std::vector<Cell> cells;
    std::vector<double> sum(across);
    std::vector<int> count(across);
    for (int i0 = 0; i0 < b.rows; i0 += down)
        for (int j0 = 0; j0 < b.columns; j0 += across) {
            const int n = std::min(down, b.rows - i0), m = std::min(across, b.columns - j0), width = m * k;
            cells.resize(static_cast<size_t>(width) * n * k);
            if (GDALRasterIO(band.band, GF_Read, b.column0 + j0 * k, b.row0 + i0 * k, width, n * k, cells.data(), width,
                             n * k, type, 0, 0) != CE_None)
                return false;
            for (int i = 0; i < n; ++i) {
                std::fill(sum.begin(), sum.end(), 0.0);
                std::fill(count.begin(), count.end(), 0);
                for (int r = 0; r < k; ++r) {
                    const Cell* row = cells.data() + (static_cast<size_t>(i) * k + r) * width;
                    for (int j = 0; j < m; ++j, row += k)
                        for (int c = 0; c < k; ++c) {
                            const double v = row[c];
                            const bool data = !std::isnan(v) && v != band.noData;
                            sum[j] += data ? v : 0.0;
                            count[j] += data;
                        }
                }
                double* out = means + static_cast<size_t>(i0 + i) * b.columns + j0;
                for (int j = 0; j < m; ++j) out[j] = count[j] ? sum[j] / count[j] : band.noData;
            }
        }
    return true;
}
bool readBlockMeans(const HeightBand& band, const CellBlocks& b, double* means) {
    switch (GDALGetRasterDataType(band.band)) {
        case GDT_Byte:
        case GDT_Int16:
        case GDT_UInt16:
        case GDT_Float32:  // cells a float holds exactly: half the bytes GDAL copies
            return readBlockMeansAs<float>(GDT_Float32, band, b, means);
        default:
            return readBlockMeansAs<double>(GDT_Float64, band, b, means);
    }
}

std::optional<AveragedCells> averagedCells(const HeightBand& band, const RasterPlace& place, int factor,
                                           bool inBlocks = false) {
    std::optional<CellBlocks> blocks;
    if (inBlocks) blocks = cellBlocks(place, factor);
    const int w = blocks ? blocks->columns : (place.width + factor - 1) / factor;
    const int h = blocks ? blocks->rows : (place.height + factor - 1) / factor;
    const int readW = blocks ? w * factor : place.width, readH = blocks ? h * factor : place.height;
    AveragedCells out{memRaster(w, h, 1, GDT_Float64), double(w) / readW, double(h) / readH, factor, blocks};
    if (!out.raster) return std::nullopt;
    // Into the memory raster's own cells (w x h, rows in order), not a copy: a
    // copy's first touch of fresh pages costs as much as the means.
    auto* cells = static_cast<double*>(GDALGetInternalHandle(out.raster.get(), "MEMORY1"));
    if (!cells) return std::nullopt;
    if (blocks) {
        if (!readBlockMeans(band, *blocks, cells)) return std::nullopt;
    } else {
        GDALRasterIOExtraArg arg;
        INIT_RASTERIO_EXTRA_ARG(arg);
        arg.eResampleAlg = GRIORA_Average;
        if (GDALRasterIOEx(band.band, GF_Read, 0, 0, readW, readH, cells, w, h, GDT_Float64, 0, 0, &arg) != CE_None)
            return std::nullopt;
    }
    GDALSetRasterNoDataValue(GDALGetRasterBand(out.raster.get(), 1), band.noData);
    return out;
}

// The heights of nodes on the cells' centres (of the raster, or of its
// blocks' means): the cells themselves, read as gdal_translate copies them (a
// warp would interpolate at the centres, to the same values at many times the
// cost), nodata cells marked kNetNoData.
bool readCellsOntoNet(const HeightBand& band, const BlockWindow& window, WarpedHeights& out, int rows, int cols) {
    out.z.resize(static_cast<size_t>(rows) * cols);
    if (GDALRasterIO(band.band, GF_Read, window.column, window.row, cols, rows, out.z.data(), cols, rows, GDT_Float64,
                     0, 0) != CE_None)
        return false;
    size_t empty = 0;
    for (double& v : out.z)
        if (std::isnan(v) || v == band.noData) v = kNetNoData, ++empty;
    // The net as a raster only serves the filling of nodes without data.
    return empty == 0 || GDALRasterIO(GDALGetRasterBand(out.netRaster.get(), 1), GF_Write, 0, 0, cols, rows,
                                      out.z.data(), cols, rows, GDT_Float64, 0, 0) == CE_None;
}

// What the net's heights are read from when no warp is needed: the raster's
// cells, or the blocks' means, under nodes on their centres.
struct ReadWindow {
    HeightBand band;
    BlockWindow window;
};
std::optional<ReadWindow> readWithoutWarp(const HeightBand& band, const RasterPlace& place, const ControlNet& net,
                                          const NetToRaster& chain, const AveragedCells* averaged) {
    if (!chain.inRasterCrs) return std::nullopt;
    if (!averaged) {
        const auto window = nodesOnBlockCentres(net, place, cellBlocks(place, 1));
        return window ? std::optional<ReadWindow>({band, *window}) : std::nullopt;
    }
    if (!averaged->blocks) return std::nullopt;
    const auto window = nodesOnBlockCentres(net, place, *averaged->blocks);
    if (!window) return std::nullopt;
    HeightBand means = band;
    means.band = GDALGetRasterBand(averaged->raster.get(), 1);
    return ReadWindow{means, *window};
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
    NetToRaster chain = netToRaster(net, place);
    if (const auto read = readWithoutWarp(band, place, net, chain, averaged)) {
        if (readCellsOntoNet(read->band, read->window, out, rows, cols)) {
            out.copiedCells = !averaged;
            out.blockSide = averaged ? averaged->factor : 0;
            if (progress) progress(1.0);
            return out;
        }
        diags.error(fileLoc, fmt::format("GDAL could not read the raster's cells: {}", CPLGetLastErrorMsg()));
        return std::nullopt;
    }
    if (averaged && averaged->blocks) {  // not the net's blocks: warp the cells themselves, as the net says
        averaged = nullptr;
        resample = net.resample;
    }
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

// The net over the footprint of `box`: where it goes, then laid out.
struct PlacedNet {
    NetExtent extent;
    ControlNet net;
    std::optional<AveragedCells> averaged;  ///< the cells averaged first, if they are
};
std::optional<PlacedNet> placedNet(const Dataset& src, const RasterPlace& place, const PixelBox& box,
                                   const scene::SamplesSpec& samples, const scene::FrameSpec& frameSpec,
                                   const scene::NetSpec& netSpec, bool ownCrsByDefault, const SourceLoc& fileLoc,
                                   Diagnostics& diags, const NetBudget& budget) {
    auto extent = netExtent(place, box, frameSpec, netSpec, ownCrsByDefault, fileLoc, diags);
    if (!extent) return std::nullopt;
    auto net = laidOutNet(src.get(), place, *extent, samples, netSpec, diags, budget);
    if (!net || (budget.beforeReading && !budget.beforeReading(*net))) return std::nullopt;
    return PlacedNet{*extent, std::move(*net), std::nullopt};
}

// How many cells a side the cells are averaged by first: a net relief made
// coarser than them is warped bilinearly from their averages, which costs
// reading the file once, where the warper's own average weighs every cell of
// every node's footprint through the projections (2.7x gdal_translate's time
// on 53 M cells); a net on the centres of blocks of cells (cell_blocks.h) is
// their means, read. Factor 1: not averaged.
struct Averaging {
    int factor = 1;
    bool blocks = false;
};
Averaging averagingFor(const PlacedNet& placed, const RasterPlace& place, const HeightBand& band,
                       const scene::SamplesSpec& samples) {
    const ControlNet& net = placed.net;
    if (const int k = blockSideOf(net, place); k >= 2 && net.resample == scene::Resample::Average &&
                                               noDataTellsAll(band) &&
                                               nodesOnBlockCentres(net, place, cellBlocks(place, k)))
        return {k, true};
    const int factor = static_cast<int>(std::min(net.dx, net.dy) / placed.extent.cellM);
    return {net.resample != samples.resample && factor >= 2 ? factor : 1, false};
}

// The averages the net is warped or read from: those at hand when they are the ones it needs, else new ones, or none.
bool keepOrAverage(PlacedNet& placed, const HeightBand& band, const RasterPlace& place,
                   const scene::SamplesSpec& samples, const SourceLoc& fileLoc, Diagnostics& diags) {
    const Averaging a = averagingFor(placed, place, band, samples);
    if (placed.averaged && placed.averaged->factor == a.factor && placed.averaged->blocks.has_value() == a.blocks)
        return true;
    placed.averaged.reset();
    if (a.factor < 2) return true;
    placed.averaged = averagedCells(band, place, a.factor, a.blocks);
    if (!placed.averaged)
        diags.error(fileLoc, fmt::format("GDAL could not average the raster's cells to the net's spacing: {}",
                                         CPLGetLastErrorMsg()));
    return placed.averaged.has_value();
}

// The box of the cells with data found among their averages, and those
// averages, when the net over every cell is one relief made coarser than
// them (asked of the limits, but with its own errors put aside: the net over
// the data is what counts). Nullopt when it is not; an empty box after an
// error.
struct AveragedData {
    std::optional<PixelBox> box;
    AveragedCells averaged;
};
std::optional<AveragedData> dataAmongAverages(const std::optional<PlacedNet>& overAll, const HeightBand& band,
                                              const RasterPlace& place, const scene::SamplesSpec& samples,
                                              const SourceLoc& fileLoc, Diagnostics& diags) {
    const Averaging a = overAll ? averagingFor(*overAll, place, band, samples) : Averaging{};
    if (a.factor < 2) return std::nullopt;
    auto averaged = averagedCells(band, place, a.factor, a.blocks);
    if (!averaged) return std::nullopt;  // the file read again below says why
    auto box = centresWithData(GDALGetRasterBand(averaged->raster.get(), 1), averaged->scaleX, averaged->scaleY,
                               averaged->offsetX(), averaged->offsetY(), band, fileLoc, diags);
    return AveragedData{box, std::move(*averaged)};
}

// The net over the cells with data by default, its cells averaged if they
// are to be. When their box would take a scan of the file and the net may
// be one relief makes coarser than the cells, the net is first laid over
// every cell: if those cells are then averaged, their box comes from the
// averages, and the file is read once when the data fill it (twice when the
// net over a smaller box is finer and needs finer averages).
std::optional<PlacedNet> netOverTheData(const Dataset& src, const RasterPlace& place, const HeightBand& band,
                                        std::optional<PixelBox> footprint, const scene::SamplesSpec& samples,
                                        const scene::FrameSpec& frameSpec, const scene::NetSpec& netSpec,
                                        const SourceLoc& fileLoc, Diagnostics& diags, const NetBudget& budget) {
    auto laidOver = [&](const PixelBox& box, Diagnostics& d) {
        // A lattice's CRS is relief's guess, not the data's own: its frame stays the scene's.
        return placedNet(src, place, box, samples, frameSpec, netSpec, !footprint, fileLoc, d, budget);
    };
    // A net spaced a whole number of cells and averaged (as relief init writes
    // the one chosen for the still) finds its box among the same block means.
    const bool chosenForStill = averagesWhenCoarser(samples, netSpec) && budget.stillWidthPx > 0;
    const bool averagedAsGiven = netSpec.spacingM > 0 && samples.resample == scene::Resample::Average;
    std::optional<AveragedData> data;
    if (defaultIsDataBox(band, place, footprint, netSpec) && (chosenForStill || averagedAsGiven)) {
        Diagnostics aside;
        data = dataAmongAverages(laidOver(allCellCentres(place), aside), band, place, samples, fileLoc, diags);
        if (data && !data->box) return std::nullopt;
    }
    const auto box = data ? data->box : defaultPixelBox(band, place, footprint, netSpec, fileLoc, diags);
    if (!box) return std::nullopt;
    auto placed = laidOver(*box, diags);
    if (!placed) return std::nullopt;
    if (data) placed->averaged = std::move(data->averaged);
    if (!keepOrAverage(*placed, band, place, samples, fileLoc, diags)) return std::nullopt;
    return placed;
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
    auto placed = netOverTheData(src, *place, band, footprint, samples, frameSpec, netSpec, fileLoc, diags, budget);
    if (!placed) return std::nullopt;
    ControlNet& net = placed->net;
    const AveragedCells* averaged = placed->averaged ? &*placed->averaged : nullptr;
    auto warped = warpHeights(src, *place, band, net, averaged ? scene::Resample::Bilinear : net.resample, diags,
                              progress, fileLoc, averaged);
    if (!warped) return std::nullopt;
    const int warnings = diags.warningCount();
    const double scale = metresPerBandUnit(band, samples, diags);
    net.metresPerUnit = scale;
    net.verticalUnitAssumed = diags.warningCount() > warnings;
    if (!checkElevations(warped->z, scale, net, *place, band, samples, diags) ||
        !resolveNodata(warped->z, GDALGetRasterBand(warped->netRaster.get(), 1), net, samples, netSpec, diags))
        return std::nullopt;
    setNodeHeights(net, warped->z, scale);
    net.copiedCells = warped->copiedCells;
    net.raster += warped->blockSide ? fmt::format(", the mean of each {0} x {0} cells", warped->blockSide)
                  : net.copiedCells ? std::string(", the cells as they are")
                                    : fmt::format(", {}", scene::nameOf(net.resample));
    return std::move(net);
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
