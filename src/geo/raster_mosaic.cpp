#include "geo/raster_mosaic.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <memory>
#include <string>
#include <string_view>

#include <cpl_conv.h>
#include <cpl_error.h>
#include <cpl_string.h>
#include <fmt/format.h>
#include <gdal_utils.h>

#include "core/text_escape.h"
#include "geo/crs_frame.h"
#include "geo/raster.h"

namespace relief::geo {

namespace fs = std::filesystem;

namespace {

// GDAL's files beside a raster, which GDAL may read as rasters of their own:
// overviews (.ovr, and Erdas's .aux and .rrd), masks, PAM metadata; in any case.
bool sideFile(const fs::path& file) {
    const std::string name = asciiLower(file.filename().string());
    if (name.empty() || name.front() == '.') return true;
    for (std::string_view end : {".ovr", ".msk", ".aux.xml", ".aux", ".rrd"})
        if (name.size() > end.size() && name.compare(name.size() - end.size(), end.size(), end) == 0) return true;
    return false;
}

// The tile's CRS, or null when it has none.
Srs crsOf(GDALDatasetH ds) {
    const char* wkt = GDALGetProjectionRef(ds);
    if (!wkt || !*wkt) return Srs();
    return Srs(OSRNewSpatialReference(wkt));
}

// The tile's box in its CRS: xmin, ymin, xmax, ymax.
std::array<double, 4> boxOf(GDALDatasetH ds) {
    double g[6] = {0, 1, 0, 0, 0, 1};
    GDALGetGeoTransform(ds, g);
    const double w = GDALGetRasterXSize(ds), h = GDALGetRasterYSize(ds);
    const double x0 = g[0], x1 = g[0] + w * g[1] + h * g[2], y0 = g[3], y1 = g[3] + w * g[4] + h * g[5];
    return {std::min(x0, x1), std::min(y0, y1), std::max(x0, x1), std::max(y0, y1)};
}

// The tiles as opened one at a time: the first (its band and metadata stand
// for the mosaic's) and every tile's box in the CRS they share.
struct OpenedTiles {
    Dataset first;
    std::vector<std::array<double, 4>> boxes;
};

// Opens every tile, one at a time (a folder of thousands must not hold a
// file open each: 1024 is a common limit), and checks that they share one
// CRS; the first problem ends it.
bool openTiles(const std::vector<fs::path>& tiles, const SourceLoc& at, Diagnostics& diags, OpenedTiles& out) {
    Srs first;
    std::map<fs::path, std::unique_ptr<FolderNames>> folders;  // the tiles' folders, each listed once
    for (const fs::path& tile : tiles) {
        auto& names = folders[tile.parent_path()];
        if (!names) names = std::make_unique<FolderNames>(tile.has_parent_path() ? tile.parent_path() : ".");
        std::string problem;
        Dataset ds = openRaster(tile, problem, names.get());
        if (!ds) {
            diags.error(at, fmt::format("samples.path: the tile {} {}: each tile must be a raster DEM GDAL reads",
                                        tile.filename().string(),
                                        problem.empty() ? std::string("is not a raster GDAL reads")
                                                        : "is refused: " + problem));
            return false;
        }
        Srs srs = crsOf(ds.get());
        if (out.boxes.empty()) {
            first = std::move(srs);
        } else if (!first != !srs || (first && !OSRIsSame(first.get(), srs.get()))) {
            diags.error(at, fmt::format("samples.path: the tiles {} ({}) and {} ({}) are in different CRSs: "
                                        "reproject one into the other's (gdalwarp -t_srs) so that all are in one",
                                        tiles.front().filename().string(), crsNameOf(first.get(), "no CRS"),
                                        tile.filename().string(), crsNameOf(srs.get(), "no CRS")));
            return false;
        }
        out.boxes.push_back(boxOf(ds.get()));
        if (!out.first) out.first = std::move(ds);
    }
    return true;
}

// The share of the tiles' bounding box they cover (overlaps counted once each: an upper bound).
double coverage(const std::vector<std::array<double, 4>>& boxes) {
    double area = 0, xmin = 1e300, ymin = 1e300, xmax = -1e300, ymax = -1e300;
    for (const auto& b : boxes) {
        area += (b[2] - b[0]) * (b[3] - b[1]);
        xmin = std::min(xmin, b[0]), ymin = std::min(ymin, b[1]), xmax = std::max(xmax, b[2]),
        ymax = std::max(ymax, b[3]);
    }
    return area / std::max((xmax - xmin) * (ymax - ymin), 1e-300);
}

}  // namespace

std::vector<fs::path> rasterTilesIn(const fs::path& folder, std::string& problem) {
    std::error_code ec;
    if (fs::directory_iterator(folder, ec); ec) {
        problem = fmt::format("the folder cannot be read ({})", ec.message());
        return {};
    }
    const FolderNames names(folder);
    if (names.sorted().size() > 8 * kMaxTiles) {  // a folder of everything: no scan of all of it
        problem = fmt::format("the folder holds more than the {} tiles a scene may mosaic", kMaxTiles);
        return {};
    }
    std::vector<fs::path> tiles;
    size_t files = 0;
    for (const std::string& name : names.sorted()) {  // in name order
        const fs::path file = folder / name;
        if (sideFile(file) || !fs::is_regular_file(file, ec)) continue;
        if (++files > 4 * kMaxTiles) break;  // a folder of everything: no scan of all of it
        if (isRasterDem(file, &names)) tiles.push_back(file);
    }
    if (tiles.size() > kMaxTiles || files > 4 * kMaxTiles) {
        problem = fmt::format("the folder holds more than the {} tiles a scene may mosaic", kMaxTiles);
        return {};
    }
    if (tiles.empty()) problem = "the folder holds no raster GDAL reads";
    return tiles;
}

Dataset mosaicOf(const std::vector<fs::path>& tiles, const SourceLoc& at, Diagnostics& diags) {
    OpenedTiles opened;
    if (!openTiles(tiles, at, diags, opened)) return Dataset();
    if (const double share = coverage(opened.boxes); share < 0.999)
        diags.warning(at, fmt::format("samples.path: the {} tiles cover {:.1f} % of their bounding box; the rest "
                                      "has no data (samples.nodata says what becomes of it): is a tile missing?",
                                      tiles.size(), 100 * std::min(share, 1.0)));
    // By name (absolute, as openRaster opens them): the VRT opens its sources itself, for as long as it lives.
    CPLStringList names;
    for (const fs::path& tile : tiles) names.AddString(fs::absolute(tile).c_str());
    CPLStringList args;
    GDALRasterBandH band = GDALGetRasterBand(opened.first.get(), 1);
    int hasNoData = 0;
    GDALGetRasterNoDataValue(band, &hasNoData);
    const GDALDataType type = GDALGetRasterDataType(band);
    if (!hasNoData && (type == GDT_Float32 || type == GDT_Float64)) args.AddString("-vrtnodata").AddString("nan");
    GDALBuildVRTOptions* options = GDALBuildVRTOptionsNew(args.List(), nullptr);
    int usageError = 0;
    CPLPushErrorHandler(CPLQuietErrorHandler);
    Dataset vrt(GDALBuildVRT("", names.size(), nullptr, names.List(), options, &usageError));
    CPLPopErrorHandler();
    GDALBuildVRTOptionsFree(options);
    if (!vrt) {
        diags.error(at, fmt::format("samples.path: GDAL could not mosaic the {} tiles: {}", tiles.size(),
                                    CPLGetLastErrorMsg()));
        return vrt;
    }
    // The first tile's metadata (its title, its credit) stand for the mosaic's.
    GDALSetMetadata(vrt.get(), GDALGetMetadata(opened.first.get(), nullptr), nullptr);
    return vrt;
}

}  // namespace relief::geo
