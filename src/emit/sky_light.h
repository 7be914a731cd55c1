#pragma once
// render.quality = "high": light from the whole sky, as a terrain
// visualisation gives it. Each node's colour is multiplied by the share of
// the sky it sees (geo/sky_view.h), computed from the refined grid relief
// renders, so that gullies are darker than the ridges beside them whatever
// the sun does. A mesh2 colours its vertices from a texture list, so the
// lit colours are quantized there (kSkyLightLevels); a drape PNG carries
// them exactly.
#include "emit/mesh.h"
#include "geo/sky_view.h"

namespace relief::emit {

/// Steps of the sky light in a mesh2's texture list: 1/128, below the
/// 8-bit still's own step where the light is full.
inline constexpr int kSkyLightLevels = 128;

/// Sets where.skyLight to every node's sky-view factor over `refined`.
void addSkyLight(ScenePlacement& where, const geo::GeoGrid& refined, const geo::SkyViewOptions& options);

/// With where.skyLight, where.fills or where.fade set: gives `mesh` its own
/// texture list (Mesh::litTexture, litColours): each node's palette colour with
/// its fill, fade and sky light (nodeColour), the light quantized to kSkyLightLevels, the
/// entries in the order the nodes first use them.
void nodeTextures(Mesh& mesh);

}  // namespace relief::emit
