#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "film/flyover.h"

namespace relief::film {
namespace {

// A ground 1000 m square at 10 m spacing, its height height(x, y).
template <class F>
geo::GeoGrid groundGrid(F height) {
    geo::GeoGrid g;
    g.dx = g.dy = 10;
    g.grid.rows = g.grid.cols = 101;
    for (int r = 0; r < 101; ++r)
        for (int c = 0; c < 101; ++c) g.grid.points.push_back({c * 10.0, r * 10.0, height(c * 10.0, r * 10.0)});
    return g;
}

TEST(CentripetalCatmullRom, PassesThroughEveryPointAndIsStraightOnALine) {
    const std::vector<Vec3> points{{0, 0, 0}, {100, 50, 10}, {300, 40, 0}, {400, 200, 30}};
    const std::vector<int> steps{10, 20, 10};
    const auto curve = centripetalCatmullRom(points, steps);
    ASSERT_EQ(curve.size(), 41u);
    EXPECT_EQ(curve[0], points[0]);
    EXPECT_NEAR(length(curve[10] - points[1]), 0, 1e-9);
    EXPECT_NEAR(length(curve[30] - points[2]), 0, 1e-9);
    EXPECT_EQ(curve[40], points[3]);
    // Collinear points, unevenly spaced: the curve stays on their line.
    const std::vector<Vec3> line{{0, 0, 0}, {10, 10, 0}, {100, 100, 0}};
    for (const Vec3& p : centripetalCatmullRom(line, std::vector<int>{8, 8})) EXPECT_NEAR(p.x, p.y, 1e-9);
}

TEST(CentripetalCatmullRom, NoLoopAtASharpTurn) {
    // A hairpin: the uniform spline loops past the turn; the centripetal one stays between the points.
    const std::vector<Vec3> hairpin{{0, 0, 0}, {100, 0, 0}, {100, 5, 0}, {0, 5, 0}};
    for (const Vec3& p : centripetalCatmullRom(hairpin, std::vector<int>{50, 50, 50})) {
        EXPECT_LE(p.x, 100 + 3.0);
        EXPECT_GE(p.y, -3.0);
        EXPECT_LE(p.y, 8.0);
    }
}

TEST(FlyoverCameras, ConstantGroundSpeedAlongACurve) {
    const geo::GeoGrid flat = groundGrid([](double, double) { return 0.0; });
    const Ground ground(flat);
    FlyoverPath path;
    path.points = {{100, 100, 0}, {500, 150, 0}, {800, 600, 0}, {300, 900, 0}};
    path.aboveGroundM = 50;
    const auto cams = flyoverCameras(path, 40, ground);
    ASSERT_EQ(cams.size(), 40u);
    EXPECT_NEAR(cams.front().eyeM.x, 100, 1e-9);
    EXPECT_NEAR(cams.back().eyeM.y, 900, 1e-9);
    const auto step = [&](size_t k) {
        return std::hypot(cams[k].eyeM.x - cams[k - 1].eyeM.x, cams[k].eyeM.y - cams[k - 1].eyeM.y);
    };
    for (size_t k = 2; k < cams.size(); ++k) EXPECT_NEAR(step(k), step(1), 0.01 * step(1)) << k;
    for (const auto& c : cams) {
        EXPECT_DOUBLE_EQ(c.eyeM.z, 50);    // flat ground
        EXPECT_DOUBLE_EQ(c.targetM.z, 0);  // looking at the ground
    }
}

TEST(FlyoverCameras, RisesBeforeARidgeAndLooksAhead) {
    // A ridge 200 m high along x = 500, 20 m wide; the path crosses it west to east.
    const geo::GeoGrid ridge = groundGrid([](double x, double) { return std::abs(x - 500) < 10 ? 200.0 : 0.0; });
    const Ground ground(ridge);
    FlyoverPath path;
    path.points = {{100, 500, 0}, {900, 500, 0}};
    path.aboveGroundM = 100;
    path.lookAheadM = 150;
    const auto cams = flyoverCameras(path, 81, ground);  // one every 10 m
    for (const auto& c : cams) {
        EXPECT_GT(c.eyeM.z, ground.highestAt(c.eyeM.x, c.eyeM.y));
        EXPECT_NEAR(c.targetM.x, c.eyeM.x + 150, 1e-6);  // the ground 150 m on, past the end straight on
        EXPECT_NEAR(c.targetM.y, 500, 1e-6);
        // Within 100 m of the ridge, before and after, the eye is 100 m over its top.
        if (std::abs(c.eyeM.x - 500) < 85) {
            EXPECT_NEAR(c.eyeM.z, 300, 1e-6) << c.eyeM.x;
        }
        if (std::abs(c.eyeM.x - 500) > 115) {
            EXPECT_NEAR(c.eyeM.z, 100, 1e-6) << c.eyeM.x;
        }
    }
}

TEST(FlyoverCameras, OwnHeightsAndAFixedTarget) {
    const geo::GeoGrid flat = groundGrid([](double, double) { return 20.0; });
    const Ground ground(flat);
    FlyoverPath path;
    path.points = {{100, 100, 300}, {900, 100, 500}};
    path.lookAtM = Vec3{500, 800, 20};
    const auto cams = flyoverCameras(path, 5, ground);
    EXPECT_NEAR(cams.front().eyeM.z, 300, 1e-9);
    EXPECT_NEAR(cams.back().eyeM.z, 500, 1e-9);
    for (const auto& c : cams) EXPECT_EQ(c.targetM, (Vec3{500, 800, 20}));
    EXPECT_DOUBLE_EQ(ground.heightAt(-50, 2000), 20);  // outside: the nearest edge
    EXPECT_TRUE(ground.covers(0, 1000));
    EXPECT_FALSE(ground.covers(-0.1, 500));
}

}  // namespace
}  // namespace relief::film
