#pragma once
// Inside geo: a raster resampled onto the net, phase by phase (raster.h says
// what the result is; rasterNet and latticeNet call this).
#include <optional>

#include "core/diagnostics.h"
#include "geo/normalize.h"
#include "geo/raster_footprint.h"
#include "geo/raster_source.h"
#include "scene/scene_spec.h"

namespace relief::geo {

/// The raster `src` (opened from the scene's file, or made from a lattice of
/// samples) resampled onto the net. `footprint`: the cells whose box is the
/// default extent; nullopt: the cells with data.
std::optional<ControlNet> warpedNet(const Dataset& src, const scene::SamplesSpec& samples,
                                    const scene::FrameSpec& frameSpec, const scene::NetSpec& netSpec,
                                    std::optional<PixelBox> footprint, Diagnostics& diags,
                                    const GridProgressFn& progress, const NetBudget& budget);

}  // namespace relief::geo
