#pragma once
// The stages composed: scene file -> SceneDesc -> ControlNet -> refined Grid
// -> Mesh -> .pov -> PNG. Each stage is a free function in its own folder;
// this file only wires them together, times them and names the outputs.
#include <filesystem>
#include <functional>
#include <map>
#include <optional>
#include <string>

#include "core/diagnostics.h"
#include "emit/write_scene.h"
#include "geo/normalize.h"
#include "measure/auto_depth.h"
#include "render/povray.h"
#include "scene/scene_desc.h"
#include "subdiv/analysis.h"
#include "subdiv/budget.h"
#include "subdiv/scheme.h"

namespace relief {

/// Stage 1 and the scheme's parameters: everything the scene file says, checked.
struct LoadedScene {
    scene::SceneDesc scene;
    std::string schemeFamily;  ///< the scheme's name (a preset resolved to its family)
    subdiv::Scheme scheme;
    std::map<std::string, double> schemeParams;  ///< every parameter, defaults filled in
    subdiv::SchemeReport report;  ///< certified smoothness and the rest (relief check)
    double seconds = 0;
};

/// Reads and validates the scene file and its scheme (name, preset or mask, and
/// parameters), reporting every problem at once, then certifies the scheme's
/// smoothness; a scheme not proven to converge is a warning unless
/// subdivision.allow_nonconvergent is set. Nothing is written.
std::optional<LoadedScene> loadScene(const std::filesystem::path& scenePath, Diagnostics& diags,
                                     const scene::SceneOverrides& overrides = {});

/// "depth 3" or "depth auto (tolerance_m = 5)".
std::string depthLabel(const scene::SceneDesc& scene);

/// For depth = "auto": "depth 4 chosen: level 1 moved the terrain 220 m, ..., 4: 4.1 m <= 5 m".
std::string autoDepthSummary(const measure::DepthChoice& choice, double toleranceM);

/// "C1 (Hölder ~1.68)" or "convergence not proven (...)".
std::string certifiedClass(const subdiv::SchemeReport& report);

/// Stages 2 and 3: the control net and the refined surface (metres, in the
/// net's frame), refused with a diagnostic when over the output budget. Used
/// by compileScene and by measurements such as profiles.
struct Surface {
    geo::ControlNet net;
    Grid refined;
    double refinedDx = 0, refinedDy = 0;  ///< spacing of the refined lattice (metres)
    subdiv::OutputEstimate estimate;
    int depth = 0;  ///< the scene's, or the one depth = "auto" chose
    std::optional<measure::DepthChoice> autoDepth;  ///< the change per level, for depth = "auto"
    double normalizeSeconds = 0, subdivideSeconds = 0;  ///< subdivide includes choosing the depth
};
std::optional<Surface> buildSurface(const LoadedScene& loaded, Diagnostics& diags, int threads = 0);

struct CompileOptions {
    std::filesystem::path povPath;       ///< where the .pov goes
    std::filesystem::path templatesDir;
    std::filesystem::path dumpNetPath;   ///< optional: .csv (x,y,z) or .asc (ESRI ASCII grid)
    int threads = 0;                     ///< refiner threads; 0 = all cores
};

struct StageTimes {
    double readScene = 0, normalize = 0, subdivide = 0, emit = 0;  ///< seconds
};

struct CompileResult {
    scene::SceneDesc scene;
    geo::ControlNet net;  ///< the control net (its grid is kept; it is small)
    subdiv::OutputEstimate estimate;
    int refinedRows = 0, refinedCols = 0;
    int depth = 0;  ///< the scene's, or the one depth = "auto" chose
    std::optional<measure::DepthChoice> autoDepth;
    int arity = 2;
    double holder = 0;  ///< the scheme's Hölder estimate, next to the observed rates
    double metresPerUnit = 1;
    emit::ParameterList parameters;  ///< as recorded in the .pov header
    StageTimes times;
    std::uintmax_t povBytes = 0;
};

/// Runs stages 2-4 and writes the .pov (and the net dump, if asked).
/// Nothing is written when any stage reports an error.
std::optional<CompileResult> compileScene(const LoadedScene& loaded,
                                          const CompileOptions& options, Diagnostics& diags);

/// Output paths derived from a scene: `out/<stem>.png` unless the scene's
/// [render] output or the caller says otherwise; the .pov and the .json
/// sidecar sit beside the PNG.
struct OutputPaths {
    std::filesystem::path png, pov, sidecar;
};
OutputPaths outputPathsFor(const std::filesystem::path& png);
std::filesystem::path defaultPngPath(const std::filesystem::path& scenePath,
                                     const std::string& sceneOutput);

/// One scene file all the way to a PNG: what `relief render`, `relief test`
/// and `relief sweep` do for each still.
struct RenderJob {
    std::filesystem::path scenePath;
    scene::SceneOverrides overrides;
    std::filesystem::path png;  ///< "" = the scene's [render] output, else out/<scene>.png
    std::filesystem::path templatesDir;
    std::filesystem::path dumpNetPath;
    int threads = 0;            ///< refiner and POV-Ray threads; 0 = all cores
};

enum class JobStatus { Ok, BadInput, ToolFailed };

struct RenderOutcome {
    JobStatus status = JobStatus::BadInput;
    std::string schemeFamily;
    std::string certified;           ///< e.g. "C1 (Hölder ~1.68)"
    OutputPaths paths;
    std::optional<CompileResult> compiled;
    render::RenderResult render;     ///< POV-Ray's timings and error text
};

/// Loads, compiles and renders; writes the PNG, the .pov and the JSON sidecar
/// (atomically; nothing when a stage fails). Diagnostics go to `diags`,
/// progress lines to `progress` (may be empty).
RenderOutcome renderSceneFile(const RenderJob& job, Diagnostics& diags,
                              const render::ProgressFn& progress);

/// The JSON sidecar: inputs, parameters, net size, vertex and triangle
/// counts, time per stage (and POV-Ray's, when `render` is given).
std::string sidecarJson(const CompileResult& compiled, const OutputPaths& paths,
                        const render::RenderResult* render);

}  // namespace relief
