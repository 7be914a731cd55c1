#pragma once
// What the .pov's header says of the scene that made it, and the sidecar's
// "parameters" with it: the inputs, the frame and net, the scheme, depth and
// geometry, the look and the still.
#include "emit/write_scene.h"
#include "pipeline.h"

namespace relief {

emit::ParameterList sceneHeader(const scene::SceneSpec& scene, const geo::ControlNet& net,
                                const subdiv::ResolvedScheme& scheme, int depth, const CompileResult& compiled);

}  // namespace relief
