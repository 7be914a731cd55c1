#pragma once
// animation.path = "flyover": each frame's camera.position and camera.look_at,
// from the path (waypoints or a vector file's first line) and the compiled
// terrain's surface (film/flyover.h does the geometry). Errors at the
// [animation] key they come from.
#include <optional>
#include <vector>

#include "core/diagnostics.h"
#include "geo/geo_grid.h"
#include "scene/scene_spec.h"

namespace relief {

/// The keys of the film's frames `frames` (0-based, camera.position and
/// camera.look_at in --set's syntax, in that order) over `surface`; nullopt
/// after an error: the track cannot be read or has no line, a waypoint or
/// track vertex is off the terrain, or one of these frames' eye is at or
/// under the ground.
std::optional<std::vector<scene::SceneOverrides>> flyoverKeys(const scene::AnimationSpec& a,
                                                              const geo::GeoGrid& surface,
                                                              const std::vector<size_t>& frames, Diagnostics& diags);

}  // namespace relief
