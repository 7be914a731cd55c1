#include "geo/gdal_crs.h"
#include "geo/gdal_setup.h"

#include <algorithm>
#include <cerrno>
#include <mutex>
#include <vector>
#include <string_view>

#include <cpl_conv.h>
#include <cpl_error.h>
#include <cpl_string.h>
#include <cpl_vsi_virtual.h>
#include <gdal.h>
#include <ogr_spatialref.h>
#include <fmt/format.h>


namespace relief::geo {

namespace {


// The drivers a scene may use: raster DEMs and images that are one file (or a
// file and sidecars named after it), and GDAL's in-memory drivers, which
// relief itself uses. Everything else (web services, databases, containers
// that can link to other files: netCDF/HDF5 external links, ERDAS Imagine's
// spill and dependent files, ER Mapper's DataFile, whose names its header
// gives) is deregistered, so that not even a source inside a VRT can reach it.
constexpr std::string_view kGdalDrivers[] = {
    "GTiff",
    "VRT",
    "MEM",
    "Memory",  // GeoTIFF, checked VRTs; relief's own rasters and contour layers
    "AAIGrid",
    "GRASSASCIIGrid",
    "SRTMHGT",
    "DTED",
    "USGSDEM",
    "BT",  // DEM formats
    "EHdr",
    "ENVI",
    "SAGA",
    "RST",
    "GSAG",
    "GSBG",
    "GS7BG",
    "Leveller",
    "Terragen",
    "HF2",
    "PNG",
    "JPEG",
    "GIF",
    "WEBP",
    "JP2OpenJPEG",  // images to drape
    // Vector files (tracks, layers); no driver that fetches linked documents (LIBKML, GML, WFS).
    "GPX",
    "GeoJSON",
    "GeoJSONSeq",
    "KML",
    "ESRI Shapefile",
    "GPKG",
    "FlatGeobuf",
    "CSV",
};

// Network paths and services lead nowhere: GDAL 3.6 has no switch to turn
// its network off, so besides the file systems of closeNetworkFileSystems,
// its HTTP traffic goes to a proxy on a loopback port nothing listens on,
// /vsicurl/ and its kin accept no file name, and the cloud handlers do not
// probe a metadata service.
constexpr std::pair<const char*, const char*> kGdalConfig[] = {
    {"GDAL_HTTP_PROXY", "127.0.0.1:9"},
    {"GDAL_HTTPS_PROXY", "127.0.0.1:9"},
    {"GDAL_HTTP_CONNECTTIMEOUT", "1"},
    {"GDAL_HTTP_TIMEOUT", "1"},
    {"CPL_VSIL_CURL_ALLOWED_FILENAME", "/relief-allows-no-network-file"},
    {"CPL_AWS_AUTODETECT_EC2", "NO"},
    {"AWS_NO_SIGN_REQUEST", "YES"},
    {"GDAL_VRT_ENABLE_PYTHON", "NO"},
    // A .aux.xml beside a raster can name any dataset as its overviews (OVERVIEW_FILE).
    {"GDAL_PAM_ENABLED", "NO"},
    {"GDAL_HTTP_UNSAFESSL", "NO"},
};

// A file system that has no files: installed for every network prefix of
// GDAL's (/vsicurl/, /vsis3/, ...), so that no path reaches the network
// whatever GDAL's configuration says.
class NoNetworkFiles final : public VSIFilesystemHandler {
public:
    VSIVirtualHandle* Open(const char*, const char*, bool, CSLConstList) override {
        errno = ENOENT;
        return nullptr;
    }
    int Stat(const char*, VSIStatBufL*, int) override {
        errno = ENOENT;
        return -1;
    }
};

constexpr std::string_view kNetworkPrefixes[] = {"/vsicurl", "/vsis3", "/vsigs", "/vsiaz", "/vsiadls",
                                                 "/vsioss", "/vsiswift", "/vsiwebhdfs", "/vsihdfs"};

void closeNetworkFileSystems() {
    char** prefixes = VSIFileManager::GetPrefixes();
    std::vector<std::string> network;
    for (char** p = prefixes; p && *p; ++p) {
        const std::string_view prefix = *p;
        if (std::any_of(std::begin(kNetworkPrefixes), std::end(kNetworkPrefixes),
                        [&](std::string_view n) { return prefix.starts_with(n); }))
            network.emplace_back(prefix);
    }
    CSLDestroy(prefixes);
    // GDAL owns the handlers in its table and deletes them when it is cleaned up, but installing
    // over a prefix forgets the handler that was there; keep those, never used again, in reach
    // (through a pointer no destructor clears, since the leak check runs after static destructors).
    static auto* replaced = new std::vector<VSIFilesystemHandler*>;
    for (const auto& prefix : network) {
        replaced->push_back(VSIFileManager::GetHandler(prefix.c_str()));
        VSIFileManager::InstallHandler(prefix, new NoNetworkFiles);
    }
}

void registerAllowedDrivers() {
    GDALAllRegister();
    for (int i = GDALGetDriverCount() - 1; i >= 0; --i) {
        GDALDriverH driver = GDALGetDriver(i);
        const std::string_view name = GDALGetDriverShortName(driver);
        if (std::find(std::begin(kGdalDrivers), std::end(kGdalDrivers), name) == std::end(kGdalDrivers)) {
            GDALDeregisterDriver(driver);
            GDALDestroyDriver(driver);
        }
    }
}

}  // namespace

void setUpGdal() {
    static std::once_flag once;
    std::call_once(once, [] {
        for (const auto& [key, value] : kGdalConfig) CPLSetConfigOption(key, value);
        // Errors are relief's to word, on one line; GDAL's go nowhere.
        CPLSetErrorHandler(CPLQuietErrorHandler);
        OSRSetPROJEnableNetwork(FALSE);
        registerAllowedDrivers();
        closeNetworkFileSystems();
    });
}

bool crsFromText(OGRSpatialReferenceH srs, const std::string& crs, std::string& problem) {
    setUpGdal();
    for (std::string_view word : {"+init", "nadgrids", "geoidgrids", "+grids", "://"})
        if (crs.find(word) != std::string::npos) {
            problem = fmt::format("holds \"{}\", which would make relief read a file or the network; give an "
                                  "EPSG code or WKT",
                                  word);
            return false;
        }
    CPLPushErrorHandler(CPLQuietErrorHandler);
    const OGRErr err = OGRSpatialReference::FromHandle(srs)->SetFromUserInput(
        crs.c_str(), OGRSpatialReference::SET_FROM_USER_INPUT_LIMITATIONS_get());
    CPLPopErrorHandler();
    if (err != OGRERR_NONE) {
        problem = "is not a CRS GDAL knows (without reading files or the network); write e.g. \"EPSG:2193\"";
        return false;
    }
    return true;
}

}  // namespace relief::geo
