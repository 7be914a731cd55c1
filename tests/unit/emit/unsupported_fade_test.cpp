#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include "emit/mesh.h"
#include "emit/sky_light.h"
#include "emit/unsupported_fade.h"

namespace relief::emit {
namespace {

// 5 x 5 nodes 100 m apart whose distance from the data is their distance east of the west edge:
// bilinear between them, the distance at any point is its x (clamped to the net).
struct EastwardReach {
    geo::GeoGrid net;
    std::vector<float> reachM;
    EastwardReach() {
        net.grid.rows = net.grid.cols = 5;
        net.x0 = 1000, net.y0 = 2000, net.dx = net.dy = 100;
        for (int r = 0; r < 5; ++r)
            for (int c = 0; c < 5; ++c) {
                net.grid.points.push_back({1000.0 + 100 * c, 2000.0 + 100 * r, 0});
                reachM.push_back(static_cast<float>(100 * c));
            }
    }
};

// Points swept across the net and beyond it, west to east, on three rows (south edge, middle, north edge).
geo::GeoGrid sweep(int across) {
    geo::GeoGrid g;
    g.grid.rows = 3, g.grid.cols = across;
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < across; ++c) g.grid.points.push_back({950 + 500.0 * c / (across - 1), 2000 + 200.0 * r, 0});
    return g;
}

// Whatever the distance the fade starts from: none up to it, the most from twice it, never less
// eastwards (farther from the data), and the smoothstep between, to its rounding.
TEST(UnsupportedFade, NoneWithinTheDataTheMostFromTwiceThatAndMoreTheFartherBetween) {
    const EastwardReach reach;
    const geo::GeoGrid points = sweep(201);
    for (const double fromM : {25.0, 60.0, 100.0, 150.0, 199.0, 400.0}) {
        SCOPED_TRACE(fromM);
        const std::vector<std::uint8_t> fade = unsupportedFade(reach.net, reach.reachM, fromM, points);
        ASSERT_EQ(fade.size(), points.grid.points.size());
        for (int r = 0; r < 3; ++r)
            for (int c = 0; c < 201; ++c) {
                const size_t node = static_cast<size_t>(r) * 201 + c;
                const double distance = std::clamp(points.grid.points[node].x - 1000, 0.0, 400.0);
                if (distance <= fromM) {
                    EXPECT_EQ(fade[node], 0) << distance;
                }
                if (distance >= 2 * fromM) {
                    EXPECT_EQ(fade[node], kFadeLevels) << distance;
                }
                const double t = std::clamp(distance / fromM - 1, 0.0, 1.0);
                EXPECT_NEAR(fade[node], t * t * (3 - 2 * t) * kFadeLevels, 0.5 + 1e-9) << distance;
                if (c) {
                    EXPECT_GE(fade[node], fade[node - 1]) << distance;
                }
                EXPECT_EQ(fade[node], fade[c]) << "the same distance on another row";
            }
    }
    // No distance to fade from (every node a sample): nothing fades.
    const auto none = unsupportedFade(reach.net, reach.reachM, 0, points);
    EXPECT_TRUE(std::all_of(none.begin(), none.end(), [](std::uint8_t f) { return f == 0; }));
}

// A fade washes a node's colour towards kFadeColour after its fill, before its light, and a
// mesh2's texture list holds exactly the colours every other geometry draws.
TEST(UnsupportedFade, ColoursEveryGeometryDraws) {
    const EastwardReach reach;
    geo::GeoGrid terrain = reach.net;
    for (size_t i = 0; i < terrain.grid.points.size(); ++i) terrain.grid.points[i].z = 10.0 * (i % 5) + i / 5;
    ScenePlacement where = placeTerrain(terrain, scene::LookSpec{});
    where.fade = std::make_shared<const std::vector<std::uint8_t>>(unsupportedFade(reach.net, reach.reachM, 100, terrain));
    const LinearRgb base{0.2, 0.4, 0.1};
    EXPECT_EQ(where.nodeColour(0, base), base);  // on the data
    EXPECT_EQ(where.fadeAt(4), unsigned(kFadeLevels));
    const LinearRgb faded = where.nodeColour(4, base);
    EXPECT_EQ(faded, mix(base, kFadeColour, kFadeOpacity));
    auto fills = std::make_shared<NodeFills>();
    fills->fillOf.assign(25, 1);
    fills->fills.push_back({{1, 0, 0}, 0.5});
    where.fills = fills;
    EXPECT_EQ(where.nodeColour(4, base), mix(mix(base, {1, 0, 0}, 0.5), kFadeColour, kFadeOpacity));
    where.fills = nullptr;

    Mesh mesh = buildMesh(terrain, where);
    nodeTextures(mesh);
    ASSERT_FALSE(mesh.litTexture.empty());
    for (size_t node = 0; node < 25; ++node) {
        SCOPED_TRACE(node);
        EXPECT_EQ(mesh.textureColours()[mesh.palette(node)], where.nodeColour(node, where.paletteColors[mesh.basePalette(node)]));
    }
    EXPECT_NE(mesh.textureColours()[mesh.palette(4)], mesh.paletteColors[mesh.basePalette(4)]);
}

}  // namespace
}  // namespace relief::emit
