// Contour ribbons on a cone (z = 100 - r): each level's line is a circle of
// radius 100 - level, and every ribbon vertex lies within its half width of
// it, on the surface (lifted a fifth of the width), never NaN.

#include <gtest/gtest.h>

#include <cmath>

#include "emit/mesh.h"
#include "emit/surface_contours.h"

namespace relief::emit {
namespace {

TEST(SurfaceContours, RingsOnAConeLieOnItsCircles) {
    geo::GeoGrid grid;
    grid.grid.rows = grid.grid.cols = 121;
    grid.x0 = 500000 - 60, grid.y0 = 5000000 - 60;
    grid.dx = grid.dy = 1;
    for (int r = 0; r < 121; ++r)
        for (int c = 0; c < 121; ++c) {
            const double x = c - 60.0, y = r - 60.0;
            grid.grid.points.push_back({grid.x0 + c, grid.y0 + r, 100 - std::hypot(x, y)});
        }
    scene::LookSpec look;
    look.vertical.exaggeration = 2;
    const ScenePlacement where = placeTerrain(grid, look);
    scene::ContourSpec spec;
    spec.intervalM = 10;
    const double widthM = 0.8;
    Diagnostics diags;
    const auto built = buildSurfaceContours(grid, where, spec, widthM, {}, diags);
    ASSERT_TRUE(built) << (diags.all().empty() ? "" : diags.all().front().message);
    const ContourRibbons& ribbons = *built;
    // Levels 20 to 100 over the surface's 15.1..100 m: 90 and below reach the grid (100 is the apex).
    EXPECT_EQ(ribbons.made.levels, 9);
    EXPECT_GE(ribbons.made.lines, 7);
    ASSERT_GT(ribbons.ribbons.vertices.size(), 100u);
    EXPECT_EQ(ribbons.ribbons.faces.size() % 2, 0u);
    for (const SceneVec3& v : ribbons.ribbons.vertices) {
        ASSERT_TRUE(std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z));
        const double x = v.x * where.metresPerUnit + where.originM.x - 500000;
        const double y = v.z * where.metresPerUnit + where.originM.y - 5000000;
        const double r = std::hypot(x, y), height = v.y * where.metresPerUnit / look.vertical.exaggeration;
        // The nearest level's circle: within the (index line's) half width and the simplification's quarter width.
        const double level = std::round((100 - r) / 10) * 10;
        EXPECT_NEAR(r, 100 - level, widthM + 0.25 * widthM + 0.05) << x << "," << y;
        // On the cone (bilinear between nodes: within 0.3 m near the apex), lifted.
        EXPECT_NEAR(height, 100 - r, 0.35) << x << "," << y;
    }
    EXPECT_LT(ribbons.ribbons.sdlBytes(), 2e6);
}

}  // namespace
}  // namespace relief::emit
