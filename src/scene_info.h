#pragma once
// `relief info`: what relief would do with a scene or a DEM and what it would
// cost, known before doing it (planSurface), as gdalinfo tells a raster.
#include <nlohmann/json.hpp>

#include "pipeline.h"

namespace relief {

/// The data (size, CRS, extent in degrees and metres, elevations, nodata,
/// credit), the frame, the net and why, the depth and why, the geometry,
/// the estimated triangles, memory and .pov size against [limits], and
/// what vertical exaggeration would make the relief show (advice). Every
/// string UTF-8: a name that is not is written with U+FFFD, and `diags` warned.
nlohmann::ordered_json sceneInfo(const LoadedScene& loaded, const Surface& surface, Diagnostics& diags);

/// The same as lines of `key: value`, a blank line between the groups.
std::string sceneInfoText(const nlohmann::ordered_json& info);

}  // namespace relief
