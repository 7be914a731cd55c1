#pragma once
// GDAL, set up once for the whole process for untrusted scenes: a scene must
// never make relief read a file it does not name, nor reach the network
// (docs/security.md). GDAL 3.6 has no switch for either, so:
//  - only the drivers of kGdalDrivers are registered (no web services, no
//    formats that pull in other files, such as netCDF/HDF5 external links);
//  - a VRT is read only after relief has checked it (vrtProblem): its sources
//    are plain files in its own folder, no raw or derived bands, no warped
//    or pansharpened datasets, no PROJ strings that name files;
//  - GDAL's network paths go nowhere (a proxy on a closed loopback port, no
//    /vsicurl/ file names allowed, no cloud metadata probes) and PROJ's
//    network is off;
//  - CRS text from a scene is read without files or network (crsFromText,
//    geo/gdal_crs.h, the one header here that speaks GDAL's types);
//  - the files GDAL reads beside a dataset, or inside an archive it opens
//    (a .shp.zip), are checked before it opens the dataset (gdalInputProblem);
//  - GDAL's own messages never reach the terminal: relief words its errors.
#include <cstdint>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace relief::geo {

/// Registers the allowed drivers and sets the configuration above, once
/// (safe to call from any thread, any number of times).
void setUpGdal();

/// The names in a raster's folder: GDAL is given those beside the raster
/// (its sibling files) instead of listing the folder itself, so that it sees
/// exactly the files the check beside it has checked; and a folder of tiles
/// is listed once, not once a tile by GDAL and again by the check (n^2
/// directory entries).
class FolderNames {
public:
    explicit FolderNames(const std::filesystem::path& folder);
    /// The folder of the file `path`.
    static FolderNames of(const std::filesystem::path& path);

    /// Whether the folder could be listed (a folder one may enter but not read cannot).
    bool listed() const { return listed_; }
    /// In byte order; empty when the folder cannot be read.
    const std::vector<std::string>& sorted() const { return names_; }
    /// The names beside the file `name` that GDAL may read with it: its own,
    /// and those that start with its stem and a dot, in any case (dem.tif.ovr,
    /// DEM.TFW, dem.prj for dem.tif), as GDAL looks for them.
    std::vector<std::string> beside(const std::string& name) const;

private:
    bool listed_ = false;
    std::vector<std::string> names_;
    std::vector<std::pair<std::string, size_t>> lowered_;  ///< names in lower case, sorted, and where in names_
};

/// What GDAL is given as the sibling files of the file `name` in `folder`
/// (FolderNames::beside), and the null-terminated list of them that GDAL's
/// identify and open take.
class SiblingFiles {
public:
    SiblingFiles(const FolderNames& folder, const std::string& name);
    SiblingFiles(const SiblingFiles&) = delete;  // forGdal points into names
    SiblingFiles& operator=(const SiblingFiles&) = delete;

    const std::vector<std::string>& names() const { return names_; }
    const char* const* forGdal() const { return list_.data(); }

private:
    std::vector<std::string> names_;
    std::vector<const char*> list_;
};

/// The most bytes a file beside a dataset may have when GDAL reads it whole
/// (a .prj, .cpg, world file, ENVI or EHdr header, .aux.xml or other
/// metadata: a few kB in use), in a folder or inflated from an archive.
inline constexpr std::uintmax_t kMaxSideTextBytes = 16'000'000;
/// What GDAL may inflate from an archive it opens as a dataset (a .shp.zip or
/// .shz), all its files together, and how many files it may hold.
inline constexpr std::uintmax_t kMaxArchiveBytes = 1'000'000'000;
inline constexpr int kMaxArchiveFiles = 1000;

/// What a scene asks GDAL to open a file as.
enum class DatasetKind { Raster, Vector };

/// Why GDAL must not open `path` for a scene as `kind`, as the end of a sentence, or "": it is not a regular file
/// (inputFileProblem), or "it is a VRT, and it holds ..." a file outside its
/// folder, a network or virtual path, or a raw, derived, warped or
/// pansharpened band or dataset; or a file beside it that GDAL would read
/// with it is not a plain file, or is too big to be read whole; or it is an
/// archive (.zip, .shz) whose files inflate past what they declare or the
/// caps above. `siblings`: the names in `path`'s folder, listed here when not
/// given.
std::string gdalInputProblem(const std::filesystem::path& path, const FolderNames* siblings = nullptr,
                             DatasetKind kind = DatasetKind::Raster);

}  // namespace relief::geo
