#pragma once
// A CRS from a scene, read by GDAL without files or network (gdal_setup.h
// says why). Kept apart from gdal_setup.h: it takes GDAL's own handle type.
#include <string>

#include <ogr_srs_api.h>

namespace relief::geo {

/// A CRS written in a scene ("EPSG:2193", WKT, a PROJ string) into `srs`,
/// without reading a file or the network (no URLs, no +init= or grid files).
/// False with `problem` set when it is refused or unknown (a predicate:
/// "is not a CRS GDAL knows ...").
bool crsFromText(OGRSpatialReferenceH srs, const std::string& text, std::string& problem);

}  // namespace relief::geo
