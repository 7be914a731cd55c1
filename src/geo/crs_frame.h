#pragma once
// Inside geo: a frame in a raster DEM's own projected CRS (FrameKind::Raster),
// whose x and y are the raster's easting and northing, so that its cells need
// no reprojection; carried to and from WGS84 by PROJ through GDAL, as the
// raster's cells are.
#include <string>
#include <string_view>

#include <ogr_srs_api.h>

#include "geo/geo_grid.h"

namespace relief::geo {

/// Whether `srs` can hold a Raster frame: projected, in metres.
bool projectedInMetres(OGRSpatialReferenceH srs);

/// The name of `srs` (or `unnamed`, when it has none) as one line of UTF-8:
/// the file says it, and it goes into the .pov header, the sidecar and relief init.
std::string crsNameOf(OGRSpatialReferenceH srs, std::string_view unnamed);

/// The Raster frame in `srs` (projectedInMetres), named and written as WKT2.
Frame crsFrame(OGRSpatialReferenceH srs);

/// A Raster frame's point to WGS84 longitude and latitude (degrees), and back;
/// false when PROJ cannot. GDAL's transformations may not be shared between
/// threads: each thread makes its own, once per CRS.
bool crsFrameToLonLat(const Frame& frame, double x, double y, double& lonDeg, double& latDeg);
bool lonLatToCrsFrame(const Frame& frame, double lonDeg, double latDeg, double& x, double& y);

}  // namespace relief::geo
