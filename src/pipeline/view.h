#pragma once
// Where the terrain sits in POV-Ray's scene, where the camera is and where
// the light comes from: the view, made once for a still (or a frame) and
// read by everything after it (the geometry, the marks, the overlays' facts).
#include <cstdint>
#include <optional>
#include <string>
#include <utility>

#include "core/diagnostics.h"
#include "core/types.h"
#include "emit/camera.h"
#include "emit/write_scene.h"
#include "geo/normalize.h"
#include "geo/sun_position.h"
#include "pipeline/map_frame.h"
#include "scene/scene_spec.h"

namespace relief {

/// Where the light comes from, as the sidecar's "sun" says it: a true
/// bearing and the apparent altitude, computed from [lighting] datetime over
/// the terrain's centre or taken from the scene's angles.
struct SunFacts {
    double azimuthDeg = 0, altitudeDeg = 0;
    bool fromDatetime = false;
    std::string datetime;           ///< as written in the scene
    double lonDeg = 0, latDeg = 0;  ///< where it was computed (fromDatetime)
};

/// Where the terrain sits in the scene, where the camera is and where the
/// light comes from: made once, read by everything after.
struct View {
    emit::ScenePlacement where;  ///< with the layers' fills and the sky light once the terrain is built
    emit::CameraView camera;
    emit::SunDirection sun;
    SunFacts sunRecord;
    /// What a pixel covers where the camera looks (true metres): the scale
    /// bar's, and the width of the lines laid on the surface.
    double metresPerPixel = 0;
    std::optional<MapFrameTicks> frameTicks;  ///< [overlay] frame, whose room the camera left
};

/// The view of `spec` over `surface`; nullopt after an error (a camera point
/// that cannot be placed, the sun below the horizon at lighting.datetime).
std::optional<View> resolveView(const scene::SceneSpec& spec, const geo::ControlNet& net, const geo::GeoGrid& refined,
                                Diagnostics& diags);

/// The sun over the terrain's centre at an instant, and that centre; nullopt
/// when the centre has no longitude and latitude in the net's frame.
std::optional<std::pair<geo::SunPosition, GeoPoint>> sunOverTerrain(const geo::ControlNet& net,
                                                                    std::int64_t utcSeconds);

}  // namespace relief
