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
//  - GDAL's own messages never reach the terminal: relief words its errors.
#include <filesystem>
#include <string>

namespace relief::geo {

/// Registers the allowed drivers and sets the configuration above, once
/// (safe to call from any thread, any number of times).
void setUpGdal();

/// Why GDAL must not open `path` for a scene, as the end of a sentence, or
/// "": it is not a regular file (inputFileProblem), or "it is a VRT, and it
/// holds ..." a file outside its folder, a network or virtual path, or a raw,
/// derived, warped or pansharpened band or dataset.
std::string gdalInputProblem(const std::filesystem::path& path);

}  // namespace relief::geo
