#include "emit/unsupported_fade.h"

#include <algorithm>
#include <cmath>

#include "emit/mesh.h"

namespace relief::emit {

namespace {

// The distance at frame point (x, y), bilinearly between the net's nodes
// (clamped to the net: the refined surface has the net's extent).
double reachAt(const geo::GeoGrid& net, const std::vector<float>& reachM, double x, double y) {
    const int rows = net.rows(), cols = net.cols();
    const double u = std::clamp((x - net.x0) / net.dx, 0.0, double(cols - 1));
    const double v = std::clamp((y - net.y0) / net.dy, 0.0, double(rows - 1));
    const int c = std::min(static_cast<int>(u), std::max(cols - 2, 0)), r = std::min(static_cast<int>(v), std::max(rows - 2, 0));
    const int c1 = std::min(c + 1, cols - 1), r1 = std::min(r + 1, rows - 1);
    const double fu = u - c, fv = v - r;
    const auto at = [&](int rr, int cc) { return double(reachM[static_cast<size_t>(rr) * cols + cc]); };
    return (1 - fv) * ((1 - fu) * at(r, c) + fu * at(r, c1)) + fv * ((1 - fu) * at(r1, c) + fu * at(r1, c1));
}

}  // namespace

std::vector<std::uint8_t> unsupportedFade(const geo::GeoGrid& net, const std::vector<float>& reachM, double fromM,
                                          const geo::GeoGrid& refined) {
    std::vector<std::uint8_t> fade(refined.grid.points.size(), 0);
    if (!(fromM > 0)) return fade;
    for (size_t node = 0; node < fade.size(); ++node) {
        const Vec3& p = refined.grid.points[node];
        const double t = std::clamp(reachAt(net, reachM, p.x, p.y) / fromM - 1, 0.0, 1.0);
        fade[node] = static_cast<std::uint8_t>(std::lround(t * t * (3 - 2 * t) * kFadeLevels));
    }
    return fade;
}

}  // namespace relief::emit
