#pragma once
// Inside geo: adjacent DEM tiles ([samples] path = [...]) as one raster, a VRT
// GDAL builds in memory (gdalbuildvrt's defaults), so that the net is
// warped from the tiles as from one file: no seam where they meet.
#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

#include "core/diagnostics.h"
#include "geo/raster_source.h"

namespace relief::geo {

/// The most tiles a scene may mosaic (a list, or a folder).
inline constexpr size_t kMaxTiles = 10000;

/// The raster tiles in `folder` ([samples] path = "tiles/"): its files that
/// GDAL takes for rasters (isRasterDem), in the order of their names; not its
/// subfolders, hidden files, or GDAL's side files of another raster (.ovr
/// overviews, .msk masks, .aux.xml). Empty, with `problem` saying why, when
/// there is none or more than kMaxTiles.
std::vector<std::filesystem::path> rasterTilesIn(const std::filesystem::path& folder, std::string& problem);

/// The tiles mosaicked: each opened as openRaster opens one (checked first),
/// all in one CRS (else an error naming two that differ), the VRT's nodata
/// the tiles' (NaN for floating-point tiles that declare none, so that a gap
/// between tiles is no data, not 0 m). A warning when the tiles cover less
/// than their bounding box (a tile missing). Null after an error at `at`.
Dataset mosaicOf(const std::vector<std::filesystem::path>& tiles, const SourceLoc& at, Diagnostics& diags);

}  // namespace relief::geo
