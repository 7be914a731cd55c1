#include "emit/graticule.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "core/number_format.h"
#include "geo/normalize.h"

namespace relief::emit {

namespace {

constexpr int kMaxPointsALine = 4000;

// The lines' values: the multiples of `step` within [lo, hi].
std::vector<double> multiplesWithin(double lo, double hi, double step) {
    std::vector<double> out;
    for (long long k = static_cast<long long>(std::ceil(lo / step - 1e-9)); k * step <= hi + 1e-9 * step; ++k)
        out.push_back(std::abs(k * step) < 1e-12 ? 0.0 : k * step);
    return out;
}

}  // namespace

double graticuleStepDeg(double spanDeg) {
    static const double kSteps[] = {1.0 / 3600, 2.0 / 3600, 5.0 / 3600, 10.0 / 3600, 15.0 / 3600, 30.0 / 3600,
                                    1.0 / 60,   2.0 / 60,   5.0 / 60,   10.0 / 60,   15.0 / 60,   30.0 / 60,
                                    1,          2,          5,          10,          15,          30};
    for (double step : kSteps)
        if (spanDeg / step <= 5) return step;
    return 30;
}

std::string graticuleLabel(double valueDeg, bool meridian, double stepDeg) {
    const double v = std::abs(valueDeg);
    const std::string h = valueDeg == 0 ? "" : meridian ? (valueDeg < 0 ? "W" : "E") : (valueDeg < 0 ? "S" : "N");
    constexpr double kTiny = 1e-9;
    if (stepDeg < 1.0 / 3600 - kTiny) return formatShortest(std::round(v * 1e6) / 1e6) + "\u00b0" + h;
    const long long seconds = std::llround(v * 3600);
    const long long d = seconds / 3600, m = seconds / 60 % 60, s = seconds % 60;
    if (stepDeg >= 1 - kTiny) return fmt::format("{}\u00b0{}", d, h);
    if (stepDeg >= 1.0 / 60 - kTiny) return fmt::format("{}\u00b0{:02}\u2032{}", d, m, h);
    return fmt::format("{}\u00b0{:02}\u2032{:02}\u2033{}", d, m, s, h);
}

LonLatBox terrainLonLatBox(const geo::GeoGrid& refined) {
    LonLatBox box{180, 90, -180, -90};
    const int rows = refined.rows(), cols = refined.cols();
    const auto add = [&](int r, int c) {
        if (const auto g = geo::reverse(refined.frame, {refined.x0 + c * refined.dx, refined.y0 + r * refined.dy, 0})) {
            box.west = std::min(box.west, g->lonDeg), box.east = std::max(box.east, g->lonDeg);
            box.south = std::min(box.south, g->latDeg), box.north = std::max(box.north, g->latDeg);
        }
    };
    // The edges, about a hundred points each: a projection bends them, so the corners alone are not enough.
    for (int k = 0; k <= 100; ++k) {
        const int c = static_cast<int>(std::lround(double(k) * (cols - 1) / 100));
        const int r = static_cast<int>(std::lround(double(k) * (rows - 1) / 100));
        add(0, c), add(rows - 1, c), add(r, 0), add(r, cols - 1);
    }
    return box;
}

int graticuleLineCount(const scene::GraticuleSpec& spec, const LonLatBox& box) {
    const double step = spec.stepDeg > 0 ? spec.stepDeg : graticuleStepDeg(std::max(box.east - box.west, box.north - box.south));
    return static_cast<int>(multiplesWithin(box.west, box.east, step).size() +
                            multiplesWithin(box.south, box.north, step).size());
}

Graticule buildGraticule(const scene::GraticuleSpec& spec, const LonLatBox& box, const geo::GeoGrid& refined,
                         const ScenePlacement& where, double widthM) {
    Graticule g;
    g.stepDeg = spec.stepDeg > 0 ? spec.stepDeg : graticuleStepDeg(std::max(box.east - box.west, box.north - box.south));
    // A point about every refined cell along a line (its degrees of one cell at the terrain's middle).
    const double cellDeg = std::max(std::min(refined.dx, refined.dy) / 111320.0, 1e-9);
    const RibbonStyle style{widthM, 0.25 * widthM, std::min(6 * widthM, std::max(refined.dx, refined.dy))};
    for (const bool meridian : {true, false}) {
        const double lo = meridian ? box.west : box.south, hi = meridian ? box.east : box.north;
        const double from = meridian ? box.south : box.west, to = meridian ? box.north : box.east;
        const int n = std::clamp(static_cast<int>(std::ceil((to - from) / cellDeg)), 2, kMaxPointsALine);
        for (double value : multiplesWithin(lo, hi, g.stepDeg)) {
            GraticuleLine line{meridian, value, graticuleLabel(value, meridian, g.stepDeg), {}};
            for (int k = 0; k <= n; ++k) {
                const double t = from + (to - from) * k / n;
                const GeoPoint p = meridian ? GeoPoint{value, t, 0} : GeoPoint{t, value, 0};
                if (const auto f = geo::forward(refined.frame, p)) line.frame.push_back({f->x, f->y});
            }
            addRibbon(g.ribbons, refined, where, line.frame, style);
            g.lines.push_back(std::move(line));
        }
    }
    return g;
}

}  // namespace relief::emit
