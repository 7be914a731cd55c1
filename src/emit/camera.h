#pragma once
// The camera model, as POV-Ray's camera sees the scene: where relief puts the
// camera (on an orbit fitted to the terrain, or at a geographic eye), and
// where a scene point lands in the still. The SDL writer (write_scene.h)
// writes this camera; annotate/ draws on the still it sees.
#include <array>
#include <optional>

#include "core/diagnostics.h"
#include "core/types.h"
#include "emit/mesh.h"
#include "scene/scene_spec.h"

namespace relief::emit {

/// The unit vector, in scene axes, towards compass bearing `azimuthDeg` at
/// `altitudeDeg` above the horizon: where the camera's orbit puts the eye,
/// and where the sun's light comes from.
SceneVec3 sceneDirection(double azimuthDeg, double altitudeDeg);

/// Where relief puts the camera: on an orbit around the terrain's centre at
/// the scene's azimuth and elevation, at the scene's distance or the nearest
/// that keeps the terrain's bounding box in view (scene units and axes).
struct CameraView {
    SceneVec3 eye, target;
    SceneVec3 right, up;    ///< unit vectors of the image's x (to the right) and y (up)
    double radius = 0;      ///< of the bounding box
    double aspect = 1;      ///< width / height
    double tanHalfFov = 0;  ///< horizontal
    bool perspective = true;  ///< from one point (a pinhole, a panorama, a sphere), not parallel
    double orthoHeight = 0; ///< orthographic: the view's height
    /// Panoramic or spherical: the image is no pinhole's (projectToImage does
    /// not apply), and tanHalfFov is half the angle across it, in radians, so
    /// that 2 d tanHalfFov / width is still a pixel's footprint at distance d.
    bool wide = false;
};
/// A camera placed by geography ([camera] position and look_at), in the
/// frame's metres: the eye, and the point it looks at (unset: the terrain's
/// centre). Both unset: on the orbit.
struct CameraPoints {
    std::optional<Vec3> eyeM, targetM;
};
/// [camera] position and look_at in `frame`'s metres; nullopt, after an
/// error at the key, when one cannot be placed there or both are one point.
std::optional<CameraPoints> cameraPointsInFrame(const scene::CameraSpec& camera, const geo::Frame& frame,
                                                Diagnostics& diags);
/// Pixels of the still the terrain's outline keeps clear of (left, top,
/// right, bottom): a framed map's annotations and furniture. All zero: a
/// margin of 4 % of the half-frame on its widest side.
using FrameInsetPx = std::array<double, 4>;
CameraView placeCamera(const ScenePlacement& where, const scene::CameraSpec& camera, const CameraPoints& points,
                       const scene::RenderSpec& render, const FrameInsetPx& insetPx = {});
/// The orbit camera of a look (no camera points): for tests and tools.
inline CameraView placeCamera(const ScenePlacement& where, const scene::LookSpec& look, const scene::RenderSpec& render) {
    return placeCamera(where, look.camera, {}, render);
}

/// Where a scene point lands in a still `widthPx` x `heightPx` as POV-Ray
/// draws it: pixels, x to the right, y down, (0, 0) the top-left corner.
std::array<double, 2> projectToImage(const CameraView& view, const SceneVec3& p, int widthPx, int heightPx);

/// Metres of terrain one pixel of a still `widthPx` wide covers at the
/// terrain's nearest point to the eye (the finest detail the still can show).
double finestMetresPerPixel(const CameraView& view, const ScenePlacement& where, int widthPx);

}  // namespace relief::emit
