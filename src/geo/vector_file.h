#pragma once
// A vector file a scene names (GPX, GeoJSON, KML, Shapefile, GeoPackage,
// FlatGeobuf, CSV with coordinates: the vector drivers gdal_setup.h allows),
// read by GDAL/OGR in whatever CRS it declares and given back in WGS84.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "core/diagnostics.h"
#include "core/types.h"

namespace relief::geo {

/// The vertices of the first line in `path` (a LineString, or a
/// MultiLineString's first part) of the layer named `layer`, or of the first
/// layer holding one when `layer` is "", as WGS84 lon, lat and the file's z
/// (0 without one). A file without a CRS is taken as lon, lat. Nullopt, after
/// an error at `at` naming the file (and its layers), when GDAL cannot read it,
/// the layer does not exist, or no line is there.
std::optional<std::vector<GeoPoint>> firstLineOf(const std::filesystem::path& path, const std::string& layer,
                                                 const SourceLoc& at, Diagnostics& diags);

}  // namespace relief::geo
