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
#include "emit/camera.h"
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

/// Where the light comes from, as drawn: a bearing on the frame's grid
/// (clockwise from the y axis) and an altitude, degrees.
struct SunDirection {
    double azimuthDeg = 315, altitudeDeg = 45;
};

/// Writes the terrain's geometry (a mesh2, a height_field) into the .pov.
using GeometryWriter = std::function<void(std::FILE* out)>;

/// What goes in the template's placeholders besides the camera and the sun:
/// the terrain, the block model under it (empty: a floating surface) and
/// what lies on its surface, in the placeholder {{contours}}: contour lines,
/// the [[layer]]s' lines and markers, the graticule (empty: none).
struct GeometryWriters {
    GeometryWriter terrain, base, onSurface;
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
