// A [[layer]] on the terrain: a point behind a cone is hidden from the eye and
// one on its near face is seen; a ribbon's vertices lie on the surface and
// within its half width of the line; a dashed line leaves its gaps; a polygon
// with a hole tints the nodes inside it and not those in the hole; a point
// off the terrain is a warning naming it.

#include <gtest/gtest.h>

#include <cmath>

#include "emit/camera.h"
#include "emit/mesh.h"
#include "emit/surface_layers.h"
#include "geo/normalize.h"

namespace relief::emit {
namespace {

// A cone 100 m high, 60 m across its foot, on a 121 x 121 grid of 1 m in UTM zone 60S.
geo::GeoGrid cone() {
    geo::GeoGrid grid;
    grid.frame.kind = scene::FrameKind::Utm;
    grid.frame.utmZone = 60;
    grid.frame.northp = false;
    grid.grid.rows = grid.grid.cols = 121;
    grid.x0 = 300000 - 60, grid.y0 = 5917000 - 60;
    grid.dx = grid.dy = 1;
    for (int r = 0; r < 121; ++r)
        for (int c = 0; c < 121; ++c)
            grid.grid.points.push_back({grid.x0 + c, grid.y0 + r, std::max(0.0, 60 - std::hypot(c - 60.0, r - 60.0))});
    return grid;
}

TEST(SeenFromEye, TheConeHidesWhatIsBehindIt) {
    const geo::GeoGrid grid = cone();
    scene::LookSpec look;
    look.camera.azimuthDeg = 180;  // the eye to the south
    look.camera.elevationDeg = 15;
    const ScenePlacement where = placeTerrain(grid, look);
    scene::RenderSpec render;
    const CameraView view = placeCamera(where, look, render);
    const auto seen = [&](double dx, double dy) {
        const double x = 300000 + dx, y = 5917000 + dy;
        const SceneVec3 p = where.scenePoint({x, y, *grid.sample(x, y)});
        return seenFromEye(grid, where, view, p, 0.5 * unitsPerPixelAt(view, p, render.width));
    };
    EXPECT_TRUE(seen(0, -30));    // on the near (south) face
    EXPECT_TRUE(seen(0, 0));      // the apex
    EXPECT_FALSE(seen(0, 40));    // on the plain behind the cone
    EXPECT_FALSE(seen(0, 20));    // on its far face
    EXPECT_TRUE(seen(50, -45));   // on the plain before it
}

TEST(AddRibbon, ItsVerticesLieOnTheSurfaceWithinHalfItsWidthOfTheLine) {
    geo::GeoGrid grid = cone();
    for (auto& p : grid.grid.points) p.z = 10 + 0.3 * (p.x - grid.x0) + 0.1 * (p.y - grid.y0);  // a tilted plane
    const ScenePlacement where = placeTerrain(grid, scene::LookSpec{});
    Ribbons ribbons;
    const std::vector<curves::Point2> line{{300000 - 50, 5917000 - 40}, {300000 + 40, 5917000 + 30}};
    addRibbon(ribbons, grid, where, line, {2.0, 0.5, 1.0});
    ASSERT_GT(ribbons.points, 100);  // cut into pieces of at most 1 m
    const double ux = 90 / std::hypot(90, 70), uy = 70 / std::hypot(90, 70);
    for (const SceneVec3& v : ribbons.vertices) {
        const double x = v.x * where.metresPerUnit + where.originM.x, y = v.z * where.metresPerUnit + where.originM.y;
        const double across = std::abs((x - line[0].x) * uy - (y - line[0].y) * ux);
        EXPECT_NEAR(across, 1.0, 1e-6);  // the ribbon's edges, half its width from the line
        const double ground = 10 + 0.3 * (x - grid.x0) + 0.1 * (y - grid.y0);
        EXPECT_NEAR(v.y * where.metresPerUnit, ground + 0.4, 1e-6);  // on the plane, lifted 0.4 of its half width
    }
}

TEST(AddRibbon, ADashedLineLeavesItsGaps) {
    const geo::GeoGrid grid = cone();
    const ScenePlacement where = placeTerrain(grid, scene::LookSpec{});
    Ribbons ribbons;
    const std::vector<curves::Point2> line{{300000 - 50, 5917000 - 55}, {300000 + 50, 5917000 - 55}};
    addRibbon(ribbons, grid, where, line, {1.0, 0, 1.0, {10, 10}});
    for (const SceneVec3& v : ribbons.vertices) {
        const double along = v.x * where.metresPerUnit + where.originM.x - (300000 - 50);
        EXPECT_LE(std::fmod(along + 1e-6, 20), 10 + 2e-6) << along;  // in a dash, never in a gap
    }
    EXPECT_EQ(ribbons.faces.size(), 5u * 2 * 10);  // five dashes of ten 1 m pieces
}

TEST(PlaceLayers, APolygonWithAHoleTintsWhatIsInsideAndNotTheHole) {
    const geo::GeoGrid grid = cone();
    const ScenePlacement where = placeTerrain(grid, scene::LookSpec{});
    const auto lonLat = [&](double dx, double dy) {
        return *geo::reverse(grid.frame, Vec3{300000 + dx, 5917000 + dy, 0});
    };
    geo::VectorFeature square;
    square.kind = geo::FeatureKind::Polygon;
    square.parts = {{lonLat(-40, -40), lonLat(40, -40), lonLat(40, 40), lonLat(-40, 40), lonLat(-40, -40)},
                    {lonLat(-10, -10), lonLat(10, -10), lonLat(10, 10), lonLat(-10, 10), lonLat(-10, -10)}};
    geo::VectorFeature far;
    far.kind = geo::FeatureKind::Point;
    far.fid = 7;
    far.label = "far away";
    far.parts = {{GeoPoint{175.5, -37.5, 0}}};
    geo::VectorLayer layer{"squares", {square, far}, 11, 0};
    scene::LayerSpec spec;
    spec.number = 1;
    spec.pathAsWritten = "squares.geojson";
    spec.fill = LinearRgb{0, 0, 1};
    Diagnostics diags;
    const SurfaceLayers placed = placeLayers({spec}, {layer}, grid, where, 0.5, diags);
    ASSERT_TRUE(placed.fills);
    const auto fillAt = [&](int dx, int dy) { return placed.fills->fillOf[size_t(60 + dy) * 121 + size_t(60 + dx)]; };
    EXPECT_EQ(fillAt(-30, -30), 1);
    EXPECT_EQ(fillAt(30, 20), 1);
    EXPECT_EQ(fillAt(0, 0), 0);    // in the hole
    EXPECT_EQ(fillAt(5, -5), 0);
    EXPECT_EQ(fillAt(50, 50), 0);  // outside
    EXPECT_EQ(placed.counts[0].read, 2);
    EXPECT_EQ(placed.counts[0].drawn, 1);
    EXPECT_EQ(placed.counts[0].offTerrain, 1);
    EXPECT_GT(placed.lines[0].faces.size(), 0u);  // its outline
    ASSERT_EQ(diags.warningCount(), 1);
    EXPECT_NE(diags.all().front().message.find("feature 7 (\"far away\") at lon 175.5, lat -37.5 is off the terrain"),
              std::string::npos)
        << diags.all().front().message;
    // A node's colour with the fill laid over it at its opacity.
    ScenePlacement filled = where;
    filled.fills = placed.fills;
    const size_t node = size_t(30) * 121 + 30;
    const LinearRgb c = filled.nodeColour(node, {1, 1, 1});
    EXPECT_NEAR(c.r, 1 - spec.fillOpacity, 1e-12);
    EXPECT_NEAR(c.b, 1, 1e-12);
}

// A track across nodes without data is cut there: two runs of ribbon, none of
// their vertices over the masked band.
TEST(AddRibbon, ALineIsCutWhereTheSurfaceHasNoData) {
    geo::GeoGrid grid = cone();
    grid.masked.assign(grid.grid.points.size(), 0);
    for (int r = 0; r < 121; ++r)
        for (int c = 55; c <= 65; ++c) grid.masked[size_t(r) * 121 + size_t(c)] = 1;  // a band 10 m wide, north-south
    const ScenePlacement where = placeTerrain(grid, scene::LookSpec{});
    Ribbons ribbons;
    const std::vector<curves::Point2> line{{300000 - 50, 5917000 - 50}, {300000 + 50, 5917000 - 50}};
    addRibbon(ribbons, grid, where, line, {1.0, 0, 1.0});
    int runs = 0;
    for (size_t f = 0; f < ribbons.faces.size(); f += 2)  // a quad's first vertex not the previous quad's last: a new run
        runs += f == 0 || ribbons.faces[f][0] != ribbons.faces[f - 2][0] + 2;
    EXPECT_EQ(runs, 2);
    for (const SceneVec3& v : ribbons.vertices) {
        const double x = v.x * where.metresPerUnit + where.originM.x - 300000;
        EXPECT_FALSE(x > -6 && x < 6) << x;  // nothing over the masked band (a cell either side of it)
    }
}

// A layer of a million vertices (a track traced at a centimetre) is simplified
// to the still's resolution: what POV-Ray gets is a few hundred points.
TEST(PlaceLayers, AMillionVerticesAreSimplifiedToTheStillsResolution) {
    const geo::GeoGrid grid = cone();
    const ScenePlacement where = placeTerrain(grid, scene::LookSpec{});
    geo::VectorFeature track;
    track.kind = geo::FeatureKind::Line;
    std::vector<GeoPoint>& part = track.parts.emplace_back();
    for (int i = 0; i < 1'000'000; ++i) {  // 100 m east, wobbling a millimetre
        const double x = -50 + 1e-4 * i, y = -40 + 1e-3 * std::sin(i * 0.01);
        part.push_back(*geo::reverse(grid.frame, Vec3{300000 + x, 5917000 + y, 0}));
    }
    scene::LayerSpec spec;
    spec.number = 1;
    Diagnostics diags;
    const SurfaceLayers placed = placeLayers({spec}, {geo::VectorLayer{"track", {track}, 1'000'000, 0}}, grid, where,
                                             0.5, diags);
    EXPECT_EQ(placed.counts[0].vertices, 1'000'000);
    EXPECT_EQ(placed.counts[0].drawn, 1);
    EXPECT_LT(placed.counts[0].ribbonPoints, 200);  // a point each refined metre (the pieces' length), no more
    EXPECT_GT(placed.counts[0].ribbonPoints, 90);
}

}  // namespace
}  // namespace relief::emit
