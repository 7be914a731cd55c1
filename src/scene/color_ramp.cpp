#include "scene/color_ramp.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>

namespace relief::scene {

double srgbToLinear(double c) {
    return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

namespace {

struct RelStop {
    double t;  ///< 0..1 over the span the preset is laid out on
    const char* hex;
};

// Land colours, low to high: lowland green, upland olive, rock brown, scree, pale stone.
constexpr RelStop kLand[] = {{0.0, "#3c6e3a"}, {0.3, "#8fa663"}, {0.6, "#a8875c"},
                             {0.85, "#9c8c7c"}, {1.0, "#ece6da"}};
// Water, deep to shallow.
constexpr RelStop kSea[] = {{0.0, "#0d2a5c"}, {0.7, "#2f6fb0"}, {1.0, "#86bfe0"}};
constexpr RelStop kGrey[] = {{0.0, "#3a3a3a"}, {1.0, "#f0f0f0"}};

ColorStop makeStop(double elevM, const char* hex) {
    ColorStop s{elevM, {}};
    parseHexColor(hex, s.rgb);
    return s;
}

template <size_t N>
void layOut(const RelStop (&rel)[N], double lo, double hi, std::vector<ColorStop>& out) {
    for (const auto& s : rel) out.push_back(makeStop(lo + s.t * (hi - lo), s.hex));
}

}  // namespace

const std::vector<std::string>& rampPresetNames() {
    static const std::vector<std::string> names{"terrain", "topobathy", "grey"};
    return names;
}

bool parseHexColor(const std::string& text, LinearRgb& out) {
    if (text.size() != 7 || text[0] != '#') return false;
    // Six hex digits and nothing else: strtol alone would take "-8", " 8" or "+8" as a byte.
    if (!std::all_of(text.begin() + 1, text.end(), [](unsigned char c) { return std::isxdigit(c) != 0; }))
        return false;
    double rgb[3];
    for (int i = 0; i < 3; ++i) {
        const std::string part = text.substr(1 + 2 * i, 2);
        const long v = std::strtol(part.c_str(), nullptr, 16);
        rgb[i] = srgbToLinear(static_cast<double>(v) / 255.0);
    }
    out.r = rgb[0];
    out.g = rgb[1];
    out.b = rgb[2];
    return true;
}

std::vector<ColorStop> resolveRamp(const ColorRamp& ramp, double zMinM, double zMaxM) {
    if (ramp.preset == "custom") return ramp.stops;
    std::vector<ColorStop> stops;
    if (zMaxM <= zMinM) zMaxM = zMinM + 1.0;
    if (ramp.preset == "grey") {
        layOut(kGrey, zMinM, zMaxM, stops);
    } else if (ramp.preset == "topobathy" && zMinM < 0.0 && zMaxM > 0.0) {
        // Shore at exactly 0 m: the sea ends just below it, the land starts at it.
        layOut(kSea, zMinM, -1e-3, stops);
        layOut(kLand, 0.0, zMaxM, stops);
    } else {
        layOut(kLand, zMinM, zMaxM, stops);
    }
    return stops;
}

LinearRgb sampleRamp(const std::vector<ColorStop>& stops, double zM) {
    if (zM <= stops.front().elevM) return stops.front().rgb;
    if (zM >= stops.back().elevM) return stops.back().rgb;
    auto hi = std::upper_bound(stops.begin(), stops.end(), zM,
                               [](double z, const ColorStop& s) { return z < s.elevM; });
    auto lo = hi - 1;
    const double span = hi->elevM - lo->elevM;
    const double t = span > 0 ? (zM - lo->elevM) / span : 0.0;
    return mix(lo->rgb, hi->rgb, t);
}

}  // namespace relief::scene
