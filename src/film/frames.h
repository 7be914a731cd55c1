#pragma once
// A film's frames as scenes: each frame is the scene with a few keys set
// (the keys `relief render --set` takes), computed from [animation]. Input:
// the scene's specs. Output: one FrameSettings a frame, in order.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/date_time.h"
#include "scene/scene_spec.h"

namespace relief::film {

struct FrameSettings {
    int number = 1;                         ///< 1-based, in the film as [animation] frames counts them
    scene::SceneOverrides overrides;        ///< the keys set, as --set takes them (values in TOML's syntax)
    std::optional<OffsetDateTime> sunTime;  ///< animation.sun: the frame's instant
};

/// Every frame of `scene`'s [animation]: the orbit's azimuth (a full turn
/// leaves out its last frame, the first again; a part includes both ends),
/// the sun's instant (both ends included, whole seconds) and its text as the
/// overlay's subtitle, and each varied key eased between its two values
/// (rounded for a key that takes integers).
std::vector<FrameSettings> frameSettings(const scene::SceneSpec& scene);

/// Ease in and out: 0 at 0, 1 at 1, flat at both ends ((1 - cos(pi t)) / 2).
double eased(double t);

/// The keys of these sections change only the view, not the terrain: frames
/// differing in them alone share one compiled terrain.
bool changesOnlyTheView(const std::string& key);

}  // namespace relief::film
