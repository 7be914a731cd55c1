#pragma once
// net.fit = true: the net prefiltered so that the scheme's surface, refined to
// the depth rendered, passes through the net's own values at its nodes. An
// approximating scheme (a B-spline) otherwise flattens peaks and fills pits by
// its filter's weight; solved exactly and separably, as interpolating
// B-splines are made: Z = Ky^-1 V Kx^-T, K an axis's refined values at the
// nodes as weights on them (fit/basis.h).
#include <optional>

#include "core/diagnostics.h"
#include "geo/normalize.h"
#include "scene/scene_spec.h"
#include "subdiv/scheme.h"

namespace relief::fit {

struct PrefilterReport {
    int depth = 0;
    double largestChangeM = 0;  ///< the most a node moved
    double gain = 1;            ///< how much the prefilter amplifies the net's finest detail at most
};

/// A prefilter that amplifies the finest detail more than this is refused: the
/// scheme's filter is too flat at the net's own frequency to be undone.
inline constexpr double kMaxPrefilterGain = 100;

/// Replaces `net`'s heights (masked nodes' filled ones too). Nullopt, after an
/// error at net.fit, when the scheme's filter cannot be undone (the gain over
/// kMaxPrefilterGain, or a singular system). An interpolating scheme needs
/// none: a warning, the net unchanged.
std::optional<PrefilterReport> prefilterNet(const subdiv::Scheme& scheme, int depth, const scene::NetSpec& spec,
                                            geo::ControlNet& net, Diagnostics& diags);

}  // namespace relief::fit
