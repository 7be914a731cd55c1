#pragma once
// The record of a run: the only writer of facts about one (what the .pov's
// header says, the JSON sidecar, relief info, relief init's scene), so that
// each fact is worded, and each rule (the data's credit) applied, once.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "annotate/overlay.h"
#include "core/diagnostics.h"
#include "emit/write_scene.h"
#include "pipeline/compile.h"
#include "pipeline/job.h"
#include "pipeline/surface.h"
#include "plan/plan.h"

namespace relief {

// The .pov's header and the sidecar's "parameters": the inputs, the frame and
// net, the scheme, depth and geometry, the look and the still.
emit::ParameterList sceneHeader(const scene::SceneSpec& scene, const geo::ControlNet& net,
                                const subdiv::ResolvedScheme& scheme, const CompileResult& compiled);

/// The JSON sidecar: inputs, parameters, net size, vertex and triangle
/// counts, time per stage, what the compile made; finishPlan adds the
/// render's (POV-Ray's seconds, every tile's record, what the overlays show).
/// Every string UTF-8: a name that is not is written with U+FFFD.
nlohmann::ordered_json sidecarJson(const scene::SceneSpec& scene, const CompileResult& compiled,
                                   const OutputPaths& paths);

/// Warns (once a run) when the sidecar of `compiled`, its .pov at `pov`,
/// will write a name or text with U+FFFD (not UTF-8), naming the first.
void warnIfSidecarNotUtf8(const scene::SceneSpec& scene, const CompileResult& compiled,
                          const std::filesystem::path& pov, Diagnostics& diags);

/// The sidecar's text: the JSON, indented, a line feed at the end.
std::string sidecarText(const nlohmann::ordered_json& sidecar);

/// What rendering a plan gave, for its sidecar.
struct RenderFacts {
    std::vector<plan::TileRecord> tiles;  ///< every tile's record, in order
    double wallSeconds = 0;               ///< the tiles' render, start to end
    double finishSeconds = 0;             ///< stitching, overlays, writing
    std::optional<annotate::OverlayRecord> overlays;
    bool perspective = true;              ///< the scale bar holds at the centre only
};
/// The render's part of the sidecar, added when a plan is finished, wherever its tiles were rendered.
void addRenderToSidecar(nlohmann::ordered_json& sidecar, const RenderFacts& render);

/// `relief info`: the data (size, CRS, extent in degrees and metres,
/// elevations, nodata, credit), the frame, the net and why, the depth and
/// why, the geometry, the estimated triangles, memory and .pov size against
/// [limits], and what vertical exaggeration would make the relief show
/// (advice), known before doing it (planSurface), as gdalinfo tells a raster.
/// Every string UTF-8: a name that is not is written with U+FFFD, and `diags` warned.
nlohmann::ordered_json sceneInfo(const LoadedScene& loaded, const Surface& surface, Diagnostics& diags);
/// The same as lines of `key: value`, a blank line between the groups.
std::string sceneInfoText(const nlohmann::ordered_json& info);

/// `relief init`: the scene as a TOML file at `scenePath`, every choice
/// written with the value relief made and a comment saying why, in the
/// order of docs/scene-format.md. Rendering it gives the still that
/// rendering `loaded`'s scene does.
/// The data's path must be UTF-8 (initCanNameData).
std::string initSceneText(const LoadedScene& loaded, const Surface& surface, const std::filesystem::path& scenePath);
/// The path a scene at `scenePath` names `data` by: relative to the scene's
/// folder, unless that climbs further than the path from the root.
std::string samplesPathFromScene(const std::filesystem::path& data, const std::filesystem::path& scenePath);
/// Whether relief init's scene at `scenePath` can name `data`: TOML holds only
/// UTF-8, and a Linux name may be any bytes. If not, an error at the file
/// saying to rename it.
bool initCanNameData(const std::filesystem::path& data, const std::filesystem::path& scenePath, Diagnostics& diags);
/// A TOML basic string on one line (quoted, every control character, quote
/// and line break escaped) holding `text`; bytes that are not UTF-8 as U+FFFD.
std::string tomlString(const std::string& text);

}  // namespace relief
