#pragma once
// GMT colour palette tables (.cpt), the format GMT and cpt-city use for
// hypsometric tints: `[texture] cpt = "file.cpt"`.
//
// Read: comment lines (#, where "# COLOR_MODEL = RGB" may stand), blank
// lines, the B, F and N lines (background, foreground, NaN colours: relief
// clamps to the ends instead, so they are accepted and not used), and slices
//   z_low  colour  z_high  colour  [L|U|B] [;label]
// with colours as R/G/B, "R G B" (0-255 each), #rrggbb or a grey level.
// A slice's two colours are interpolated; where one slice ends in another
// colour than the next begins with, the tint steps. Other colour models
// (HSV, CMYK), named colours and categorical tables are errors naming the
// line and column.
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/diagnostics.h"
#include "scene/scene_spec.h"

namespace relief::scene {

/// The stops of a .cpt's text (elevations in the file's units, metres for a
/// DEM; colours made linear), bottom to top; nullopt and errors in `diags`
/// at `file`:line:column when the text is not a palette relief can use.
std::optional<std::vector<ColorStop>> parseCpt(std::string_view text, const std::string& file, Diagnostics& diags);

}  // namespace relief::scene
