#pragma once
// A vector file a scene names (GPX, GeoJSON, KML, Shapefile, GeoPackage,
// FlatGeobuf, CSV with coordinates: the vector drivers gdal_setup.h allows),
// read by GDAL/OGR in whatever CRS it declares and given back in WGS84.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <gdal.h>

#include "core/diagnostics.h"
#include "core/types.h"
#include "geo/raster_source.h"

namespace relief::geo {

/// `path` opened as a vector dataset (`openOptions`: a null-ended list of
/// NAME=VALUE for the driver); null, after an error at `at` that begins with
/// `shown` and says why (or which formats relief reads), when it cannot be.
Dataset openVectorFile(const std::filesystem::path& path, const std::string& shown, const SourceLoc& at,
                       Diagnostics& diags, const char* const* openOptions = nullptr);

/// The names of `ds`'s layers, quoted, printable and cut to 60 characters
/// each (a file's names are untrusted), comma-separated: "none" when it has none.
std::string layerNamesOf(GDALDatasetH ds);

/// The vertices of the first line in `path` (a LineString, or a
/// MultiLineString's first part) of the layer named `layer`, or of the first
/// layer holding one when `layer` is "", as WGS84 lon, lat and the file's z
/// carried with them (0 without one; in a geocentric CRS, the height above
/// the ellipsoid). A file without a CRS is taken as lon, lat. Nullopt, after
/// an error at `at` naming the file (and its layers), when GDAL cannot read it,
/// the layer does not exist, or no line is there.
std::optional<std::vector<GeoPoint>> firstLineOf(const std::filesystem::path& path, const std::string& layer,
                                                 const SourceLoc& at, Diagnostics& diags);

}  // namespace relief::geo
