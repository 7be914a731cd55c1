#pragma once
// What compileScene lays on the terrain's surface beside it: the scene's
// [[layer]]s (their files read by geo/, placed by emit/) and the graticule;
// and, for each view, their labels and legend entries for annotate/.
#include <cstdio>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "annotate/overlay.h"
#include "core/diagnostics.h"
#include "emit/camera.h"
#include "emit/graticule.h"
#include "emit/surface_layers.h"
#include "scene/scene_spec.h"
#include "subdiv/budget.h"

namespace relief {

struct SurfaceMarks {
    emit::SurfaceLayers layers;
    std::optional<emit::Graticule> graticule;
    std::vector<std::string> layerNames;  ///< each [[layer]]'s layer in its file
    long long triangles() const;
    bool empty() const;
};

/// The scene's [[layer]]s and graticule on `refined`, lines as wide as their
/// specs say at `metresPerPixel` (the centre of the view), polygons' fills
/// as the surface's tints (layers.fills: the geometry is built after them).
/// Nullopt after an error: a file that cannot be read, a graticule of too
/// many lines. Overlays off ([overlay] enabled = false): none.
std::optional<SurfaceMarks> buildSurfaceMarks(const scene::SceneSpec& spec, const geo::GeoGrid& refined,
                                              const emit::ScenePlacement& where, double metresPerPixel,
                                              Diagnostics& diags);

/// Whether the marks fit [limits] beside the `trianglesBeside` the surface
/// and contours already take; else an error at the layer drawing the most
/// (or the graticule), naming its counts and the limit.
bool surfaceMarksWithinLimits(const SurfaceMarks& marks, const scene::SceneSpec& spec, const subdiv::Budget& budget,
                              long long trianglesBeside,
                              Diagnostics& diags);

/// The marks' SDL (the template's {{contours}} holds them after the contours).
void writeSurfaceMarks(std::FILE* out, const SurfaceMarks& marks, const scene::SceneSpec& spec,
                       const emit::ScenePlacement& where, const emit::CameraView& view);

/// For one view: the labels of the points the eye sees and of the graticule's
/// lines, and the layers' legend entries, into `facts`; what each layer
/// became, points hidden from this eye counted, as the sidecar's "layers".
nlohmann::ordered_json describeSurfaceMarks(const SurfaceMarks& marks, const scene::SceneSpec& spec,
                                            const geo::GeoGrid& refined, const emit::ScenePlacement& where,
                                            const emit::CameraView& view, annotate::OverlayFacts& facts);

}  // namespace relief
