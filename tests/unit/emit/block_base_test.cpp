// The block model: walls and floor close the surface into a solid, around
// holes too; the floor sits a tenth of the relief below the lowest point.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <string>
#include <utility>

#include "emit/block_base.h"
#include "emit/mesh.h"

namespace relief::emit {
namespace {

geo::GeoGrid rampGrid(int rows, int cols) {
    geo::GeoGrid grid;
    grid.grid.rows = rows;
    grid.grid.cols = cols;
    grid.x0 = 300000;
    grid.y0 = 5900000;
    grid.dx = grid.dy = 100;
    for (int r = 0; r < rows; ++r)
        for (int c = 0; c < cols; ++c)
            grid.grid.points.push_back({grid.x0 + 100.0 * c, grid.y0 + 100.0 * r, 50.0 + 10.0 * c + 3.0 * r});
    return grid;
}

// The surface's triangles (as the mesh2 cuts the cells) and the block make a
// closed solid: every edge with a vertex on the surface belongs to exactly two
// triangles; the walls' bottom edges close into loops (every floor vertex
// meets an even number of them); and the floor covers what the surface
// covers, seen from above (its runs of cells meet the walls' feet along
// straight lines, so it is checked by area, not edge by edge).
void expectClosed(const geo::GeoGrid& grid) {
    using Key = std::pair<size_t, bool>;  // (node, on the floor)
    std::map<std::pair<Key, Key>, int> edges;
    auto add = [&](Key a, Key b, Key c) {
        for (auto [p, q] : {std::pair{a, b}, std::pair{b, c}, std::pair{c, a}}) ++edges[std::minmax(p, q)];
    };
    const auto& pts = grid.grid.points;
    auto area = [&](size_t a, size_t b, size_t c) {
        return 0.5 * std::fabs((pts[b].x - pts[a].x) * (pts[c].y - pts[a].y) -
                               (pts[c].x - pts[a].x) * (pts[b].y - pts[a].y));
    };
    const size_t cols = grid.grid.cols;
    auto kept = [&](size_t i) { return grid.masked.empty() || !grid.masked[i]; };
    double surfaceArea = 0;
    for (size_t r = 0; r + 1 < size_t(grid.grid.rows); ++r)
        for (size_t c = 0; c + 1 < cols; ++c) {
            const size_t sw = r * cols + c, se = sw + 1, nw = sw + cols, ne = nw + 1;
            if (kept(sw) && kept(se) && kept(nw)) add({sw, false}, {se, false}, {nw, false}), surfaceArea += area(sw, se, nw);
            if (kept(se) && kept(ne) && kept(nw)) add({se, false}, {ne, false}, {nw, false}), surfaceArea += area(se, ne, nw);
        }
    const BlockGeometry block = buildBlockBase(grid);
    double floorArea = 0;
    std::map<size_t, int> footDegree;
    for (const auto& f : block.faces) {
        const auto key = [&](std::uint32_t v) { return Key{block.vertices[v].node, block.vertices[v].floor}; };
        const bool floor = block.vertices[f[0]].floor && block.vertices[f[1]].floor && block.vertices[f[2]].floor;
        if (floor) {
            floorArea += area(key(f[0]).first, key(f[1]).first, key(f[2]).first);
            continue;
        }
        add(key(f[0]), key(f[1]), key(f[2]));
    }
    for (const auto& [edge, count] : edges) {
        if (edge.first.second && edge.second.second) {  // a wall's foot
            EXPECT_EQ(count, 1);
            ++footDegree[edge.first.first], ++footDegree[edge.second.first];
            continue;
        }
        EXPECT_EQ(count, 2) << "edge (" << edge.first.first << (edge.first.second ? "f" : "t") << ", "
                            << edge.second.first << (edge.second.second ? "f" : "t") << ")";
    }
    for (const auto& [node, degree] : footDegree) EXPECT_EQ(degree % 2, 0) << "node " << node;
    EXPECT_GT(surfaceArea, 0);
    EXPECT_NEAR(floorArea, surfaceArea, 1e-9 * surfaceArea);
    EXPECT_EQ(block.wallTriangles + block.floorTriangles, static_cast<long long>(block.faces.size()));
}

TEST(BlockBase, ARectangleHasFourWallsAndAFloorOfTwoTriangles) {
    const geo::GeoGrid grid = rampGrid(3, 4);
    const BlockGeometry block = buildBlockBase(grid);
    EXPECT_EQ(block.wallTriangles, 2 * (3 + 3 + 2 + 2));  // two a perimeter edge
    EXPECT_EQ(block.floorTriangles, 2);                   // the rows merged into one rectangle
    expectClosed(grid);
}

TEST(BlockBase, HolesAndNotchesAreWalledAndTheSolidStaysClosed) {
    geo::GeoGrid grid = rampGrid(9, 11);
    grid.masked.assign(99, 0);
    for (int node : {0, 1, 11,          // a notch at the south-west corner
                     4 * 11 + 5,        // one node alone in the middle
                     6 * 11 + 7, 6 * 11 + 8, 7 * 11 + 8,  // a hole of three
                     98})               // the north-east corner
        grid.masked[node] = 1;
    expectClosed(grid);
    const BlockGeometry block = buildBlockBase(grid);
    EXPECT_GT(block.wallTriangles, 2 * (8 + 8 + 10 + 10));  // the holes add walls
}

std::string written(const geo::GeoGrid& grid, const ScenePlacement& where) {
    char* data = nullptr;
    size_t size = 0;
    std::FILE* f = open_memstream(&data, &size);
    writeBlockBase(f, grid, where);
    std::fclose(f);
    std::string out(data, size);
    std::free(data);
    return out;
}

TEST(BlockBase, TheFloorIsATenthOfTheReliefBelowTheLowestPointByDefault) {
    const geo::GeoGrid grid = rampGrid(3, 4);  // 50 m to 86 m
    scene::LookSpec look;
    look.vertical.exaggeration = 2;
    const ScenePlacement where = placeTerrain(grid, look);
    ASSERT_TRUE(where.baseElevationM);
    EXPECT_DOUBLE_EQ(*where.baseElevationM, 50 - 3.6);
    // 10 m a scene unit, doubled: the floor at y = 46.4 * 2 / 10 under each corner.
    const std::string sdl = written(grid, where);
    EXPECT_NE(sdl.find("floor at 46.40 m"), std::string::npos);
    EXPECT_NE(sdl.find(",9.28000,"), std::string::npos) << sdl.substr(0, 400);
    // The camera frames the block: the bounds reach down to the floor.
    EXPECT_DOUBLE_EQ(where.boundsMin.y, 46.4 * 2 / 10);

    look.base.thicknessM = 20;
    EXPECT_DOUBLE_EQ(*placeTerrain(grid, look).baseElevationM, 30);
    look.base.enabled = false;
    EXPECT_FALSE(placeTerrain(grid, look).baseElevationM);
    EXPECT_DOUBLE_EQ(placeTerrain(grid, look).boundsMin.y, 50.0 * 2 / 10);
}

// The walls are one colour, lit mostly by the even light: no colour changes
// along them (which streaked them under every change of the surface's edge),
// and a ramp whose lowest colour is near black (a topobathy's deep sea) gives
// a wall that still reads as the block's side, not a black slab.
TEST(BlockBase, TheWallsAreOneColourNeverNearBlack) {
    const geo::GeoGrid grid = rampGrid(4, 5);
    scene::LookSpec look;
    ScenePlacement where = placeTerrain(grid, look);
    where.paletteColors.front() = {0.0, 0.0, 0.0};  // the darkest a ramp can start
    const std::string sdl = written(grid, where);
    EXPECT_EQ(sdl.find("texture_list"), std::string::npos);
    size_t textures = 0;
    for (size_t at = sdl.find("texture {"); at != std::string::npos; at = sdl.find("texture {", at + 1)) ++textures;
    EXPECT_EQ(textures, 1u);
    const LinearRgb c = blockWallColour(where);
    const double luminance = 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b;
    EXPECT_GT(luminance, 0.05);  // sRGB 63 or more: the shadowed wall (half its light even) about 45
    EXPECT_NE(sdl.find("ambient 0.5 diffuse 0.5"), std::string::npos) << sdl.substr(sdl.size() - 300);
}

}  // namespace
}  // namespace relief::emit
