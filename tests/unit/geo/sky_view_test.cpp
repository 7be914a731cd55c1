#include "geo/sky_view.h"

#include <cmath>

#include <gtest/gtest.h>

namespace relief::geo {
namespace {

// A 101 x 101 grid at 2 m whose height is f(x, y), x and y in metres from node (0, 0).
template <class F>
GeoGrid gridOf(F f) {
    GeoGrid g;
    g.dx = g.dy = 2;
    g.grid.rows = g.grid.cols = 101;
    for (int r = 0; r < 101; ++r)
        for (int c = 0; c < 101; ++c) g.grid.points.push_back({2.0 * c, 2.0 * r, f(2.0 * c, 2.0 * r)});
    return g;
}

// 1 - mean over the 16 azimuths of the horizon's sine, the horizon's tangent given per azimuth.
template <class F>
double expectedFactor(F tanOfHorizon) {
    double hidden = 0;
    for (int k = 0; k < 16; ++k) {
        const double t = std::max(0.0, tanOfHorizon(2 * M_PI * k / 16));
        hidden += t / std::sqrt(1 + t * t);
    }
    return 1 - hidden / 16;
}

TEST(SkyView, FlatGroundSeesTheWholeSky) {
    const auto svf = skyViewFactor(gridOf([](double, double) { return 40.0; }), {.radiusM = 30});
    for (float v : svf) EXPECT_FLOAT_EQ(v, 1.0f);
}

TEST(SkyView, ATiltedPlaneHidesTheSkyBehindItsUpslope) {
    // Rising 0.5 m a metre to the east: looking at azimuth a, the plane rises 0.5 cos(a) a metre.
    const auto svf = skyViewFactor(gridOf([](double x, double) { return 0.5 * x; }), {.radiusM = 30});
    const double expected = expectedFactor([](double a) { return 0.5 * std::cos(a); });
    EXPECT_NEAR(svf[50 * 101 + 20], expected, 1e-6);
    EXPECT_LT(expected, 0.95);
}

TEST(SkyView, AValleyFloorSeesLessThanItsRidge) {
    // A V running north-south, walls rising 1 m a metre east and west of x = 100.
    const GeoGrid g = gridOf([](double x, double) { return std::fabs(x - 100); });
    const auto svf = skyViewFactor(g, {.radiusM = 30});
    const double floor = expectedFactor([](double a) { return std::fabs(std::cos(a)); });
    EXPECT_NEAR(svf[50 * 101 + 50], floor, 1e-6);  // the floor, 30 m from either edge
    EXPECT_GT(svf[50 * 101 + 80], floor + 0.1);    // up the wall, the other wall lower in view
}

TEST(SkyView, OneAnswerForAnyThreadCountAndMaskedNodesGetOne) {
    GeoGrid g = gridOf([](double x, double y) { return 10 * std::sin(x / 17) * std::cos(y / 23); });
    g.masked.assign(g.grid.points.size(), 0);
    g.masked[40 * 101 + 40] = 1;
    const auto one = skyViewFactor(g, {.threads = 1});
    const auto two = skyViewFactor(g, {.threads = 2});
    EXPECT_EQ(one, two);
    EXPECT_EQ(one[40 * 101 + 40], 1.0f);
    EXPECT_DOUBLE_EQ(skyViewRadiusM(g, {}), 200.0 / 40 < 8 ? 8.0 : 200.0 / 40);
}

}  // namespace
}  // namespace relief::geo
