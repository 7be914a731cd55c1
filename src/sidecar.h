#pragma once
// The JSON sidecar beside a still: sidecarJson (pipeline.h) writes what
// compiling made; addRenderToSidecar adds the render's part when a plan is
// finished, wherever its tiles were rendered.
#include <filesystem>
#include <optional>
#include <vector>

#include <nlohmann/json.hpp>

#include "annotate/overlay.h"
#include "pipeline.h"
#include "plan/plan.h"

namespace relief {

/// What rendering a plan gave, for its sidecar.
struct RenderFacts {
    std::vector<plan::TileRecord> tiles;  ///< every tile's record, in order
    double wallSeconds = 0;               ///< the tiles' render, start to end
    double finishSeconds = 0;             ///< stitching, overlays, writing
    std::optional<annotate::OverlayRecord> overlays;
    bool perspective = true;              ///< the scale bar holds at the centre only
};

void addRenderToSidecar(nlohmann::ordered_json& sidecar, const RenderFacts& render);

}  // namespace relief
