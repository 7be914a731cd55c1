#include <cmath>

#include <gtest/gtest.h>

#include "geo/samples.h"
#include "pipeline/depth.h"
#include "pipeline/surface.h"
#include "subdiv/analysis.h"

namespace relief {
namespace {

// Rows z = c (x - xc)^2 with an even number of nodes, the classic 4-point
// scheme (it reproduces cubics away from the ends): level 1 puts the new
// points on the parabola, and the farthest from the old polyline is the one
// under the horizontal middle chord, c h^2 / 4 below it (the ghost points'
// linear extrapolation makes the end points move less: c h^2 / 8). Columns
// are straight and never move. So level 1 moves 0.25 m for c = 0.01, h = 10 m;
// later levels near the ends are no longer on the parabola, and move by about
// a quarter of the level before (the scheme is C1 with Hölder exponent 2).
TEST(AutoDepth, ParabolaRowsMoveByTheChordSag) {
    geo::ControlNet net;
    net.grid.rows = 4;
    net.grid.cols = 6;
    net.dx = net.dy = 10;
    net.x0 = 1000, net.y0 = 2000;
    const double c = 0.01, xc = net.x0 + 25;
    for (int r = 0; r < net.grid.rows; ++r)
        for (int k = 0; k < net.grid.cols; ++k) {
            const double x = net.x0 + k * net.dx;
            net.grid.points.push_back({x, net.y0 + r * net.dy, c * (x - xc) * (x - xc)});
        }
    const auto choice = chooseDepth(subdiv::dlgFourPoint(1.0 / 16), net, 0.02, 8, 2);
    ASSERT_TRUE(choice.reached);
    ASSERT_GE(choice.levels.size(), 3u);
    EXPECT_EQ(choice.depth, static_cast<int>(choice.levels.size()));
    EXPECT_LE(choice.levels.back().distanceM, 0.02);
    EXPECT_GT(choice.levels[choice.levels.size() - 2].distanceM, 0.02);
    EXPECT_NEAR(choice.levels[0].distanceM, 0.25, 1e-12);
    EXPECT_EQ(choice.levels[0].curve, "row 0");  // every row is the same: the first is named
    EXPECT_NEAR(choice.levels[0].x, xc, 1e-9);   // under the middle chord
    EXPECT_NEAR(choice.levels[0].y, net.y0, 1e-9);
    EXPECT_NEAR(choice.levels[0].z, 0.0, 1e-12);
    for (size_t k = 1; k < choice.levels.size(); ++k) {
        const double rate = observedRate(choice, k, 2);
        EXPECT_GT(rate, 1.6) << "level " << k + 1;
        EXPECT_LT(rate, 2.2) << "level " << k + 1;
    }
    EXPECT_TRUE(std::isnan(observedRate(choice, 0, 2)));

    // Not reached within the levels allowed: the last level is reported.
    const auto capped = chooseDepth(subdiv::dlgFourPoint(1.0 / 16), net, 1e-3, 2, 1);
    EXPECT_FALSE(capped.reached);
    EXPECT_EQ(capped.depth, 2);
    EXPECT_EQ(capped.levels.size(), 2u);
}

// Least-squares slope of log_arity(distance) against the level.
double fittedRate(const DepthChoice& c, int arity, size_t from) {
    double sx = 0, sy = 0, sxx = 0, sxy = 0;
    const double n = static_cast<double>(c.levels.size() - from);
    for (size_t i = from; i < c.levels.size(); ++i) {
        const double x = c.levels[i].level, y = std::log(c.levels[i].distanceM) / std::log(arity);
        sx += x, sy += y, sxx += x * x, sxy += x * y;
    }
    return -(n * sxy - sx * sy) / (n * sxx - sx * sx);
}

// The two mountain scenes of paper 001 (same net, real topobathy data): the
// change per level shrinks by about 2^-alpha, alpha the certified scheme's
// Hölder exponent (min(alpha, 2) in general: a polyline follows a smooth curve
// to second order). Measured: gentle (alpha 1.68) 1.40, 1.83, 1.79, 1.77,
// 1.75; sharp (alpha 0.51) 0.83, 0.69, 0.52, 0.45, 0.80, 0.57.
TEST(AutoDepth, MountainRatesMatchSmoothness) {
    struct Case {
        const char* scene;
        double tolerance;
        int levels;
    };
    double rates[2];
    int i = 0;
    for (const Case& k : {Case{"mountains-gentle.toml", 1.0, 6}, Case{"mountains-sharp.toml", 40.0, 7}}) {
        Diagnostics diags;
        const auto loaded = loadScene(std::string(RELIEF_SOURCE_DIR) + "/tests/data/scenes/" + k.scene, diags);
        ASSERT_TRUE(loaded) << k.scene;
        const auto& spec = loaded->scene;
        const auto samples = geo::readSamples(spec.samples.path, "", diags);
        const auto net = geo::normalize(spec.frame, spec.net, "", samples, diags);
        ASSERT_TRUE(net);
        const auto choice = chooseDepth(loaded->resolved.scheme, *net, k.tolerance, 8);
        ASSERT_TRUE(choice.reached) << k.scene;
        EXPECT_EQ(choice.depth, k.levels) << k.scene;
        for (size_t l = 1; l < choice.levels.size(); ++l)
            EXPECT_LT(choice.levels[l].distanceM, choice.levels[l - 1].distanceM) << k.scene;
        const double predicted = std::min(loaded->resolved.report.holder, 2.0);
        rates[i++] = fittedRate(choice, loaded->resolved.scheme.arity, 1);
        EXPECT_NEAR(rates[i - 1], predicted, 0.2) << k.scene;
    }
    EXPECT_GT(rates[0] - rates[1], 1.0);  // gentle converges much faster than sharp
}

}  // namespace
}  // namespace relief
