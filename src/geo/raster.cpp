#include "geo/raster.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <string_view>
#include <vector>

#include <cpl_conv.h>
#include <cpl_error.h>
#include <cpl_string.h>
#include <gdal.h>
#include <gdal_alg.h>
#include <gdalwarper.h>
#include <ogr_srs_api.h>
#include <fmt/format.h>

#include "core/input_file.h"
#include "core/number_format.h"
#include "core/text_escape.h"
#include "geo/gdal_crs.h"
#include "geo/gdal_setup.h"

namespace relief::geo {

namespace {

struct DatasetCloser {
    void operator()(void* ds) const { GDALClose(ds); }
};
using Dataset = std::unique_ptr<void, DatasetCloser>;
struct SrsDeleter {
    void operator()(void* s) const { OSRDestroySpatialReference(static_cast<OGRSpatialReferenceH>(s)); }
};
struct TransformDeleter {
    void operator()(void* t) const { OCTDestroyCoordinateTransformation(static_cast<OGRCoordinateTransformationH>(t)); }
};
using Srs = std::unique_ptr<void, SrsDeleter>;
using Transform = std::unique_ptr<void, TransformDeleter>;

// WGS84 longitude and latitude (in that order, as GIS software gives them).
Srs wgs84Lonlat() {
    Srs wgs84(OSRNewSpatialReference(nullptr));
    OSRSetWellKnownGeogCS(wgs84.get(), "WGS84");
    OSRSetAxisMappingStrategy(wgs84.get(), OAMS_TRADITIONAL_GIS_ORDER);
    return wgs84;
}

// The transformations from WGS84 to `srs` and back; either is null when PROJ has none.
std::pair<Transform, Transform> wgs84Transforms(OGRSpatialReferenceH srs) {
    const Srs wgs84 = wgs84Lonlat();
    return {Transform(OCTNewCoordinateTransformation(wgs84.get(), srs)),
            Transform(OCTNewCoordinateTransformation(srs, wgs84.get()))};
}

// A raster a scene names, opened as GDAL reads it once relief has checked it
// (gdal_setup.h); `problem` says why not when GDAL must not open it.
Dataset openRaster(const std::filesystem::path& path, std::string& problem) {
    problem = gdalInputProblem(path);
    if (!problem.empty()) return Dataset();
    // Absolute: a relative name is never taken for a driver's prefix ("NETCDF:...").
    std::error_code ec;
    const std::string name = std::filesystem::absolute(path, ec).string();
    CPLPushErrorHandler(CPLQuietErrorHandler);
    Dataset ds(GDALOpenEx(name.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY, nullptr, nullptr, nullptr));
    CPLPopErrorHandler();
    return ds;
}

// The credit a raster's metadata carries: GeoTIFF's copyright tag, or a
// COPYRIGHT, LICENSE, LICENCE or ATTRIBUTION item (as GDAL's drivers name
// them); a licence such as CC BY asks for it in the still.
std::string rasterCredit(GDALDatasetH ds) {
    for (const char* key : {"TIFFTAG_COPYRIGHT", "COPYRIGHT", "ATTRIBUTION", "LICENSE", "LICENCE"})
        if (const char* v = GDALGetMetadataItem(ds, key, nullptr); v && *v) {
            // A file's own text, cut (at a character) to what a still can show.
            std::string credit = v;
            if (credit.size() <= scene::kMaxTextBytes) return credit;
            size_t cut = scene::kMaxTextBytes;
            while (cut > 0 && (static_cast<unsigned char>(credit[cut]) & 0xC0) == 0x80) --cut;
            return credit.substr(0, cut) + "\u2026";
        }
    return {};
}

// The chain from a net node to a raster pixel and back: frame <-> WGS84
// (GeographicLib) <-> the raster's CRS (PROJ, through GDAL) <-> pixel and line
// (the geotransform). GDAL's warper calls it with its own pixel coordinates of
// the net: pixel centres are the nodes, row 0 north.
struct NetToRaster {
    Frame frame;
    double x0 = 0, y0 = 0, dx = 1, dy = 1;
    int rows = 0;
    OGRCoordinateTransformationH toRaster = nullptr, toWgs84 = nullptr;
    double geo[6] = {}, inverse[6] = {};
    /// A raster in degrees: 360 degrees in its pixels, so that a node west of
    /// the antimeridian finds the raster's cells east of it (lon 181 = -179);
    /// 0 otherwise.
    double wrapPixels = 0;
    int width = 0;
};

// A raster in geographic degrees wraps round the antimeridian.
double wrapPixelsOf(OGRSpatialReferenceH srs, const double geo[6]) {
    return OSRIsGeographic(srs) && geo[1] != 0 ? std::fabs(360.0 / geo[1]) : 0;
}

int transformNetToRaster(void* arg, int dstToSrc, int count, double* x, double* y, double* z, int* ok) {
    const auto& t = *static_cast<const NetToRaster*>(arg);
    for (int i = 0; i < count; ++i) {
        ok[i] = FALSE;
        double lat = 0, lon = 0, h = 0;
        if (dstToSrc) {
            const Vec3 p{t.x0 + (x[i] - 0.5) * t.dx, t.y0 + (t.rows - 0.5 - y[i]) * t.dy, 0};
            if (!frameToGeodetic(t.frame, p, lat, lon, h)) continue;
            double cx = lon, cy = lat, cz = 0;
            if (!OCTTransform(t.toRaster, 1, &cx, &cy, &cz)) continue;
            x[i] = t.inverse[0] + cx * t.inverse[1] + cy * t.inverse[2];
            y[i] = t.inverse[3] + cx * t.inverse[4] + cy * t.inverse[5];
            if (t.wrapPixels > 0 && (x[i] < 0 || x[i] > t.width)) {
                // Only onto the raster: a node off it stays where it is (continuous for the approximator).
                const double wrapped = x[i] + (x[i] < 0 ? t.wrapPixels : -t.wrapPixels);
                if (wrapped >= 0 && wrapped <= t.width) x[i] = wrapped;
            }
        } else {
            double cx = t.geo[0] + x[i] * t.geo[1] + y[i] * t.geo[2];
            double cy = t.geo[3] + x[i] * t.geo[4] + y[i] * t.geo[5], cz = 0;
            if (!OCTTransform(t.toWgs84, 1, &cx, &cy, &cz)) continue;
            Vec3 p;
            if (!geodeticToFrame(t.frame, cy, cx, 0, p)) continue;
            x[i] = (p.x - t.x0) / t.dx + 0.5;
            y[i] = t.rows - 0.5 - (p.y - t.y0) / t.dy;
        }
        if (z) z[i] = 0;
        ok[i] = std::isfinite(x[i]) && std::isfinite(y[i]);
    }
    return TRUE;
}

int CPL_STDCALL reportWarpProgress(double fraction, const char*, void* fn) {
    (*static_cast<const GridProgressFn*>(fn))(fraction);
    return TRUE;
}

// Runs the warp `wo` describes onto a cols x rows net through `chain`,
// approximated within maxErrorPixels of the source (GDAL's approximating
// transformer, as gdalwarp uses by default), quietly; takes `wo` and frees it.
CPLErr warpOntoNet(GDALWarpOptions* wo, NetToRaster& chain, double maxErrorPixels, const GridProgressFn& progress,
                   int cols, int rows) {
    struct ApproxDeleter {
        void operator()(void* t) const { GDALDestroyApproxTransformer(t); }
    };
    std::unique_ptr<void, ApproxDeleter> approx(GDALCreateApproxTransformer(transformNetToRaster, &chain, maxErrorPixels));
    wo->pfnTransformer = GDALApproxTransform;
    wo->pTransformerArg = approx.get();
    if (progress) {
        wo->pfnProgress = reportWarpProgress;
        wo->pProgressArg = const_cast<GridProgressFn*>(&progress);
    }
    CPLPushErrorHandler(CPLQuietErrorHandler);
    GDALWarpOperation warp;
    CPLErr err = warp.Initialize(wo);
    if (err == CE_None) err = warp.ChunkAndWarpImage(0, 0, cols, rows);
    CPLPopErrorHandler();
    GDALDestroyWarpOptions(wo);
    return err;
}

GDALResampleAlg gdalResampling(scene::Resample r) {
    switch (r) {
        case scene::Resample::Bilinear: return GRA_Bilinear;
        case scene::Resample::Cubic: return GRA_Cubic;
        case scene::Resample::Average: return GRA_Average;
        case scene::Resample::Nearest: return GRA_NearestNeighbour;
    }
    return GRA_Bilinear;
}

// Metres per unit of the band's values: 1 for metres, 0.3048 for feet
// (1200/3937 for US survey feet); 0 when the unit is not a length relief knows.
double metresPerUnit(std::string unit) {
    std::transform(unit.begin(), unit.end(), unit.begin(), [](unsigned char c) { return std::tolower(c); });
    if (unit == "m" || unit == "metre" || unit == "meter" || unit == "metres" || unit == "meters") return 1;
    if (unit == "ft" || unit == "foot" || unit == "feet" || unit == "international foot") return 0.3048;
    if (unit == "us-ft" || unit == "us survey foot" || unit == "ftus") return 1200.0 / 3937.0;
    return 0;
}

// The box of cells (pixel edges: x0, y0, x1, y1) that holds every cell with
// data, so that a raster with a nodata border (a region, a coastline tile)
// defaults to its data, not to its border. Read at most kScan cells across,
// and widened by one read cell; nullopt when no read cell has data.
struct PixelBox {
    double x0, y0, x1, y1;
};
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
std::string headerProblem(GDALDatasetH ds, double cells) {
    const std::string_view driver = GDALGetDriverShortName(GDALGetDatasetDriver(ds));
    const auto among = [&](const auto& list) { return std::find(std::begin(list), std::end(list), driver) != std::end(list); };
    const bool ascii = among(kAsciiDrivers);
    char** files = GDALGetFileList(ds);
    std::uintmax_t bytes = 0;
    std::error_code ec;
    for (char** f = files; f && *f; ++f) bytes += std::filesystem::file_size(*f, ec), ec.clear();
    CSLDestroy(files);
    if (ascii && bytes > 0 && 2 * cells > double(bytes) + 4096)
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

}  // namespace

bool isRasterDem(const std::filesystem::path& path) {
    std::string problem;
    if (openRaster(path, problem)) return true;
    // A VRT relief refuses, or a file identified as a raster format but not
    // readable (a truncated GeoTIFF): still a raster, so that the error is about
    // the raster, not about a CSV header made of binary bytes.
    if (!problem.empty()) return inputFileProblem(path).empty();  // refused for what it brings with it
    CPLPushErrorHandler(CPLQuietErrorHandler);
    GDALDriverH driver = GDALIdentifyDriverEx(path.c_str(), GDAL_OF_RASTER, nullptr, nullptr);
    CPLPopErrorHandler();
    return driver != nullptr;
}

namespace {

// The raster `src` (opened from the scene's file, or made from a lattice of
// samples) resampled onto the net. `footprint`: the cells whose box is the
// default extent; nullopt: the cells with data.
std::optional<ControlNet> warpedNet(const Dataset& src, const scene::SamplesSpec& samples,
                                    const scene::FrameSpec& frameSpec, const scene::NetSpec& netSpec,
                                    std::optional<PixelBox> footprint, Diagnostics& diags,
                                    const GridProgressFn& progress, const NetBudget& budget) {
    const std::string& name = samples.pathAsWritten;
    const SourceLoc fileLoc{name, 0, 0};
    const int width = GDALGetRasterXSize(src.get()), height = GDALGetRasterYSize(src.get());
    const double cells = double(width) * double(height);
    // From the header, before a cell is read: a net at the raster's own cell
    // size (the default) must fit the budget.
    const bool netGiven = netSpec.spacingM > 0 || netSpec.locs.has("net.rows") || netSpec.locs.has("net.cols");
    if (std::string problem = headerProblem(src.get(), cells); !problem.empty()) {
        diags.error(fileLoc, problem);
        return std::nullopt;
    }
    if (!netGiven && cells > budget.maxNodes) {
        diags.error(fileLoc, fmt::format("the raster is {} x {} cells ({:.3g}); a net at its own cell size would "
                                         "have more nodes than the {:.3g} allowed by {}: give net.spacing_m "
                                         "(a coarser net) or net.extent_lonlat (a window)",
                                         width, height, cells, budget.maxNodes, budget.why));
        return std::nullopt;
    }
    const int bands = GDALGetRasterCount(src.get());
    if (samples.band > bands) {
        diags.error(samples.locs.at("samples.band"),
                    fmt::format("samples.band = {}, but {} has {} band{}: give a band from 1 to {}",
                                samples.band, name, bands, bands == 1 ? "" : "s", bands));
        return std::nullopt;
    }
    // An image (a photo, a map tile) is not a DEM: its red channel read as
    // heights would render as terrain, wrongly and without a word.
    switch (GDALGetRasterColorInterpretation(GDALGetRasterBand(src.get(), samples.band))) {
        case GCI_RedBand: case GCI_GreenBand: case GCI_BlueBand: case GCI_AlphaBand:
        case GCI_PaletteIndex: case GCI_HueBand: case GCI_SaturationBand: case GCI_LightnessBand:
        case GCI_CyanBand: case GCI_MagentaBand: case GCI_YellowBand: case GCI_BlackBand:
        case GCI_YCbCr_YBand: case GCI_YCbCr_CbBand: case GCI_YCbCr_CrBand:
            diags.error(fileLoc,
                        fmt::format("band {} of the raster is the {} band of an image ({} band{} in all), not elevations: "
                                    "a DEM has a band of heights; an image is a texture, not samples",
                                    samples.band,
                                    GDALGetColorInterpretationName(
                                        GDALGetRasterColorInterpretation(GDALGetRasterBand(src.get(), samples.band))),
                                    bands, bands == 1 ? "" : "s"));
            return std::nullopt;
        default: break;
    }
    if (width < 2 || height < 2) {
        diags.error(fileLoc, fmt::format("the raster is {} x {} cells; a surface needs at least 2 x 2",
                                         width, height));
        return std::nullopt;
    }
    double geo[6];
    if (GDALGetGeoTransform(src.get(), geo) != CE_None) {
        diags.error(fileLoc, "the raster has no georeferencing (geotransform): give it one, e.g. with "
                             "gdal_translate -a_ullr and -a_srs");
        return std::nullopt;
    }
    if (geo[2] != 0 || geo[4] != 0) {
        diags.error(fileLoc, "the raster's geotransform is rotated; relief reads north-up rasters: "
                             "warp it first (gdalwarp)");
        return std::nullopt;
    }
    double inverse[6];
    if (!GDALInvGeoTransform(geo, inverse)) {
        diags.error(fileLoc, "the raster's geotransform cannot be inverted (a cell of size 0?)");
        return std::nullopt;
    }

    // The raster's CRS, or the scene's word for it.
    Srs rasterSrs(OSRNewSpatialReference(nullptr));
    OSRSetAxisMappingStrategy(rasterSrs.get(), OAMS_TRADITIONAL_GIS_ORDER);
    if (!samples.crs.empty()) {
        if (std::string problem; !crsFromText(rasterSrs.get(), samples.crs, problem)) {
            diags.error(samples.locs.at("samples.crs"),
                        fmt::format("samples.crs = \"{}\" {}", printableExcerpt(samples.crs, 80), problem));
            return std::nullopt;
        }
    } else {
        const char* wkt = GDALGetProjectionRef(src.get());
        if (!wkt || !*wkt || OSRImportFromWkt(rasterSrs.get(), const_cast<char**>(&wkt)) != OGRERR_NONE) {
            diags.error(fileLoc, "the raster has no coordinate reference system: give it in the scene, "
                                 "e.g. crs = \"EPSG:2193\" in [samples]");
            return std::nullopt;
        }
    }
    // Named, not structured bindings: lambdas below capture them (clang 14 cannot capture a binding).
    auto transforms = wgs84Transforms(rasterSrs.get());
    Transform& toRaster = transforms.first;
    Transform& toWgs84 = transforms.second;
    if (!toRaster || !toWgs84) {
        diags.error(fileLoc, "PROJ cannot transform between WGS84 and the raster's CRS");
        return std::nullopt;
    }

    GDALRasterBandH band = GDALGetRasterBand(src.get(), samples.band);
    int hasNoData = FALSE;
    const double declaredNoData = GDALGetRasterNoDataValue(band, &hasNoData);
    // No declared nodata: NaN cells are still no data.
    const double srcNoData = hasNoData ? declaredNoData : std::nan("");
    const bool window = netSpec.extentM || netSpec.extentLonLat;
    PixelBox box = footprint ? *footprint : PixelBox{0, 0, double(width), double(height)};
    if (!window && !footprint && dataBoxAffordable(band, cells)) {
        const auto data = dataBox(band, width, height, srcNoData);
        if (!data) {
            diags.error(fileLoc, fmt::format("every cell of band {} is nodata ({}): check the band and the "
                                             "raster's nodata value",
                                             samples.band, hasNoData ? formatShortest(declaredNoData) : "NaN"));
            return std::nullopt;
        }
        box = *data;
    }

    // The footprint: points along the edges of the raster's data, in WGS84.
    std::vector<GeoSample> edge;
    auto addPixel = [&](double px, double py) {
        double cx = geo[0] + px * geo[1], cy = geo[3] + py * geo[5], cz = 0;
        if (OCTTransform(toWgs84.get(), 1, &cx, &cy, &cz) && std::fabs(cy) <= 90)
            edge.push_back({cx, cy, 0, {}});
    };
    constexpr int kEdgePoints = 64;
    const double boxW = box.x1 - box.x0, boxH = box.y1 - box.y0;
    for (int i = 0; i <= kEdgePoints; ++i) {
        const double f = static_cast<double>(i) / kEdgePoints;
        addPixel(box.x0 + f * boxW, box.y0), addPixel(box.x0 + f * boxW, box.y1);
        addPixel(box.x0, box.y0 + f * boxH), addPixel(box.x1, box.y0 + f * boxH);
    }
    if (edge.size() < 4) {
        diags.error(fileLoc, "the raster's corners cannot be carried to latitude and longitude: check its CRS");
        return std::nullopt;
    }
    if (netSpec.extentLonLat) {  // the frame of the window, not of the whole raster
        const auto& w = *netSpec.extentLonLat;
        edge = {{w[0], w[1], 0, {}}, {w[2], w[1], 0, {}}, {w[0], w[3], 0, {}}, {w[2], w[3], 0, {}}};
    }
    auto frame = chooseFrame(frameSpec, edge, diags);
    if (!frame) return std::nullopt;
    auto framed = [&](double px, double py, Vec3& p) {
        double cx = geo[0] + px * geo[1], cy = geo[3] + py * geo[5], cz = 0;
        return OCTTransform(toWgs84.get(), 1, &cx, &cy, &cz) && geodeticToFrame(*frame, cy, cx, 0, p);
    };
    // The largest axis-aligned box inside the footprint: the west edge's
    // easternmost point, the east edge's westernmost, and so on.
    double west = -1e300, east = 1e300, south = -1e300, north = 1e300;
    int outside = 0;
    // Which pixel edge is which: rows usually run south (negative pixel height), but may run north.
    const double westPx = geo[1] > 0 ? box.x0 : box.x1, eastPx = geo[1] > 0 ? box.x1 : box.x0;
    const double northPx = geo[5] < 0 ? box.y0 : box.y1, southPx = geo[5] < 0 ? box.y1 : box.y0;
    for (int i = 0; i <= kEdgePoints; ++i) {
        const double f = static_cast<double>(i) / kEdgePoints;
        Vec3 p;
        framed(westPx, box.y0 + f * boxH, p) ? void(west = std::max(west, p.x)) : void(++outside);
        framed(eastPx, box.y0 + f * boxH, p) ? void(east = std::min(east, p.x)) : void(++outside);
        framed(box.x0 + f * boxW, southPx, p) ? void(south = std::max(south, p.y)) : void(++outside);
        framed(box.x0 + f * boxW, northPx, p) ? void(north = std::min(north, p.y)) : void(++outside);
    }
    if (outside > 0 && !window) {
        double lonMin = 180, lonMax = -180, latMin = 90, latMax = -90;
        for (const auto& g : edge)
            lonMin = std::min(lonMin, g.lonDeg), lonMax = std::max(lonMax, g.lonDeg),
            latMin = std::min(latMin, g.latDeg), latMax = std::max(latMax, g.latDeg);
        diags.error(fileLoc, fmt::format("the raster spans lon {:.2f}..{:.2f}, lat {:.2f}..{:.2f}, more than {} "
                                         "can hold: choose a window of it with net.extent_m, or "
                                         "frame.kind = \"local\"",
                                         lonMin, lonMax, latMin, latMax, frame->describe()));
        return std::nullopt;
    }
    // The raster's cell on the ground, at the centre of the raster or of the scene's window.
    double px = 0.5 * (box.x0 + box.x1), py = 0.5 * (box.y0 + box.y1);
    if (window) {
        double lat = 0, lon = 0, h = 0;
        if (netSpec.extentLonLat) {
            lon = 0.5 * ((*netSpec.extentLonLat)[0] + (*netSpec.extentLonLat)[2]);
            lat = 0.5 * ((*netSpec.extentLonLat)[1] + (*netSpec.extentLonLat)[3]);
        } else {
            const auto& e = *netSpec.extentM;
            frameToGeodetic(*frame, {0.5 * (e[0] + e[2]), 0.5 * (e[1] + e[3]), 0}, lat, lon, h);
        }
        double cx = lon, cy = lat, cz = 0;
        if (OCTTransform(toRaster.get(), 1, &cx, &cy, &cz)) {
            px = inverse[0] + cx * inverse[1] + cy * inverse[2];
            py = inverse[3] + cx * inverse[4] + cy * inverse[5];
        }
    }
    Vec3 c0, c1, c2;
    double cell = 0;
    if (framed(px, py, c0) && framed(px + 1, py, c1) && framed(px, py + 1, c2))
        cell = std::min(length(c1 - c0), length(c2 - c0));
    if (window) west = south = 0, east = north = 1;  // the scene's window: layoutNet places the net
    if (!(east > west && north > south) || !(cell > 0)) {
        diags.error(fileLoc, fmt::format("the raster's footprint cannot be laid out in {}: check its CRS",
                                         frame->describe()));
        return std::nullopt;
    }

    ControlNet net;
    net.frame = *frame;
    net.sampleCount = static_cast<size_t>(width) * height;
    const char* crsName = OSRGetName(rasterSrs.get());
    static constexpr const char* kResampling[] = {"bilinear", "cubic", "average", "nearest"};
    net.attribution = rasterCredit(src.get());
    net.raster = fmt::format("{} x {} cells, band {}, {}, {}", width, height, samples.band,
                             crsName ? crsName : "unnamed CRS", kResampling[static_cast<int>(samples.resample)]);
    if (!layoutNet(netSpec, {west, south, east, north}, cell, net, diags, budget)) return std::nullopt;
    const int rows = net.rows(), cols = net.cols();

    // The net as a raster of its own (pixel centres = nodes, row 0 north), warped into.
    constexpr double kNoData = -1.0e30;
    Dataset dst(GDALCreate(GDALGetDriverByName("MEM"), "", cols, rows, 1, GDT_Float64, nullptr));
    if (!dst) {
        diags.error(fileLoc, fmt::format("there is no memory for a net of {} x {} nodes: give net.spacing_m (a "
                                         "coarser net), or lower limits.max_memory_mb to what this machine has",
                                         rows, cols));
        return std::nullopt;
    }
    GDALRasterBandH out = GDALGetRasterBand(dst.get(), 1);
    GDALSetRasterNoDataValue(out, kNoData);
    NetToRaster chain{net.frame, net.x0, net.y0, net.dx, net.dy, rows, toRaster.get(), toWgs84.get(), {}, {}};
    std::copy(geo, geo + 6, chain.geo);
    std::copy(inverse, inverse + 6, chain.inverse);
    chain.wrapPixels = wrapPixelsOf(rasterSrs.get(), geo);
    chain.width = width;

    GDALWarpOptions* wo = GDALCreateWarpOptions();
    wo->hSrcDS = src.get();
    wo->hDstDS = dst.get();
    wo->nBandCount = 1;
    wo->panSrcBands = static_cast<int*>(CPLMalloc(sizeof(int)));
    wo->panSrcBands[0] = samples.band;
    wo->panDstBands = static_cast<int*>(CPLMalloc(sizeof(int)));
    wo->panDstBands[0] = 1;
    wo->eWorkingDataType = GDT_Float64;
    wo->eResampleAlg = gdalResampling(samples.resample);
    wo->padfSrcNoDataReal = static_cast<double*>(CPLMalloc(sizeof(double)));
    wo->padfSrcNoDataReal[0] = srcNoData;
    wo->padfDstNoDataReal = static_cast<double*>(CPLMalloc(sizeof(double)));
    wo->padfDstNoDataReal[0] = kNoData;
    wo->papszWarpOptions = CSLSetNameValue(wo->papszWarpOptions, "INIT_DEST", "NO_DATA");
    // The exact chain costs two projections per net node; GDAL's approximating
    // transformer interpolates it linearly along each row of the net wherever
    // that stays within kMaxErrorPixels of it (checked at the row's ends and
    // middle, and recursively), as gdalwarp does by default with 0.125 raster
    // cells. Within 0.001 cells it is 8x faster on a 1000 x 1000 DEM
    // (0.07 s against 0.59 s) and changes no height by more than 0.7 mm there.
    constexpr double kMaxErrorCells = 0.001;
    if (warpOntoNet(wo, chain, kMaxErrorCells, progress, cols, rows) != CE_None) {
        diags.error(fileLoc, fmt::format("GDAL could not resample the raster onto the net: {}",
                                         CPLGetLastErrorMsg()));
        return std::nullopt;
    }

    std::vector<double> z(static_cast<size_t>(rows) * cols);
    if (GDALRasterIO(out, GF_Read, 0, 0, cols, rows, z.data(), cols, rows, GDT_Float64, 0, 0) != CE_None) {
        diags.error(fileLoc, "reading the resampled net back failed");
        return std::nullopt;
    }
    // Vertical units.
    const char* unitType = GDALGetRasterUnitType(band);
    const std::string unit = !samples.verticalUnit.empty() ? samples.verticalUnit : unitType ? unitType : "";
    double scale = metresPerUnit(unit);
    if (scale == 0) {
        diags.warning(fileLoc, fmt::format("the raster does not say its elevations are in metres (unit \"{}\"); "
                                           "they are taken as metres: say so with vertical_unit = \"m\" "
                                           "(or \"ft\", \"us-ft\") in [samples]",
                                           unit));
        scale = 1;
    }
    // Elevations beyond the Earth's are a unit or a file error, named at the
    // first such cell (the raster's column and row, counted from 0 at its
    // north-west corner).
    // Elevations = "any" still end at kAnyElevationLimitM.
    const double lowest = samples.earthElevations ? scene::kLowestElevationM : -scene::kAnyElevationLimitM;
    const double highest = samples.earthElevations ? scene::kHighestElevationM : scene::kAnyElevationLimitM;
    {
        for (size_t i = 0; i < z.size(); ++i) {
            const double h = scale * z[i];
            if (!(z[i] > kNoData * 0.5) || (h >= lowest && h <= highest)) continue;
            const size_t r = rows - 1 - i / cols, c = i % cols;
            double lat = 0, lon = 0, ignored = 0, px = -1, py = -1;
            frameToGeodetic(net.frame, {net.x0 + c * net.dx, net.y0 + r * net.dy, 0}, lat, lon, ignored);
            double cx = lon, cy = lat, cz = 0;
            if (OCTTransform(toRaster.get(), 1, &cx, &cy, &cz))
                px = inverse[0] + cx * inverse[1] + cy * inverse[2], py = inverse[3] + cx * inverse[4] + cy * inverse[5];
            // The node mixes up to four cells (bilinear): name the one that holds such a value.
            long cellX = static_cast<long>(std::floor(px)), cellY = static_cast<long>(std::floor(py));
            double held = h;
            for (int k = 0; k < 4; ++k) {
                const long tx = std::clamp(static_cast<long>(std::floor(px - 0.5)) + (k & 1), 0L, long{width - 1});
                const long ty = std::clamp(static_cast<long>(std::floor(py - 0.5)) + (k >> 1), 0L, long{height - 1});
                double v = 0;
                if (GDALRasterIO(band, GF_Read, static_cast<int>(tx), static_cast<int>(ty), 1, 1, &v, 1, 1, GDT_Float64, 0,
                                 0) != CE_None || std::isnan(v) || v == srcNoData)
                    continue;
                if (scale * v < lowest || scale * v > highest) {
                    cellX = tx, cellY = ty, held = scale * v;
                    break;
                }
            }
            if (samples.earthElevations)
                diags.error(fileLoc, fmt::format("the cell at column {}, row {} (near lat {:.6f} lon {:.6f}) holds {} m, "
                                                 "beyond the Earth's ({} to {} m): check the band, its unit and its "
                                                 "nodata value, or set elevations = \"any\" in [samples] for data that "
                                                 "are not terrain in metres",
                                                 cellX, cellY, lat, lon, formatShortest(held), lowest, highest));
            else
                diags.error(fileLoc, fmt::format("the cell at column {}, row {} (near lat {:.6f} lon {:.6f}) holds {} "
                                                 "m, beyond the {:.0e} m any elevation may be (the surface's vertices "
                                                 "are single-precision): check the band, its unit and its nodata value",
                                                 cellX, cellY, lat, lon, formatShortest(held), highest));
            return std::nullopt;
        }
    }
    size_t empty = 0, firstEmpty = z.size();
    for (size_t i = 0; i < z.size(); ++i)
        if (!(z[i] > kNoData * 0.5)) {
            if (firstEmpty == z.size()) firstEmpty = i;
            ++empty;
        }
    if (empty == z.size()) {
        // The raster has data (dataBox), so the scene's window missed it.
        const char* key = netSpec.extentLonLat ? "net.extent_lonlat" : "net.extent_m";
        diags.error(netSpec.locs.has(key) ? netSpec.locs.at(key) : fileLoc,
                    fmt::format("no node of the net has data: every cell of {} inside {} is nodata; move the "
                                "window onto the raster's data",
                                name, key));
        return std::nullopt;
    }
    if (empty > 0 && samples.nodata == scene::NodataPolicy::Error) {
        const size_t r = rows - 1 - firstEmpty / cols, c = firstEmpty % cols;
        double lat = 0, lon = 0, h = 0;
        frameToGeodetic(net.frame, {net.x0 + c * net.dx, net.y0 + r * net.dy, 0}, lat, lon, h);
        diags.error(samples.locs.at("samples.nodata"),
                    fmt::format("{} of the net's {} nodes have no data (nodata cells or outside the "
                                "raster), the first at lat {:.6f} lon {:.6f}; set nodata = \"mask\" or "
                                "\"fill\", or a smaller net.extent_m",
                                empty, z.size(), lat, lon));
        return std::nullopt;
    }
    if (empty > 0) {
        // Filled from the surrounding nodes (GDAL's inverse-distance search). To
        // fill, far enough to reach every node; to mask, only as far as the
        // refiner's stencils reach from a node with data (a few nodes), since
        // nothing shows the masked nodes' heights.
        const bool mask = samples.nodata == scene::NodataPolicy::Mask;
        constexpr int kMaskFillReach = 8;
        if (mask) {
            net.masked.assign(z.size(), 0);
            for (size_t i = 0; i < z.size(); ++i)
                if (!(z[i] > kNoData * 0.5)) net.masked[static_cast<size_t>(rows - 1 - i / cols) * cols + i % cols] = 1;
            bool wholeCell = false;
            for (int r = 0; r + 1 < rows && !wholeCell; ++r)
                for (int c = 0; c + 1 < cols && !wholeCell; ++c)
                    wholeCell = !net.isMasked(r, c) && !net.isMasked(r, c + 1) && !net.isMasked(r + 1, c) &&
                                !net.isMasked(r + 1, c + 1);
            if (!wholeCell) {
                diags.error(fileLoc, fmt::format("only {} of the net's {} nodes have data, and no cell of the net "
                                                 "has data at all four corners: choose a finer net.spacing_m "
                                                 "or a window with more data",
                                                 z.size() - empty, z.size()));
                return std::nullopt;
            }
        }
        if (GDALFillNodata(out, nullptr, mask ? kMaskFillReach : std::max(rows, cols), 0, 0, nullptr, nullptr,
                           nullptr) != CE_None ||
            GDALRasterIO(out, GF_Read, 0, 0, cols, rows, z.data(), cols, rows, GDT_Float64, 0, 0) != CE_None) {
            diags.error(fileLoc, "filling the nodes without data failed");
            return std::nullopt;
        }
        if (mask) {
            // Beyond the fill's reach: any finite height; the lowest with data.
            double lowest = 1e300;
            for (const double v : z)
                if (v > kNoData * 0.5) lowest = std::min(lowest, v);
            for (double& v : z)
                if (!(v > kNoData * 0.5)) v = lowest;
        } else {
            net.filledNodata = empty;
        }
    }

    net.grid.points.resize(z.size());
    for (int r = 0; r < rows; ++r)
        for (int c = 0; c < cols; ++c) {
            const double h = scale * z[static_cast<size_t>(rows - 1 - r) * cols + c];
            Vec3 p{net.x0 + c * net.dx, net.y0 + r * net.dy, h};
            if (net.frame.kind == scene::FrameKind::Local) {
                // z above the tangent plane, as for samples: the height plus the Earth's curvature.
                double lat, lon, ignored;
                frameToGeodetic(net.frame, {p.x, p.y, 0}, lat, lon, ignored);
                Vec3 q;
                if (geodeticToFrame(net.frame, lat, lon, h, q)) p.z = q.z;
            }
            net.grid.at(r, c) = p;
        }
    return net;
}

}  // namespace

std::optional<ControlNet> rasterNet(const scene::SamplesSpec& samples, const scene::FrameSpec& frameSpec,
                                    const scene::NetSpec& netSpec, Diagnostics& diags,
                                    const GridProgressFn& progress, const NetBudget& budget) {
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
    Dataset mem(GDALCreate(GDALGetDriverByName("MEM"), "", lattice.cols, lattice.rows, 1, GDT_Float64, nullptr));
    Srs srs(OSRNewSpatialReference(nullptr));
    char* wkt = nullptr;
    std::string problem;
    if (!mem || !crsFromText(srs.get(), lattice.crs, problem) ||
        OSRExportToWkt(srs.get(), &wkt) != OGRERR_NONE) {
        CPLFree(wkt);
        diags.error({samples.pathAsWritten, 0, 0}, "GDAL cannot hold the lattice of samples as a raster");
        return std::nullopt;
    }
    // Pixel edges half a spacing outside the samples, row 0 north.
    double geo[6] = {lattice.xWest - 0.5 * lattice.dx, lattice.dx, 0, lattice.yNorth + 0.5 * lattice.dy, 0, -lattice.dy};
    GDALSetGeoTransform(mem.get(), geo);
    GDALSetProjection(mem.get(), wkt);
    CPLFree(wkt);
    GDALRasterBandH band = GDALGetRasterBand(mem.get(), 1);
    GDALSetRasterUnitType(band, "m");  // the CSV's elev column is metres
    if (GDALRasterIO(band, GF_Write, 0, 0, lattice.cols, lattice.rows, const_cast<double*>(lattice.z.data()),
                     lattice.cols, lattice.rows, GDT_Float64, 0, 0) != CE_None) {
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

namespace relief::geo {

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
    const int bands = GDALGetRasterCount(src.get());
    const bool grey = bands == 1 || bands == 2;  // grey, or grey and alpha
    if (bands < 1 || (!grey && bands < 3) ||
        GDALGetRasterColorInterpretation(GDALGetRasterBand(src.get(), 1)) == GCI_PaletteIndex) {
        diags.error(fileLoc, fmt::format("texture.image: {} band{}{}: a drape needs red, green and blue bands or one "
                                         "grey band (expand a palette image with gdal_translate -expand rgb)",
                                         bands, bands == 1 ? "" : "s",
                                         bands >= 1 && GDALGetRasterColorInterpretation(GDALGetRasterBand(
                                                           src.get(), 1)) == GCI_PaletteIndex
                                             ? " with a colour table"
                                             : ""));
        return std::nullopt;
    }
    double geoTransform[6], inverse[6];
    if (GDALGetGeoTransform(src.get(), geoTransform) != CE_None || !GDALInvGeoTransform(geoTransform, inverse)) {
        diags.error(fileLoc, "texture.image has no georeferencing (geotransform): give it one, e.g. with "
                             "gdal_translate -a_ullr and -a_srs");
        return std::nullopt;
    }
    Srs imageSrs(OSRNewSpatialReference(nullptr));
    OSRSetAxisMappingStrategy(imageSrs.get(), OAMS_TRADITIONAL_GIS_ORDER);
    const char* wkt = GDALGetProjectionRef(src.get());
    if (!wkt || !*wkt || OSRImportFromWkt(imageSrs.get(), const_cast<char**>(&wkt)) != OGRERR_NONE) {
        diags.error(fileLoc, "texture.image has no CRS: give it one with gdal_translate -a_srs EPSG:...");
        return std::nullopt;
    }
    auto transforms = wgs84Transforms(imageSrs.get());
    Transform& toImage = transforms.first;
    Transform& toWgs84 = transforms.second;
    if (!toImage || !toWgs84) {
        diags.error(fileLoc, "texture.image: its CRS cannot be carried to WGS84");
        return std::nullopt;
    }

    // The grid as an image of its own (pixel centres = nodes, row 0 north):
    // three bands of colour and an alpha band the warper sets where it has data.
    const int rows = grid.rows(), cols = grid.cols();
    Dataset dst(GDALCreate(GDALGetDriverByName("MEM"), "", cols, rows, 4, GDT_Byte, nullptr));
    NetToRaster chain{grid.frame, grid.x0, grid.y0, grid.dx, grid.dy, rows, toImage.get(), toWgs84.get(), {}, {}};
    std::copy(geoTransform, geoTransform + 6, chain.geo);
    std::copy(inverse, inverse + 6, chain.inverse);
    chain.wrapPixels = wrapPixelsOf(imageSrs.get(), geoTransform);
    chain.width = GDALGetRasterXSize(src.get());
    GDALWarpOptions* wo = GDALCreateWarpOptions();
    wo->hSrcDS = src.get();
    wo->hDstDS = dst.get();
    wo->nBandCount = 3;
    wo->panSrcBands = static_cast<int*>(CPLMalloc(3 * sizeof(int)));
    wo->panDstBands = static_cast<int*>(CPLMalloc(3 * sizeof(int)));
    for (int b = 0; b < 3; ++b) wo->panSrcBands[b] = grey ? 1 : b + 1, wo->panDstBands[b] = b + 1;
    // The image's own alpha band, or its nodata value, says where it has data.
    const int alphaBand = bands == 2 ? 2 : bands >= 4 ? 4 : 0;
    if (alphaBand && GDALGetRasterColorInterpretation(GDALGetRasterBand(src.get(), alphaBand)) == GCI_AlphaBand)
        wo->nSrcAlphaBand = alphaBand;
    int hasNoData = 0;
    const double noData = GDALGetRasterNoDataValue(GDALGetRasterBand(src.get(), 1), &hasNoData);
    if (hasNoData && !wo->nSrcAlphaBand) {
        wo->padfSrcNoDataReal = static_cast<double*>(CPLMalloc(3 * sizeof(double)));
        for (int b = 0; b < 3; ++b) wo->padfSrcNoDataReal[b] = noData;
        wo->papszWarpOptions = CSLSetNameValue(wo->papszWarpOptions, "UNIFIED_SRC_NODATA", "YES");
    }
    wo->nDstAlphaBand = 4;
    wo->eResampleAlg = GRA_Bilinear;
    wo->papszWarpOptions = CSLSetNameValue(wo->papszWarpOptions, "INIT_DEST", "0");
    constexpr double kMaxErrorPixels = 0.01;
    if (warpOntoNet(wo, chain, kMaxErrorPixels, {}, cols, rows) != CE_None) {
        diags.error(fileLoc, fmt::format("GDAL could not resample texture.image onto the surface: {}",
                                         CPLGetLastErrorMsg()));
        return std::nullopt;
    }
    ImageOnGrid out;
    out.attribution = rasterCredit(src.get());
    out.rows = rows;
    out.cols = cols;
    const size_t n = static_cast<size_t>(rows) * cols;
    std::vector<std::uint8_t> band(n);
    out.rgb.resize(3 * n);
    out.covered.resize(n);
    for (int b = 0; b < 4; ++b) {
        if (GDALRasterIO(GDALGetRasterBand(dst.get(), b + 1), GF_Read, 0, 0, cols, rows, band.data(), cols, rows,
                         GDT_Byte, 0, 0) != CE_None) {
            diags.error(fileLoc, "reading the resampled image back failed");
            return std::nullopt;
        }
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
    if (out.coveredCount == 0) {
        diags.error(fileLoc, "texture.image does not cover the terrain: check that it shows the same place (and its "
                             "CRS)");
        return std::nullopt;
    }
    return out;
}

}  // namespace relief::geo
