#pragma once
// Inside geo: adjacent DEM tiles ([samples] path = [...]) as one raster, a VRT
// GDAL builds in memory (gdalbuildvrt's defaults), so that the net is
// warped from the tiles as from one file: no seam where they meet.
#include <filesystem>
#include <vector>

#include "core/diagnostics.h"
#include "geo/raster_source.h"

namespace relief::geo {

/// The tiles mosaicked: each opened as openRaster opens one (checked first),
/// all in one CRS (else an error naming two that differ), the VRT's nodata
/// the tiles' (NaN for floating-point tiles that declare none, so that a gap
/// between tiles is no data, not 0 m). A warning when the tiles cover less
/// than their bounding box (a tile missing). Null after an error at `at`.
Dataset mosaicOf(const std::vector<std::filesystem::path>& tiles, const SourceLoc& at, Diagnostics& diags);

}  // namespace relief::geo
