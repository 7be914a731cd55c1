// An image draped on the surface (raster.h: imageOnGrid): checked, placed on
// the Earth, warped onto the grid's nodes and read back in the grid's order.
#include <tuple>
#include <vector>

#include <cpl_conv.h>
#include <cpl_error.h>
#include <cpl_string.h>
#include <fmt/format.h>

#include "geo/raster.h"
#include "geo/raster_source.h"
#include "geo/raster_warp.h"

namespace relief::geo {

namespace {

bool isPalette(GDALDatasetH src) {
    return GDALGetRasterColorInterpretation(GDALGetRasterBand(src, 1)) == GCI_PaletteIndex;
}

// Red, green and blue bands (and alpha), or one grey band (and alpha).
bool checkImageBands(GDALDatasetH src, const SourceLoc& fileLoc, Diagnostics& diags) {
    const int bands = GDALGetRasterCount(src);
    const bool grey = bands == 1 || bands == 2;
    if (bands >= 1 && (grey || bands >= 3) && !isPalette(src)) return true;
    diags.error(fileLoc, fmt::format("texture.image: {} band{}{}: a drape needs red, green and blue bands or one "
                                     "grey band (expand a palette image with gdal_translate -expand rgb)",
                                     bands, bands == 1 ? "" : "s",
                                     bands >= 1 && isPalette(src) ? " with a colour table" : ""));
    return false;
}

// The image's geotransform and its own CRS, carried to and from WGS84.
std::optional<RasterPlace> placeOfImage(GDALDatasetH src, const SourceLoc& fileLoc, Diagnostics& diags) {
    RasterPlace place;
    place.width = GDALGetRasterXSize(src), place.height = GDALGetRasterYSize(src);
    if (GDALGetGeoTransform(src, place.geo.data()) != CE_None ||
        !GDALInvGeoTransform(place.geo.data(), place.inverse.data())) {
        diags.error(fileLoc, "texture.image has no georeferencing (geotransform): give it one, e.g. with "
                             "gdal_translate -a_ullr and -a_srs");
        return std::nullopt;
    }
    place.crs.srs = Srs(OSRNewSpatialReference(nullptr));
    OSRSetAxisMappingStrategy(place.crs.srs.get(), OAMS_TRADITIONAL_GIS_ORDER);
    const char* wkt = GDALGetProjectionRef(src);
    if (!wkt || !*wkt || OSRImportFromWkt(place.crs.srs.get(), const_cast<char**>(&wkt)) != OGRERR_NONE) {
        diags.error(fileLoc, "texture.image has no CRS: give it one with gdal_translate -a_srs EPSG:...");
        return std::nullopt;
    }
    std::tie(place.crs.toRaster, place.crs.toWgs84) = wgs84Transforms(place.crs.srs.get());
    if (!place.crs.toRaster || !place.crs.toWgs84) {
        diags.error(fileLoc, "texture.image: its CRS cannot be carried to WGS84");
        return std::nullopt;
    }
    return place;
}

// The grid as an image of its own (pixel centres = nodes, row 0 north): three
// bands of colour and an alpha band the warper sets where it has data; null,
// after an error, when GDAL could not resample the image onto it.
Dataset warpedImage(GDALDatasetH src, const RasterPlace& place, const GeoGrid& grid, const SourceLoc& fileLoc,
                    Diagnostics& diags) {
    Dataset dst = memRaster(grid.cols(), grid.rows(), 4, GDT_Byte);
    const int bands = GDALGetRasterCount(src);
    const bool grey = bands == 1 || bands == 2;
    GDALWarpOptions* wo = warpOptions(src, dst.get(), grey ? std::vector<int>{1, 1, 1} : std::vector<int>{1, 2, 3});
    // The image's own alpha band, or its nodata value, says where it has data.
    const int alphaBand = bands == 2 ? 2 : bands >= 4 ? 4 : 0;
    if (alphaBand && GDALGetRasterColorInterpretation(GDALGetRasterBand(src, alphaBand)) == GCI_AlphaBand)
        wo->nSrcAlphaBand = alphaBand;
    int hasNoData = 0;
    const double noData = GDALGetRasterNoDataValue(GDALGetRasterBand(src, 1), &hasNoData);
    if (hasNoData && !wo->nSrcAlphaBand) {
        wo->padfSrcNoDataReal = static_cast<double*>(CPLMalloc(3 * sizeof(double)));
        for (int b = 0; b < 3; ++b) wo->padfSrcNoDataReal[b] = noData;
        wo->papszWarpOptions = CSLSetNameValue(wo->papszWarpOptions, "UNIFIED_SRC_NODATA", "YES");
    }
    wo->nDstAlphaBand = 4;
    wo->eResampleAlg = GRA_Bilinear;
    wo->papszWarpOptions = CSLSetNameValue(wo->papszWarpOptions, "INIT_DEST", "0");
    constexpr double kMaxErrorPixels = 0.01;
    if (warpOntoNet(wo, netToRaster(grid, place), kMaxErrorPixels, {}) == CE_None) return dst;
    diags.error(fileLoc, fmt::format("GDAL could not resample texture.image onto the surface: {}",
                                     CPLGetLastErrorMsg()));
    return Dataset();
}

// The warped image's bands in the grid's order (row 0 south); false when GDAL cannot read them.
bool readImageBack(GDALDatasetH dst, ImageOnGrid& out) {
    const int rows = out.rows, cols = out.cols;
    const size_t n = static_cast<size_t>(rows) * cols;
    std::vector<std::uint8_t> band(n);
    out.rgb.resize(3 * n);
    out.covered.resize(n);
    for (int b = 0; b < 4; ++b) {
        if (GDALRasterIO(GDALGetRasterBand(dst, b + 1), GF_Read, 0, 0, cols, rows, band.data(), cols, rows,
                         GDT_Byte, 0, 0) != CE_None)
            return false;
        // The MEM image's row 0 is north; the grid's row 0 is south.
        for (int r = 0; r < rows; ++r)
            for (int c = 0; c < cols; ++c) {
                const std::uint8_t v = band[static_cast<size_t>(rows - 1 - r) * cols + c];
                const size_t node = static_cast<size_t>(r) * cols + c;
                if (b < 3) out.rgb[3 * node + b] = v;
                else out.covered[node] = v > 127;
            }
    }
    for (const auto c : out.covered) out.coveredCount += c;
    return true;
}

}  // namespace

std::optional<ImageOnGrid> imageOnGrid(const std::filesystem::path& path, const std::string& pathAsWritten,
                                       const GeoGrid& grid, Diagnostics& diags) {
    const SourceLoc fileLoc{pathAsWritten, 0, 0};
    std::string problem;
    Dataset src = openRaster(path, problem);
    if (!src) {
        diags.error(fileLoc, !problem.empty()
                                 ? fmt::format("texture.image: relief does not read this image: {}", problem)
                                 : std::string("texture.image: GDAL cannot read it as a raster image (a GeoTIFF, "
                                               "PNG with a world file, JPEG 2000, ...)"));
        return std::nullopt;
    }
    if (!checkImageBands(src.get(), fileLoc, diags)) return std::nullopt;
    const auto place = placeOfImage(src.get(), fileLoc, diags);
    if (!place) return std::nullopt;
    const Dataset dst = warpedImage(src.get(), *place, grid, fileLoc, diags);
    if (!dst) return std::nullopt;
    ImageOnGrid out;
    out.attribution = rasterCredit(src.get());
    out.rows = grid.rows();
    out.cols = grid.cols();
    if (!readImageBack(dst.get(), out)) {
        diags.error(fileLoc, "reading the resampled image back failed");
        return std::nullopt;
    }
    if (out.coveredCount == 0) {
        diags.error(fileLoc, "texture.image does not cover the terrain: check that it shows the same place (and its "
                             "CRS)");
        return std::nullopt;
    }
    return out;
}

}  // namespace relief::geo
