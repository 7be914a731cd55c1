#include "geo/gdal_crs.h"
#include "geo/gdal_setup.h"

#include <algorithm>
#include <cctype>
#include <memory>
#include <mutex>
#include <set>
#include <vector>
#include <string_view>

#include <cpl_conv.h>
#include <cpl_error.h>
#include <cpl_minixml.h>
#include <gdal.h>
#include <ogr_spatialref.h>
#include <fmt/format.h>

#include "core/input_file.h"
#include "core/text_escape.h"

namespace relief::geo {

namespace {

namespace fs = std::filesystem;

// The drivers a scene may use: raster DEMs and images that are one file (or a
// file and sidecars named after it), and GDAL's in-memory drivers, which
// relief itself uses. Everything else (web services, databases, containers
// that can link to other files) is deregistered, so that not even a source
// inside a VRT can reach it.
constexpr std::string_view kGdalDrivers[] = {
    "GTiff", "VRT",  "MEM",  "Memory",   // GeoTIFF, checked VRTs; relief's own rasters and contour layers
    "AAIGrid", "GRASSASCIIGrid", "SRTMHGT", "DTED", "USGSDEM", "BT", "HFA",  // DEM formats
    "EHdr", "ENVI", "ERS", "SAGA", "RST", "GSAG", "GSBG", "GS7BG", "Leveller", "Terragen", "HF2",
    "PNG", "JPEG", "GIF", "WEBP", "JP2OpenJPEG",  // images to drape
};

// Network paths and services lead nowhere: GDAL 3.6 has no switch to turn
// its network off, so its HTTP traffic goes to a proxy on a loopback port
// nothing listens on, /vsicurl/ and its kin accept no file name, and the
// cloud handlers do not probe a metadata service.
constexpr std::pair<const char*, const char*> kGdalConfig[] = {
    {"GDAL_HTTP_PROXY", "127.0.0.1:9"},
    {"GDAL_HTTPS_PROXY", "127.0.0.1:9"},
    {"GDAL_HTTP_CONNECTTIMEOUT", "1"},
    {"GDAL_HTTP_TIMEOUT", "1"},
    {"CPL_VSIL_CURL_ALLOWED_FILENAME", "/relief-allows-no-network-file"},
    {"CPL_AWS_AUTODETECT_EC2", "NO"},
    {"AWS_NO_SIGN_REQUEST", "YES"},
    {"GDAL_VRT_ENABLE_PYTHON", "NO"},
    {"GDAL_HTTP_UNSAFESSL", "NO"},
};

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

struct XmlDeleter {
    void operator()(CPLXMLNode* n) const { CPLDestroyXMLNode(n); }
};

std::string attribute(const CPLXMLNode* element, std::string_view name) {
    for (const CPLXMLNode* c = element->psChild; c; c = c->psNext)
        if (c->eType == CXT_Attribute && c->pszValue && c->psChild && c->psChild->pszValue) {
            std::string_view n = c->pszValue;
            if (n.size() == name.size() &&
                std::equal(n.begin(), n.end(), name.begin(), [](char a, char b) { return std::tolower(a) == std::tolower(b); }))
                return c->psChild->pszValue;
        }
    return {};
}

std::string text(const CPLXMLNode* element) {
    std::string out;
    for (const CPLXMLNode* c = element->psChild; c; c = c->psNext)
        if (c->eType == CXT_Text && c->pszValue) out += c->pszValue;
    return out;
}

// GDAL's own test: "<VRTDataset" in the first bytes.
bool startsWithVrt(const fs::path& path) {
    std::string problem;
    const auto head = readInputHead(path, 1024, problem);
    return head && head->find("<VRTDataset") != std::string::npos;
}

bool inside(const fs::path& file, const fs::path& folder) {
    auto f = file.begin();
    for (auto d = folder.begin(); d != folder.end(); ++d, ++f)
        if (f == file.end() || *d != *f) return false;
    return true;
}

constexpr size_t kMaxVrtDepth = 4;
constexpr std::uintmax_t kMaxVrtBytes = 16u << 20;

// The VRTs being checked (the chain from the scene's down) and those found good: each
// file is read once, however many sources name it, and a VRT that names itself is refused.
struct VrtWalk {
    std::vector<fs::path> chain;
    std::set<fs::path> good;
};

std::string vrtProblem(const fs::path& vrt, VrtWalk& walk);

// A source a VRT names: a plain file in the VRT's folder (or below), which may be a VRT itself.
std::string sourceProblem(const CPLXMLNode* element, const fs::path& vrt, VrtWalk& walk) {
    const std::string name = text(element);
    const std::string shown = printableExcerpt(name, 80);
    if (name.empty()) return "a source with no file name";
    if (name.starts_with("/vsi") || name.find("://") != std::string::npos || name.find(':') != std::string::npos ||
        name.find('<') != std::string::npos)
        return fmt::format("the source \"{}\", which is not a plain file name (no virtual, network or driver paths)",
                           shown);
    std::error_code ec;
    const fs::path folder = fs::weakly_canonical(fs::absolute(vrt, ec).parent_path(), ec);
    const bool relative = attribute(element, "relativeToVRT") == "1";
    const fs::path resolved = fs::weakly_canonical(relative ? folder / name : fs::absolute(name, ec), ec);
    if (!inside(resolved, folder))
        return fmt::format("the source \"{}\", a file outside the VRT's folder", shown);
    if (std::string problem = inputFileProblem(resolved); !problem.empty())
        return fmt::format("the source \"{}\" ({})", shown, problem);
    if (walk.good.count(resolved) || !startsWithVrt(resolved)) return "";
    if (std::find(walk.chain.begin(), walk.chain.end(), resolved) != walk.chain.end())
        return fmt::format("the source \"{}\", a VRT that leads back to itself", shown);
    if (walk.chain.size() >= kMaxVrtDepth) return fmt::format("VRTs nested more than {} deep", kMaxVrtDepth);
    if (std::string problem = vrtProblem(resolved, walk); !problem.empty())
        return fmt::format("the source \"{}\", a VRT: {}", shown, problem);
    return "";
}

// Elements through which GDAL reads other files or runs code.
std::string elementProblem(const CPLXMLNode* e, const fs::path& vrt, VrtWalk& walk) {
    const std::string_view name = e->pszValue ? e->pszValue : "";
    if (name == "VRTDataset" && !attribute(e, "subClass").empty())
        return fmt::format("a {} (relief reads plain VRTs of sources only)", printableExcerpt(attribute(e, "subClass"), 40));
    if (name == "VRTRasterBand") {
        const std::string sub = attribute(e, "subClass");
        if (sub == "VRTRawRasterBand") return "a VRTRawRasterBand, which reads the raw bytes of any file";
        if (!sub.empty() && sub != "VRTSourcedRasterBand")
            return fmt::format("a {} (relief reads bands of sources only)", printableExcerpt(sub, 40));
    }
    if (name == "SourceFilename") return sourceProblem(e, vrt, walk);
    for (std::string_view other : {"SourceDataset", "DestinationDataset", "DEMPath", "Grids", "PixelFunctionCode"})
        if (name == other) return fmt::format("a <{}> element, which names a dataset or code", other);
    if (name == "SRS") {
        const std::string crs = text(e);
        for (std::string_view word : {"+init", "nadgrids", "geoidgrids", "+grids"})
            if (crs.find(word) != std::string::npos)
                return fmt::format("an SRS with {}, which makes PROJ read a file", word);
    }
    return "";
}

std::string treeProblem(const CPLXMLNode* node, const fs::path& vrt, VrtWalk& walk) {
    for (; node; node = node->psNext) {
        if (node->eType != CXT_Element) continue;
        if (std::string problem = elementProblem(node, vrt, walk); !problem.empty()) return problem;
        if (std::string problem = treeProblem(node->psChild, vrt, walk); !problem.empty()) return problem;
    }
    return "";
}

std::string vrtProblem(const fs::path& vrt, VrtWalk& walk) {
    std::string problem;
    const auto xml = readInputFile(vrt, kMaxVrtBytes, problem);
    if (!xml) return problem;
    CPLPushErrorHandler(CPLQuietErrorHandler);
    std::unique_ptr<CPLXMLNode, XmlDeleter> root(CPLParseXMLString(xml->c_str()));
    CPLPopErrorHandler();
    if (!root) return "it is not well-formed XML";
    std::error_code ec;
    walk.chain.push_back(fs::weakly_canonical(fs::absolute(vrt, ec), ec));
    std::string p = treeProblem(root.get(), vrt, walk);
    if (p.empty()) walk.good.insert(walk.chain.back());
    walk.chain.pop_back();
    return p.empty() ? "" : "it holds " + p;
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
    });
}

std::string gdalInputProblem(const fs::path& path) {
    if (std::string problem = inputFileProblem(path); !problem.empty()) return problem;
    setUpGdal();
    CPLPushErrorHandler(CPLQuietErrorHandler);
    GDALDriverH driver = GDALIdentifyDriverEx(path.c_str(), GDAL_OF_RASTER, nullptr, nullptr);
    CPLPopErrorHandler();
    const bool vrt = (driver && std::string_view(GDALGetDriverShortName(driver)) == "VRT") || startsWithVrt(path);
    if (!vrt) return "";
    VrtWalk walk;
    const std::string problem = vrtProblem(path, walk);
    return problem.empty() ? "" : "it is a VRT, and " + problem;
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
