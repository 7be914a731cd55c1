#pragma once
// Stage 4 of 6 (part 2). Input: Mesh, LookSpec and RenderSpec. Output: a POV-Ray scene
// (.pov) from templates/scene.pov.in with the mesh as a `mesh2`. The same
// inputs give byte-identical output: every number goes through the
// locale-free writers of core/number_format.h.
#include <array>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "core/diagnostics.h"
#include "emit/mesh.h"
#include "emit/template.h"
#include "scene/scene_spec.h"

namespace relief::emit {

/// Ordered key/value pairs recorded in the .pov header and the JSON sidecar.
using ParameterList = std::vector<std::pair<std::string, std::string>>;

/// Writes `mesh2 { vertex_vectors, normal_vectors, texture_list (the 256-entry
/// palette), face_indices (two triangles per grid quad, counter-clockwise seen
/// from above, each with its three palette indices) }`. Returns bytes written.
/// `progress`, if set, is told the fraction written (0..1), at most ~100 times.
using WriteProgressFn = std::function<void(double fraction)>;
size_t writeMesh2(const Mesh& mesh, std::FILE* out, const WriteProgressFn& progress = {});

/// Where relief puts the camera: on an orbit around the terrain's centre at
/// the scene's azimuth and elevation, at the scene's distance or the nearest
/// that keeps the terrain's bounding box in view (scene units and axes).
struct CameraView {
    Vec3 eye, target;
    Vec3 right, up;         ///< unit vectors of the image's x (to the right) and y (up), scene axes
    double radius = 0;      ///< of the bounding box
    double aspect = 1;      ///< width / height
    double tanHalfFov = 0;  ///< horizontal
    bool perspective = true;
    double orthoHeight = 0; ///< orthographic: the view's height
};
/// A camera placed by geography ([camera] position and look_at), in the
/// frame's metres: the eye, and the point it looks at (unset: the terrain's
/// centre). Both unset: on the orbit.
struct CameraPoints {
    std::optional<Vec3> eyeM, targetM;
};
CameraView placeCamera(const ScenePlacement& where, const scene::CameraSpec& camera, const CameraPoints& points,
                       const scene::RenderSpec& render);
/// The orbit camera of a look (no camera points): for tests and tools.
inline CameraView placeCamera(const ScenePlacement& where, const scene::LookSpec& look, const scene::RenderSpec& render) {
    return placeCamera(where, look.camera, {}, render);
}

/// Where the light comes from, as drawn: a bearing on the frame's grid
/// (clockwise from the y axis) and an altitude, degrees.
struct SunDirection {
    double azimuthDeg = 315, altitudeDeg = 45;
};

/// Where a scene point lands in a still `widthPx` x `heightPx` as POV-Ray
/// draws it: pixels, x to the right, y down, (0, 0) the top-left corner.
std::array<double, 2> projectToImage(const CameraView& view, const Vec3& p, int widthPx, int heightPx);

/// Metres of terrain one pixel of a still `widthPx` wide covers at the
/// terrain's nearest point to the eye (the finest detail the still can show).
double finestMetresPerPixel(const CameraView& view, const ScenePlacement& where, int widthPx);

/// Writes the terrain's geometry (a mesh2, a height_field) into the .pov.
using GeometryWriter = std::function<void(std::FILE* out)>;

/// What goes in the template's placeholders besides the camera and the sun:
/// the terrain, the block model under it (empty: a floating surface) and the
/// contour lines on it (empty: none).
struct GeometryWriters {
    GeometryWriter terrain, base, contours;
};

/// The template's bindings: header (every key and value through
/// oneLineText in core/text_escape.h), the camera `view` and the `sun`, the
/// geometry and the rest of the look (background, water, haze).
Bindings sceneBindings(const ScenePlacement& where, const CameraView& view, const SunDirection& sun,
                       GeometryWriters writers, const scene::LookSpec& look, const scene::RenderSpec& render,
                       const ParameterList& header);

/// Loads `<templatesDir>/scene.pov.in`.
std::optional<Template> loadSceneTemplate(const std::filesystem::path& templatesDir,
                                          Diagnostics& diags);

/// Checks bindings, then writes the .pov atomically (temp file + rename).
bool writeScene(const std::filesystem::path& out, const Template& tmpl, const ScenePlacement& where,
                const CameraView& view, const SunDirection& sun, GeometryWriters writers, const scene::LookSpec& look,
                const scene::RenderSpec& render, const ParameterList& header, Diagnostics& diags);

}  // namespace relief::emit
