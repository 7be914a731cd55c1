// A raster as GDAL opens it, whether it is one, and the phases that check it
// as a DEM before a cell is read: its header, its band, its geotransform, its CRS.
#include "geo/raster_source.h"

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <limits>
#include <optional>
#include <string_view>
#include <tuple>

#include <cpl_error.h>
#include <cpl_string.h>
#include <fmt/format.h>

#include "core/input_file.h"
#include "core/text_escape.h"
#include "geo/gdal_crs.h"
#include "geo/gdal_setup.h"
#include "geo/raster_heights.h"
#include "geo/raster.h"

namespace relief::geo {

std::pair<Transform, Transform> wgs84Transforms(OGRSpatialReferenceH srs) {
    // Longitude first, as GIS software gives them.
    const Srs wgs84(OSRNewSpatialReference(nullptr));
    OSRSetWellKnownGeogCS(wgs84.get(), "WGS84");
    OSRSetAxisMappingStrategy(wgs84.get(), OAMS_TRADITIONAL_GIS_ORDER);
    return {Transform(OCTNewCoordinateTransformation(wgs84.get(), srs)),
            Transform(OCTNewCoordinateTransformation(srs, wgs84.get()))};
}

Dataset openRaster(const std::filesystem::path& path, std::string& problem, const FolderNames* siblings) {
    return openChecked(path, GDAL_OF_RASTER, problem, siblings);
}

Dataset openChecked(const std::filesystem::path& path, unsigned kind, std::string& problem,
                    const FolderNames* siblings, const char* const* openOptions) {
    std::optional<FolderNames> listedHere;
    if (!siblings) siblings = &listedHere.emplace(FolderNames::of(path));
    problem = gdalInputProblem(path, siblings, (kind & GDAL_OF_VECTOR) ? DatasetKind::Vector : DatasetKind::Raster);
    if (!problem.empty()) return Dataset();
    // Absolute: a relative name is never taken for a driver's prefix ("NETCDF:...").
    std::error_code ec;
    const std::string name = std::filesystem::absolute(path, ec).string();
    // Only the files beside it that were checked: GDAL lists no folder itself.
    const SiblingFiles beside(*siblings, path.filename().string());
    CPLPushErrorHandler(CPLQuietErrorHandler);
    Dataset ds(GDALOpenEx(name.c_str(), kind | GDAL_OF_READONLY, nullptr, openOptions, beside.forGdal()));
    CPLPopErrorHandler();
    return ds;
}

namespace {

// The first of the metadata items `keys` the raster has: a file's own text,
// as UTF-8 (text that is not is Latin-1, as an old GeoTIFF's tags often are:
// every byte a character, so "Montaña" reads right), cut (at a character) to
// what a still can show.
std::string metadataText(GDALDatasetH ds, std::initializer_list<const char*> keys) {
    for (const char* key : keys)
        if (const char* v = GDALGetMetadataItem(ds, key, nullptr); v && *v) {
            std::string text = isUtf8(v) ? std::string(v) : latin1AsUtf8(v);
            if (text.size() <= scene::kMaxTextBytes) return text;
            size_t cut = scene::kMaxTextBytes;
            while (cut > 0 && (static_cast<unsigned char>(text[cut]) & 0xC0) == 0x80) --cut;
            return text.substr(0, cut) + "\u2026";
        }
    return {};
}

}  // namespace

// A licence such as CC BY asks for the credit in the still.
std::string rasterCredit(GDALDatasetH ds) {
    return metadataText(ds, {"TIFFTAG_COPYRIGHT", "COPYRIGHT", "ATTRIBUTION", "LICENSE", "LICENCE"});
}

bool RasterPlace::toPixel(double lonDeg, double latDeg, double& px, double& py) const {
    double cx = lonDeg, cy = latDeg, cz = 0;
    if (!OCTTransform(crs.toRaster.get(), 1, &cx, &cy, &cz)) return false;
    px = inverse[0] + cx * inverse[1] + cy * inverse[2];
    py = inverse[3] + cx * inverse[4] + cy * inverse[5];
    return true;
}

bool RasterPlace::toLonLat(double px, double py, double& lonDeg, double& latDeg) const {
    double cx = geo[0] + px * geo[1], cy = geo[3] + py * geo[5], cz = 0;
    if (!OCTTransform(crs.toWgs84.get(), 1, &cx, &cy, &cz)) return false;
    lonDeg = cx, latDeg = cy;
    return true;
}

double RasterPlace::wrapPixels() const {
    return OSRIsGeographic(crs.srs.get()) && geo[1] != 0 ? std::fabs(360.0 / geo[1]) : 0;
}

namespace {

// What GDAL's warper would read of the raster: every cell, unless the raster
// has overviews. Beyond kMaxReadCells (16 GB of 32-bit cells) that takes
// longer than any still is worth, and a header that claims more cells than
// its file can hold (an ASCII grid: two bytes a cell at least) is damaged or
// hostile; both are refused from the header, before anything is read.
constexpr double kMaxReadCells = 2e9;
constexpr std::string_view kAsciiDrivers[] = {"AAIGrid", "GRASSASCIIGrid", "GSAG", "USGSDEM"};
// Uncompressed: every cell takes its type's bytes in the file.
constexpr std::string_view kRawDrivers[] = {"EHdr", "ENVI", "BT", "GS7BG", "GSBG", "RST", "SRTMHGT",
                                            "Terragen", "Leveller", "DTED", "SAGA"};

std::uintmax_t bytesOfFiles(GDALDatasetH ds) {
    char** files = GDALGetFileList(ds);
    std::uintmax_t bytes = 0;
    std::error_code ec;
    for (char** f = files; f && *f; ++f) bytes += std::filesystem::file_size(*f, ec), ec.clear();
    CSLDestroy(files);
    return bytes;
}

std::string headerProblem(GDALDatasetH ds, double cells) {
    const std::string_view driver = GDALGetDriverShortName(GDALGetDatasetDriver(ds));
    const auto among = [&](const auto& list) { return std::find(std::begin(list), std::end(list), driver) != std::end(list); };
    const std::uintmax_t bytes = bytesOfFiles(ds);
    if (among(kAsciiDrivers) && bytes > 0 && 2 * cells > double(bytes) + 4096)
        return fmt::format("the raster's header says {} x {} cells, more than its {} bytes can hold (an {} grid "
                           "takes two bytes a cell at least): the file is damaged or truncated",
                           GDALGetRasterXSize(ds), GDALGetRasterYSize(ds), bytes, driver);
    GDALRasterBandH band = GDALGetRasterBand(ds, 1);
    const double cellBytes = band ? GDALGetDataTypeSizeBytes(GDALGetRasterDataType(band)) : 1;
    if (among(kRawDrivers) && bytes > 0 && cells * cellBytes > double(bytes) + 65536)
        return fmt::format("the raster's header says {} x {} cells of {} bytes, more than its {} bytes hold: the "
                           "file is damaged or truncated",
                           GDALGetRasterXSize(ds), GDALGetRasterYSize(ds), cellBytes, bytes);
    if (cells > kMaxReadCells && band && GDALGetOverviewCount(band) == 0)
        return fmt::format("the raster is {} x {} cells ({:.3g}), more than the {:.3g} relief reads from a raster "
                           "without overviews: add overviews (gdaladdo) or cut a window (gdal_translate -projwin)",
                           GDALGetRasterXSize(ds), GDALGetRasterYSize(ds), cells, kMaxReadCells);
    return "";
}

// From the header, before a cell is read: a net at the raster's own cell size
// (the default) must fit the budget.
bool checkHeader(GDALDatasetH src, const scene::NetSpec& net, const NetBudget& budget, const SourceLoc& fileLoc,
                 Diagnostics& diags) {
    const int width = GDALGetRasterXSize(src), height = GDALGetRasterYSize(src);
    const double cells = double(width) * double(height);
    const bool netGiven = net.spacingM > 0 || net.locs.has("net.rows") || net.locs.has("net.cols");
    if (std::string problem = headerProblem(src, cells); !problem.empty()) {
        diags.error(fileLoc, problem);
        return false;
    }
    if (!netGiven && cells > budget.maxNodes) {
        diags.error(fileLoc, fmt::format("the raster is {} x {} cells ({:.3g}); a net at its own cell size would "
                                         "have more nodes than the {:.3g} allowed by {}: give net.spacing_m "
                                         "(a coarser net) or net.extent_lonlat (a window)",
                                         width, height, cells, budget.maxNodes, budget.why));
        return false;
    }
    return true;
}

// An image (a photo, a map tile) is not a DEM: its red channel read as
// heights would render as terrain, wrongly and without a word.
constexpr GDALColorInterp kImageBands[] = {
    GCI_RedBand,  GCI_GreenBand,   GCI_BlueBand,   GCI_AlphaBand,   GCI_PaletteIndex, GCI_HueBand,
    GCI_SaturationBand, GCI_LightnessBand, GCI_CyanBand, GCI_MagentaBand, GCI_YellowBand, GCI_BlackBand,
    GCI_YCbCr_YBand, GCI_YCbCr_CbBand, GCI_YCbCr_CrBand};

bool checkHeightBand(GDALDatasetH src, const scene::SamplesSpec& samples, Diagnostics& diags) {
    const int bands = GDALGetRasterCount(src);
    if (samples.band > bands) {
        diags.error(samples.locs.at("samples.band"),
                    fmt::format("samples.band = {}, but {} has {} band{}: give a band from 1 to {}",
                                samples.band, samples.pathAsWritten, bands, bands == 1 ? "" : "s", bands));
        return false;
    }
    const GDALColorInterp colour = GDALGetRasterColorInterpretation(GDALGetRasterBand(src, samples.band));
    if (std::find(std::begin(kImageBands), std::end(kImageBands), colour) == std::end(kImageBands)) return true;
    diags.error({samples.pathAsWritten, 0, 0},
                fmt::format("band {} of the raster is the {} band of an image ({} band{} in all), not elevations: "
                            "a DEM has a band of heights; an image is a texture, not samples",
                            samples.band, GDALGetColorInterpretationName(colour), bands, bands == 1 ? "" : "s"));
    return false;
}

// The size and a north-up geotransform, with its inverse.
bool georeference(GDALDatasetH src, RasterPlace& place, const SourceLoc& fileLoc, Diagnostics& diags) {
    place.width = GDALGetRasterXSize(src), place.height = GDALGetRasterYSize(src);
    if (place.width < 2 || place.height < 2) {
        diags.error(fileLoc, fmt::format("the raster is {} x {} cells; a surface needs at least 2 x 2",
                                         place.width, place.height));
        return false;
    }
    if (GDALGetGeoTransform(src, place.geo.data()) != CE_None) {
        diags.error(fileLoc, "the raster has no georeferencing (geotransform): give it one, e.g. with "
                             "gdal_translate -a_ullr and -a_srs");
        return false;
    }
    if (place.geo[2] != 0 || place.geo[4] != 0) {
        diags.error(fileLoc, "the raster's geotransform is rotated; relief reads north-up rasters: "
                             "warp it first (gdalwarp)");
        return false;
    }
    if (!GDALInvGeoTransform(place.geo.data(), place.inverse.data())) {
        diags.error(fileLoc, "the raster's geotransform cannot be inverted (a cell of size 0?)");
        return false;
    }
    return true;
}

// The raster's CRS, or the scene's word for it, carried to and from WGS84.
std::optional<RasterCrs> demCrs(GDALDatasetH src, const scene::SamplesSpec& samples, const SourceLoc& fileLoc,
                                Diagnostics& diags) {
    RasterCrs crs{Srs(OSRNewSpatialReference(nullptr)), nullptr, nullptr};
    OSRSetAxisMappingStrategy(crs.srs.get(), OAMS_TRADITIONAL_GIS_ORDER);
    if (!samples.crs.empty()) {
        if (std::string problem; !crsFromText(crs.srs.get(), samples.crs, problem)) {
            diags.error(samples.locs.at("samples.crs"),
                        fmt::format("samples.crs = \"{}\" {}", printableExcerpt(samples.crs, 80), problem));
            return std::nullopt;
        }
    } else {
        const char* wkt = GDALGetProjectionRef(src);
        if (!wkt || !*wkt || OSRImportFromWkt(crs.srs.get(), const_cast<char**>(&wkt)) != OGRERR_NONE) {
            diags.error(fileLoc, "the raster has no coordinate reference system: give it in the scene, "
                                 "e.g. crs = \"EPSG:2193\" in [samples]");
            return std::nullopt;
        }
    }
    std::tie(crs.toRaster, crs.toWgs84) = wgs84Transforms(crs.srs.get());
    if (!crs.toRaster || !crs.toWgs84) {
        diags.error(fileLoc, "PROJ cannot transform between WGS84 and the raster's CRS");
        return std::nullopt;
    }
    return crs;
}

}  // namespace

std::optional<RasterPlace> placeOfDem(GDALDatasetH src, const scene::SamplesSpec& samples,
                                      const scene::NetSpec& net, const NetBudget& budget, Diagnostics& diags) {
    const SourceLoc fileLoc{samples.pathAsWritten, 0, 0};
    RasterPlace place;
    if (!checkHeader(src, net, budget, fileLoc, diags) || !checkHeightBand(src, samples, diags) ||
        !georeference(src, place, fileLoc, diags))
        return std::nullopt;
    auto crs = demCrs(src, samples, fileLoc, diags);
    if (!crs) return std::nullopt;
    place.crs = std::move(*crs);
    return place;
}

HeightBand heightBand(GDALDatasetH src, int number) {
    HeightBand b;
    b.band = GDALGetRasterBand(src, number);
    b.number = number;
    int hasNoData = FALSE;
    b.declaredNoData = GDALGetRasterNoDataValue(b.band, &hasNoData);
    b.hasNoData = hasNoData;
    b.noData = hasNoData ? b.declaredNoData : std::nan("");
    // As a Float32 cell holds it (-9999.1 is -9999.099609375 there), as GTiff says but not every
    // driver does: the cells, read as doubles, must compare equal to it.
    constexpr double kFloatMax = std::numeric_limits<float>::max();
    if (hasNoData && GDALGetRasterDataType(b.band) == GDT_Float32 && std::isfinite(b.noData) &&
        std::fabs(b.noData) <= kFloatMax * (1 + 1e-7))
        b.noData = static_cast<float>(std::clamp(b.noData, -kFloatMax, kFloatMax));
    return b;
}

std::optional<RasterSummary> rasterSummary(const std::filesystem::path& path) {
    std::string problem;
    const Dataset ds = openRaster(path, problem);
    if (!ds || GDALGetRasterCount(ds.get()) < 1) return std::nullopt;
    RasterSummary s;
    s.title = metadataText(ds.get(), {"TIFFTAG_DOCUMENTNAME", "TITLE", "DESCRIPTION"});
    double minMax[2] = {0, 0};
    const HeightBand band = heightBand(ds.get(), 1);
    CPLPushErrorHandler(CPLQuietErrorHandler);
    const CPLErr err = GDALComputeRasterMinMax(band.band, TRUE, minMax);
    CPLPopErrorHandler();
    Diagnostics unitUnknown;  // taken as metres; the scene's net says so when it is made
    const double metres = metresPerBandUnit(band, {}, unitUnknown);
    if (err == CE_None && std::isfinite(minMax[0]) && std::isfinite(minMax[1]))
        s.range = std::array<double, 2>{metres * minMax[0], metres * minMax[1]};
    return s;
}

bool isRasterDem(const std::filesystem::path& path, const FolderNames* siblings) {
    std::optional<FolderNames> listedHere;
    if (!siblings) siblings = &listedHere.emplace(FolderNames::of(path));
    std::string problem;
    if (openRaster(path, problem, siblings)) return true;
    // A VRT relief refuses, or a file identified as a raster format but not
    // readable (a truncated GeoTIFF): still a raster, so that the error is about
    // the raster, not about a CSV header made of binary bytes.
    if (!problem.empty()) return inputFileProblem(path).empty();  // refused for what it brings with it
    CPLPushErrorHandler(CPLQuietErrorHandler);
    const SiblingFiles beside(*siblings, path.filename().string());
    GDALDriverH driver = GDALIdentifyDriverEx(path.c_str(), GDAL_OF_RASTER, nullptr, beside.forGdal());
    CPLPopErrorHandler();
    return driver != nullptr;
}

}  // namespace relief::geo
