#pragma once
// Stage 3 of 6 (part 3): what a refinement will cost, known before doing it.
#include <string>

#include "core/diagnostics.h"
#include "scene/scene_spec.h"
#include "subdiv/scheme.h"

namespace relief::subdiv {

struct OutputEstimate {
    long long rows = 0, cols = 0;  ///< refined grid size
    double vertices = 0;
    double triangles = 0;
    double sdlBytes = 0;  ///< the .pov's size, from the writer's bytes per vertex and face
    double parseSeconds = 0;  ///< POV-Ray's parse time at ~4 us per triangle (measured here)
    double memoryBytes = 0;   ///< relief's peak: the refined grid, its mesh, the last coarser level
    /// The adaptive mesh: triangles, SDL and parse time are the full mesh2's (an
    /// upper bound) until the mesh is built; the budget checks them on the built one.
    bool meshAfterBuild = false;
    /// A height field: no triangles to parse or write, so limits.max_triangles
    /// does not apply; its own figures (the PNG's parse time, the memory) do.
    bool heightField = false;
};

/// What the geometry of the refined grid costs depends on its kind.
enum class GeometryCost { Mesh2, Adaptive, HeightField };

struct Budget {
    double maxTriangles;
    double maxSdlMB;
    double maxParseS;
    double maxMemoryMB;
    /// A scene's [limits], the memory three quarters of this machine's
    /// (core/memory_budget.h) unless it says: what a job is held to, made once
    /// when the scene is loaded (LoadedScene::budget).
    static Budget of(const scene::LimitsSpec& limits);
};

inline constexpr double kParseSecondsPerTriangle = 4e-6;
// Measured on the writer's output (emit/write_scene.cpp) for the default scene: a vertex line plus
// its normal line, and a face line with its three palette indices.
inline constexpr double kSdlBytesPerVertex = 58;
inline constexpr double kSdlBytesPerTriangle = 31;
// Per refined vertex: the grid (3 doubles), its mask byte and the mesh's vertex number (masked
// grids); the mesh2 is a view of the grid, its vectors computed as they are written. The last
// coarser level is counted at its own size.
inline constexpr double kMemoryBytesPerVertex = 3 * 8 + 1 + 4;
// The adaptive mesh's faces beside that: at most two a node, three node numbers each.
inline constexpr double kAdaptiveFaceBytesPerVertex = 2 * 3 * 4;

// A height_field's .pov is its header, camera and 256-entry colour map; POV-Ray
// parses the PNG at ~0.15 us per node (0.45 s for 2393 x 1285, measured), and
// relief holds 2 bytes per node for its levels beside the refined grid.
inline constexpr double kHeightFieldSdlBytes = 16e3;
inline constexpr double kParseSecondsPerHeightFieldNode = 0.15e-6;

/// The refined grid's size and what its geometry costs: the full mesh2, the
/// height field of the same grid, or the adaptive mesh (its memory at most
/// the full mesh's, its triangles known once it is built: see meshAfterBuild).
OutputEstimate estimateOutput(const Scheme& scheme, int rows, int cols, int depth,
                              GeometryCost kind = GeometryCost::Mesh2);

/// The estimate with a built mesh2's own vertices and triangles.
OutputEstimate withBuiltMesh(OutputEstimate est, double vertices, double triangles);

/// Every figure of the estimate within the budget (only memory while meshAfterBuild).
bool withinBudget(const OutputEstimate& est, const Budget& budget);

/// The deepest depth, at most maxDepth, whose output is within the budget
/// (0 when not even depth 1 is).
int deepestWithinBudget(const Scheme& scheme, int rows, int cols, const Budget& budget, int maxDepth);

/// The figures of the estimate over the budget, each against its key
/// ("2.1e+07 triangles > limits.max_triangles = 2e+07; ..."), "" when within.
std::string overBudget(const OutputEstimate& est, const Budget& budget);

/// What lines lying on the surface add to POV-Ray's parse beside the surface's
/// `meshTriangles`: their ribbons' triangles and SDL (contours and marks alike).
OutputEstimate linesOnSurface(double ribbonTriangles, double sdlBytes, long long meshTriangles);

/// Reports an error at `where` when the estimate exceeds the budget, naming
/// each exceeded figure and the ways out (`adaptive`: the built adaptive mesh,
/// whose tolerance is one of them). Returns true when within budget.
bool checkBudget(const OutputEstimate& est, const Budget& budget, const SourceLoc& where,
                 int depth, Diagnostics& diags, bool adaptive = false);

}  // namespace relief::subdiv
