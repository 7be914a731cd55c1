#pragma once
// relief export: the surface (surface.h) as the still would render it, taken
// away as a 3-D model (model/terrain_model.h): within a triangle budget (the
// adaptive mesh, its bound said, where every node would be over it), closed
// into a solid for printing, scaled to a size in millimetres.
#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>

#include "core/diagnostics.h"
#include "emit/mesh.h"
#include "model/terrain_model.h"
#include "pipeline/load.h"
#include "pipeline/progress.h"
#include "pipeline/surface.h"
#include "scene/scene_spec.h"

namespace relief {

/// The default --max-triangles: a model Blender, a slicer and a web page
/// open at once (a .glb of about 50 MB).
inline constexpr long long kDefaultModelTriangles = 2'000'000;

struct ExportJob {
    std::filesystem::path scenePath;     ///< a scene file, or a DEM alone
    scene::SceneOverrides overrides;     ///< --set
    std::filesystem::path output;        ///< empty: out/<scene name>.glb
    std::optional<double> acrossMM;      ///< --scale: the wider horizontal extent, in millimetres
    long long maxTriangles = kDefaultModelTriangles;
    bool solid = false;                  ///< --solid: walls and a floor whatever the format (STL always has them)
    int threads = 0;
};

struct ExportOutcome {
    std::filesystem::path output;
    std::string format;                  ///< the format's name
    size_t vertices = 0, surfaceTriangles = 0, wallTriangles = 0, floorTriangles = 0;
    int rows = 0, cols = 0, depth = 0;   ///< the refined surface's lattice and depth
    /// 0: every node of the refined surface a vertex; else the adaptive mesh's
    /// bound, true metres (vertical) from the refined surface.
    double toleranceM = 0;
    double unitsPerMetre = 1;            ///< 1: metres; --scale's millimetres per metre
    std::optional<double> floorElevationM;
    std::uintmax_t bytes = 0;
    double seconds = 0;
};

/// The model of a loaded scene's surface that export writes and preview
/// shows: its colours as the still draws them, within `maxTriangles`, and
/// where the terrain sits in the scene (the still's placement, which the
/// model's metres are of: scene units times where.metresPerUnit).
struct SceneModel {
    model::TerrainModel model;
    double toleranceM = 0;  ///< ExportOutcome::toleranceM
    emit::ScenePlacement where;
};
/// nullopt after an error (none fits, nothing has data, a drape unread), in `diags`.
std::optional<SceneModel> sceneModel(const LoadedScene& loaded, const Surface& surface, long long maxTriangles,
                                     Diagnostics& diags, const ProgressFn& progress = {});

/// Loads the scene, builds its surface, and writes the model to job.output
/// (whole or not at all); nullopt after an error, reported in `diags`.
std::optional<ExportOutcome> exportTerrain(const ExportJob& job, Diagnostics& diags, const ProgressFn& progress = {});

}  // namespace relief
