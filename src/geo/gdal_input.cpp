// What GDAL may open for a scene (gdal_setup.h): the named file, checked, and
// the files beside it or in it (an archive), checked; a VRT only if it is made
// of elements that name nothing but plain files in its own folder.
#include "geo/gdal_setup.h"

#include <algorithm>
#include <cctype>
#include <memory>
#include <optional>
#include <set>
#include <string_view>
#include <vector>

#include <cpl_error.h>
#include <cpl_minixml.h>
#include <cpl_string.h>
#include <cpl_vsi.h>
#include <gdal.h>
#include <fmt/format.h>

#include "core/input_file.h"
#include "core/text_escape.h"

namespace relief::geo {

namespace {

namespace fs = std::filesystem;

bool sameWord(std::string_view a, std::string_view b) {  // as GDAL's EQUAL: letters in any case
    return a.size() == b.size() &&
           std::equal(a.begin(), a.end(), b.begin(), [](char x, char y) { return std::tolower(x) == std::tolower(y); });
}

// The elements of a VRT of sources, and nothing else: GDAL reads element names
// in any case, so they are compared so too. Not here, hence refused: Overview
// and MaskBand (datasets of their own), OpenOptions (ROOT_PATH moves where a
// nested VRT's sources resolve), KernelFilteredSource, GDALWarpOptions,
// pansharpening, pixel functions.
constexpr std::string_view kVrtElements[] = {
    "VRTDataset", "SRS", "GeoTransform", "GCPList", "GCP", "Metadata", "MDI", "VRTRasterBand", "ColorInterp",
    "NoDataValue", "HideNoDataValue", "ColorTable", "Entry", "Description", "UnitType", "Offset", "Scale",
    "CategoryNames", "Category", "OverviewList", "SimpleSource", "ComplexSource", "AveragedSource",
    "SourceFilename", "SourceBand", "SourceProperties", "SrcRect", "DstRect", "NODATA", "ScaleOffset", "ScaleRatio",
    "LUT", "UseMaskBand", "ColorTableComponent", "Exponent", "SrcMin", "SrcMax", "DstMin", "DstMax",
};

struct XmlDeleter {
    void operator()(CPLXMLNode* n) const { CPLDestroyXMLNode(n); }
};

// An attribute's value, and whether the element has it.
std::optional<std::string> attribute(const CPLXMLNode* element, std::string_view name) {
    for (const CPLXMLNode* c = element->psChild; c; c = c->psNext)
        if (c->eType == CXT_Attribute && c->pszValue && sameWord(c->pszValue, name))
            return c->psChild && c->psChild->pszValue ? c->psChild->pszValue : "";
    return std::nullopt;
}

std::vector<std::string> texts(const CPLXMLNode* element) {
    std::vector<std::string> out;
    for (const CPLXMLNode* c = element->psChild; c; c = c->psNext)
        if (c->eType == CXT_Text && c->pszValue) out.emplace_back(c->pszValue);
    return out;
}

// GDAL's own test for a VRT, a little wider: "<VRTDataset" in the first
// bytes, in any case.
bool looksLikeVrt(const fs::path& path) {
    std::string problem;
    auto head = readInputHead(path, 1024, problem);
    if (!head) return false;
    return asciiLower(*head).find("<vrtdataset") != std::string::npos;
}

// The VRTs being checked (the chain from the scene's down) and those found
// good: each file is read once, however many sources name it, and a VRT that
// names itself is refused.
struct VrtWalk {
    std::vector<fs::path> chain;
    std::set<fs::path> good;
};
constexpr size_t kMaxVrtDepth = 4;
constexpr std::uintmax_t kMaxVrtBytes = 16'000'000;

std::string vrtProblem(const fs::path& vrt, VrtWalk& walk);

// A source a VRT names: a plain file in the VRT's folder (or below), which may be a VRT itself.
std::string sourceProblem(const CPLXMLNode* element, const fs::path& vrt, VrtWalk& walk) {
    const auto parts = texts(element);
    if (parts.size() != 1 || parts[0].empty()) return "a source whose file name is not one plain text";
    const std::string& name = parts[0];
    const std::string shown = printableExcerpt(name, 80);
    if (name.starts_with("/vsi") || name.find("://") != std::string::npos || name.find(':') != std::string::npos ||
        name.find('<') != std::string::npos)
        return fmt::format("the source \"{}\", which is not a plain file name (no virtual, network or driver paths)",
                           shown);
    // GDAL reads relativeToVRT with atoi: only the plain 0 and 1 mean the same to both.
    const auto relativeTo = attribute(element, "relativeToVRT").value_or("0");
    if (relativeTo != "0" && relativeTo != "1")
        return fmt::format("the source \"{}\" with relativeToVRT=\"{}\" (write 0 or 1)", shown,
                           printableExcerpt(relativeTo, 20));
    std::error_code ec;
    const fs::path folder = fs::absolute(vrt, ec).parent_path();
    const fs::path resolved = fs::weakly_canonical(relativeTo == "1" ? folder / name : fs::absolute(name, ec), ec);
    if (!pathInside(resolved, folder)) return fmt::format("the source \"{}\", a file outside the VRT's folder", shown);
    if (std::string problem = inputFileProblem(resolved); !problem.empty())
        return fmt::format("the source \"{}\" ({})", shown, problem);
    if (walk.good.count(resolved) || !looksLikeVrt(resolved)) return "";
    if (std::find(walk.chain.begin(), walk.chain.end(), resolved) != walk.chain.end())
        return fmt::format("the source \"{}\", a VRT that leads back to itself", shown);
    if (walk.chain.size() >= kMaxVrtDepth) return fmt::format("VRTs nested more than {} deep", kMaxVrtDepth);
    if (std::string problem = vrtProblem(resolved, walk); !problem.empty())
        return fmt::format("the source \"{}\", a VRT: {}", shown, problem);
    return "";
}

// Why an element is not one of a plain VRT's, or "".
std::string elementProblem(const CPLXMLNode* e, const fs::path& vrt, VrtWalk& walk) {
    const std::string name = e->pszValue ? e->pszValue : "";
    if (std::none_of(std::begin(kVrtElements), std::end(kVrtElements), [&](auto k) { return sameWord(k, name); }))
        return fmt::format("a <{}> element, which relief does not read in a scene's VRT", printableExcerpt(name, 40));
    const std::string subClass = attribute(e, "subClass").value_or("");
    if (sameWord(name, "VRTDataset") && !subClass.empty())
        return fmt::format("a {} (relief reads plain VRTs of sources only)", printableExcerpt(subClass, 40));
    if (sameWord(name, "VRTRasterBand") && sameWord(subClass, "VRTRawRasterBand"))
        return "a VRTRawRasterBand, which reads the raw bytes of any file";
    if (sameWord(name, "VRTRasterBand") && !subClass.empty() && !sameWord(subClass, "VRTSourcedRasterBand"))
        return fmt::format("a {} (relief reads bands of sources only)", printableExcerpt(subClass, 40));
    if (sameWord(name, "Metadata") && sameWord(attribute(e, "domain").value_or(""), "OVERVIEWS"))
        return "overviews in another file (metadata domain OVERVIEWS)";
    if (sameWord(name, "MDI") && sameWord(attribute(e, "key").value_or(""), "OVERVIEW_FILE"))
        return "an OVERVIEW_FILE, which names another dataset";
    if (sameWord(name, "SourceFilename")) return sourceProblem(e, vrt, walk);
    if (sameWord(name, "SRS")) {
        std::string crs;
        for (const auto& t : texts(e)) crs += t;
        for (std::string_view word : {"+init", "nadgrids", "geoidgrids", "+grids"})
            if (crs.find(word) != std::string::npos) return fmt::format("an SRS with {}, which makes PROJ read a file", word);
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

// The side files GDAL reads whole (CSLLoad, CPLParseXMLFile, VSIIngestFile):
// a CRS, a shapefile's code page, a raster's header or statistics or colours,
// metadata (.aux.xml and the imagery vendors' .xml, .imd, .rpb, .pvl), a
// CSV's column types. The others (.dbf, .shx, .qix, .ovr, .msk, a
// GeoPackage's -wal, ...) it reads a piece at a time, as it needs them.
constexpr std::string_view kReadWholeSuffixes[] = {".prj", ".cpg", ".xml", ".hdr", ".stx", ".clr", ".csvt",
                                                  ".rdc", ".sgrd", ".imd", ".rpb", ".pvl", ".wld"};

// A world file of the dataset `mainName`, as GDAL looks for one: for dem.tif,
// dem.tfw (the extension's first and last letters and a w) or dem.tifw.
bool isWorldFileOf(const std::string& mainName, const std::string& sideName) {
    const std::string main = asciiLower(mainName), side = asciiLower(sideName);
    const size_t dot = main.rfind('.');
    if (dot == std::string::npos || dot + 1 == main.size()) return false;
    const std::string ext = main.substr(dot + 1);
    return side.ends_with(fmt::format(".{}{}w", ext.front(), ext.back())) || side.ends_with("." + ext + "w");
}

bool readWhole(const std::string& mainName, const std::string& sideName) {
    const std::string side = asciiLower(sideName);
    return std::any_of(std::begin(kReadWholeSuffixes), std::end(kReadWholeSuffixes),
                       [&](std::string_view suffix) { return side.ends_with(suffix); }) ||
           isWorldFileOf(mainName, sideName);
}

constexpr std::string_view kRemoveOrReplace = "remove it, or put the real file there";

// A file GDAL would read with `mainName`: a regular file (a FIFO would block
// GDAL, a link to /dev/zero fill memory), within kMaxSideTextBytes when GDAL
// reads it whole, and checked as a VRT when it is one.
std::string sideFileProblem(const fs::path& file, const std::string& mainName) {
    const std::string name = file.filename().string(), shown = printableExcerpt(name, 80);
    if (std::string problem = inputFileProblem(file); !problem.empty())
        return fmt::format("the file beside it that GDAL would read with it, {}, is not a plain file ({}); {}", shown,
                           problem, kRemoveOrReplace);
    if (readWhole(mainName, name))
        if (std::string problem = inputFileProblem(file, kMaxSideTextBytes); !problem.empty())
            return fmt::format("the file beside it that GDAL would read whole with it, {}: {}; {}", shown, problem,
                               kRemoveOrReplace);
    VrtWalk walk;
    if (looksLikeVrt(file))
        if (std::string problem = vrtProblem(file, walk); !problem.empty())
            return fmt::format("the file beside it that GDAL would read with it, {}, is a VRT, and {}", shown, problem);
    return "";
}

// GDAL opens files beside a dataset by its name (dem.tif.ovr, dem.tif.msk,
// dem.prj, dem.tfw, walk.dbf, walk.cpg, ...): each is checked as above.
std::string sidecarProblem(const fs::path& path, const SiblingFiles& beside) {
    std::error_code ec;
    const fs::path folder = fs::absolute(path, ec).parent_path();
    const std::string name = path.filename().string();
    for (const std::string& other : beside.names()) {
        const fs::path file = folder / other;
        if (other == name || fs::is_directory(file, ec)) continue;
        if (std::string problem = sideFileProblem(file, name); !problem.empty()) return problem;
    }
    return "";
}

struct StringListDeleter {
    void operator()(char** list) const { CSLDestroy(list); }
};

// A file of an archive, as GDAL's /vsizip/ names it, and the size its headers declare.
struct ArchivedFile {
    std::string vsiPath, name;
    std::uintmax_t declaredBytes = 0;
};

// Whether `file` inflates to more bytes than it declares. GDAL 3.6's /vsizip/
// inflates a file until its deflate stream ends, whatever its headers say (a
// file declared 1,000 bytes reads back as 100 MB): only reading tells.
bool inflatesPastDeclared(const ArchivedFile& file) {
    VSILFILE* f = VSIFOpenL(file.vsiPath.c_str(), "rb");
    if (!f) return false;  // GDAL cannot open it either
    std::vector<char> buffer(1 << 16);
    std::uintmax_t inflated = 0;
    while (inflated <= file.declaredBytes) {
        const size_t n = VSIFReadL(buffer.data(), 1, buffer.size(), f);
        if (n == 0) break;
        inflated += n;
    }
    VSIFCloseL(f);
    return inflated > file.declaredBytes;
}

// The files at the top of the archive `root` (a /vsizip/ path; GDAL's
// shapefile driver reads no deeper); nullopt, with `problem` set, when there
// are more than kMaxArchiveFiles or one GDAL reads whole declares more than
// kMaxSideTextBytes.
std::optional<std::vector<ArchivedFile>> archivedFiles(const std::string& root, std::string& problem) {
    const std::unique_ptr<char*, StringListDeleter> names(VSIReadDirEx(root.c_str(), kMaxArchiveFiles + 1));
    std::vector<ArchivedFile> files;
    if (!names) return files;  // not an archive GDAL lists, so not one it reads files from
    if (CSLCount(names.get()) > kMaxArchiveFiles) {
        problem = fmt::format("it is an archive of more than {} files: unzip it and name the file to read",
                              kMaxArchiveFiles);
        return std::nullopt;
    }
    for (char** name = names.get(); *name; ++name) {
        ArchivedFile file{root + "/" + *name, printableExcerpt(*name, 80), 0};
        VSIStatBufL st;
        if (VSIStatL(file.vsiPath.c_str(), &st) != 0 || VSI_ISDIR(st.st_mode)) continue;
        file.declaredBytes = static_cast<std::uintmax_t>(st.st_size);
        if (readWhole("", *name) && file.declaredBytes > kMaxSideTextBytes) {
            problem = fmt::format("its file {}, which GDAL reads whole, inflates to {}, more than the {} such a file "
                                  "may be; remove it from the archive, or give the real files",
                                  file.name, byteSize(file.declaredBytes), byteSize(kMaxSideTextBytes));
            return std::nullopt;
        }
        files.push_back(std::move(file));
    }
    return files;
}

// What the files of an archive declare, held to kMaxArchiveBytes before
// anything is inflated; then each inflated once, to one buffer past what it
// declares at most, to show that it holds no more.
std::string inflationProblem(const std::vector<ArchivedFile>& files) {
    std::uintmax_t declared = 0;
    for (const auto& f : files) declared += f.declaredBytes;
    if (declared > kMaxArchiveBytes)
        return fmt::format("its files inflate to {}, more than the {} relief lets GDAL inflate from an archive: "
                           "unzip it and name the file to read",
                           byteSize(declared), byteSize(kMaxArchiveBytes));
    for (const auto& f : files)
        if (inflatesPastDeclared(f))
            return fmt::format("its file {} inflates to more than the {} it declares: the archive is damaged or "
                               "forged; give the real files",
                               f.name, byteSize(f.declaredBytes));
    return "";
}

// An archive GDAL opens as a dataset (a shapefile's .shp.zip or .shz), read
// through GDAL's own /vsizip/, as GDAL will read it.
std::string archiveProblem(const fs::path& path) {
    std::error_code ec;
    const std::string root = "/vsizip/" + fs::absolute(path, ec).string();
    CPLPushErrorHandler(CPLQuietErrorHandler);
    std::string problem;
    if (const auto files = archivedFiles(root, problem)) problem = inflationProblem(*files);
    CPLPopErrorHandler();
    return problem;
}

// GDAL's shapefile driver opens a .shp.zip or .shz as the archive it is; its
// raster drivers open no archive by its name (3.6).
bool isArchiveName(const fs::path& path) {
    const std::string name = asciiLower(path.filename().string());
    return name.ends_with(".zip") || name.ends_with(".shz");
}

}  // namespace

FolderNames::FolderNames(const fs::path& folder) {
    std::error_code ec;
    for (auto it = fs::directory_iterator(folder, ec); !ec && it != fs::directory_iterator(); it.increment(ec))
        names_.push_back(it->path().filename().string());
    listed_ = !ec;
    std::sort(names_.begin(), names_.end());
    for (size_t i = 0; i < names_.size(); ++i) lowered_.emplace_back(asciiLower(names_[i]), i);
    std::sort(lowered_.begin(), lowered_.end());
}

FolderNames FolderNames::of(const fs::path& path) {
    std::error_code ec;
    return FolderNames(fs::absolute(path, ec).parent_path());
}

std::vector<std::string> FolderNames::beside(const std::string& name) const {
    const std::string own = asciiLower(name), prefix = own.substr(0, own.find('.')) + ".";
    std::vector<std::string> out;
    for (auto it = std::lower_bound(lowered_.begin(), lowered_.end(), std::make_pair(prefix, size_t{0}));
         it != lowered_.end() && it->first.starts_with(prefix); ++it)
        out.push_back(names_[it->second]);
    if (std::find(out.begin(), out.end(), name) == out.end()) out.push_back(name);
    return out;
}

SiblingFiles::SiblingFiles(const FolderNames& folder, const std::string& name) : names_(folder.beside(name)) {
    for (const std::string& n : names_) list_.push_back(n.c_str());
    list_.push_back(nullptr);
}

std::string gdalInputProblem(const fs::path& path, const FolderNames* siblings, DatasetKind kind) {
    if (std::string problem = inputFileProblem(path); !problem.empty()) return problem;
    setUpGdal();
    if (kind == DatasetKind::Vector && isArchiveName(path))
        if (std::string problem = archiveProblem(path); !problem.empty()) return problem;
    std::optional<FolderNames> listedHere;
    const FolderNames& names = siblings ? *siblings : listedHere.emplace(FolderNames::of(path));
    const SiblingFiles beside(names, path.filename().string());
    CPLPushErrorHandler(CPLQuietErrorHandler);
    GDALDriverH driver = GDALIdentifyDriverEx(path.c_str(), kind == DatasetKind::Vector ? GDAL_OF_VECTOR : GDAL_OF_RASTER,
                                              nullptr, beside.forGdal());
    CPLPopErrorHandler();
    if ((driver && std::string_view(GDALGetDriverShortName(driver)) == "VRT") || looksLikeVrt(path)) {
        VrtWalk walk;
        if (const std::string problem = vrtProblem(path, walk); !problem.empty()) return "it is a VRT, and " + problem;
    }
    if (!driver) return "";  // a file GDAL does not take for a dataset of that kind brings no sidecars
    // Told of no side file, GDAL would lose a .prj or a .tfw without a word; left to look for them
    // by name, it would read them unchecked.
    if (!names.listed())
        return "its folder cannot be listed, so the files GDAL reads beside it (.prj, .tfw, .ovr, .dbf, ...) cannot "
               "be checked: let relief read the folder (chmod +r), or copy the file and its side files elsewhere";
    return sidecarProblem(path, beside);
}

}  // namespace relief::geo
