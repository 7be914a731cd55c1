#pragma once
// Elevation colour ramps: named presets and custom stops.
#include <string>
#include <vector>

#include "scene/scene_spec.h"

namespace relief::scene {

/// Names accepted for `[texture] ramp`.
const std::vector<std::string>& rampPresetNames();

/// The stops of a ramp for terrain whose heights span [zMinM, zMaxM]. Presets
/// are laid out over that span; "topobathy" puts its shore colour at 0 m.
std::vector<ColorStop> resolveRamp(const ColorRamp& ramp, double zMinM, double zMaxM);

/// Colour at elevation `zM`, interpolated linearly between stops, clamped at the ends.
LinearRgb sampleRamp(const std::vector<ColorStop>& stops, double zM);

/// An sRGB component (0..1) made linear (IEC 61966-2-1).
double srgbToLinear(double c);

/// Parses "#rrggbb"; returns false on malformed text.
bool parseHexColor(const std::string& text, LinearRgb& out);

}  // namespace relief::scene
