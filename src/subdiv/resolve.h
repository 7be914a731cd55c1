#pragma once
// Stage 3 of 6 (part 0). Input: a SchemeSpec, as a scene file or the command
// line names a scheme (family and parameters, a preset, or a mask). Output: the
// Scheme, every parameter, and what it certifiably gives. The only place a
// scheme spec becomes a Scheme, so every caller reports the same problems in
// the same words, at the key that caused them.
#include <map>
#include <optional>
#include <string>

#include "core/diagnostics.h"
#include "scene/scene_spec.h"
#include "subdiv/analysis.h"
#include "subdiv/scheme.h"

namespace relief::subdiv {

struct ResolvedScheme {
    std::string family;   ///< the scheme's family ("mask" for a user's mask); a preset resolved
    Scheme scheme;
    SchemeParams params;  ///< every parameter of the family, defaults filled in
    SchemeReport report;  ///< certified smoothness and the rest (relief check)
};

/// Resolves the preset (if any) into its family and parameters, checks the
/// family's parameter names (with suggestions) and ranges, fills in defaults,
/// builds the scheme (or the mask's), and certifies it. Reports every problem
/// at its key in `spec.locs` ("subdivision.scheme", ".preset", ".mask", ".<param>").
/// A scheme not proven to converge is a warning unless spec.allowNonconvergent.
std::optional<ResolvedScheme> resolveScheme(const scene::SchemeSpec& spec, Diagnostics& diags);

}  // namespace relief::subdiv
