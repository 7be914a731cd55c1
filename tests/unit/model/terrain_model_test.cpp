#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <random>
#include <tuple>
#include <vector>

#include "emit/adaptive_mesh.h"
#include "model/terrain_model.h"

namespace relief::model {
namespace {

// A hilly 17 x 13 lattice 10 m apart, its nodes without data given by `masked`.
geo::GeoGrid hills(const std::vector<std::uint8_t>& masked) {
    geo::GeoGrid g;
    g.grid.rows = 13, g.grid.cols = 17;
    g.x0 = 500000, g.y0 = 4000000, g.dx = g.dy = 10;
    for (int r = 0; r < 13; ++r)
        for (int c = 0; c < 17; ++c)
            g.grid.points.push_back({g.x0 + 10.0 * c, g.y0 + 10.0 * r, 100 + 20 * std::sin(0.4 * c) * std::cos(0.3 * r)});
    g.masked = masked;
    return g;
}

Vec3 minus(const Vec3& a, const Vec3& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
Vec3 cross(const Vec3& a, const Vec3& b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }

// A closed solid facing out: corners taken by their positions (the walls have vertices of their
// own), every directed edge as often as its reverse (once each, two triangles an edge in opposite
// directions, where `manifold`: holes that touch each other only at a corner pinch the solid
// there, the vertical edge under that node with four walls); every triangle facing as its
// vertices' normals say (unit; the surface's up, the floor's down, the walls' level); the volume
// (divergence theorem) positive, and the surface's triangles those of the mesh.
void expectClosedSolid(const TerrainModel& m, size_t surfaceTriangles, bool manifold) {
    std::map<std::tuple<double, double, double>, std::uint32_t> at;
    std::vector<std::uint32_t> corner(m.positions.size());
    for (size_t v = 0; v < m.positions.size(); ++v)
        corner[v] = at.try_emplace({m.positions[v].x, m.positions[v].y, m.positions[v].z}, static_cast<std::uint32_t>(v))
                        .first->second;
    ASSERT_EQ(m.normals.size(), m.positions.size());
    std::map<std::pair<std::uint32_t, std::uint32_t>, int> edges;
    double volume = 0;
    for (const ModelPart& part : m.parts)
        for (const auto& f : part.faces) {
            for (int k = 0; k < 3; ++k) ++edges[{corner[f[k]], corner[f[(k + 1) % 3]]}];
            const Vec3 &a = m.positions[f[0]], &b = m.positions[f[1]], &c = m.positions[f[2]];
            const Vec3 n = cross(minus(b, a), minus(c, a));
            volume += (a.x * n.x + a.y * n.y + a.z * n.z) / 6;
            const double length = std::sqrt(n.x * n.x + n.y * n.y + n.z * n.z);
            for (const std::uint32_t v : f) {
                const Vec3& vn = m.normals[v];
                EXPECT_NEAR(vn.x * vn.x + vn.y * vn.y + vn.z * vn.z, 1, 1e-9);
                const double facing = (vn.x * n.x + vn.y * n.y + vn.z * n.z) / length;
                if (part.name == "surface") {
                    EXPECT_GT(facing, 0) << part.name;  // the full surface's normal, near the triangle's
                    EXPECT_GT(vn.z, 0);
                } else {
                    EXPECT_NEAR(facing, 1, 1e-9) << part.name;  // flat: the triangle's own
                }
            }
        }
    for (const auto& [edge, count] : edges) {
        if (manifold) {
            ASSERT_EQ(count, 1) << edge.first << "-" << edge.second;
        }
        const auto back = edges.find({edge.second, edge.first});
        ASSERT_TRUE(back != edges.end()) << "an open edge " << edge.first << "-" << edge.second;
        ASSERT_EQ(back->second, count) << edge.first << "-" << edge.second;
    }
    EXPECT_GT(volume, 0);
    ASSERT_NE(m.part("surface"), nullptr);
    EXPECT_EQ(m.part("surface")->faces.size(), surfaceTriangles);
}

// Whatever the holes (none, one node, a corner, a run; random nodes, a tenth and a third of the
// lattice, whose holes touch at corners), and whether the mesh is every node's or the adaptive
// one: a closed solid facing out.
TEST(TerrainModel, ClosedSolidWhateverTheHoles) {
    std::vector<std::vector<std::uint8_t>> masks(6, std::vector<std::uint8_t>(13 * 17, 0));
    masks[1][6 * 17 + 8] = 1;
    masks[2][0] = masks[2][1] = masks[2][17] = 1;
    for (int c = 3; c < 12; ++c) masks[3][5 * 17 + c] = 1;
    std::mt19937 random(7);
    for (int k = 4; k < 6; ++k)
        for (auto& m : masks[k]) m = std::uniform_real_distribution<double>(0, 1)(random) < (k == 4 ? 0.1 : 0.33);
    for (size_t k = 0; k < masks.size(); ++k) {
        SCOPED_TRACE(k);
        geo::GeoGrid grid = hills(k == 0 ? std::vector<std::uint8_t>{} : masks[k]);
        scene::LookSpec look;
        const emit::ScenePlacement where = emit::placeTerrain(grid, look);
        const double floor = where.zMinM - 5;
        const emit::Mesh full = emit::buildMesh(grid, where);
        const bool manifold = k < 4;
        expectClosedSolid(terrainModel(full, floor), static_cast<size_t>(full.triangles), manifold);
        const emit::Mesh adaptive = emit::buildAdaptiveMesh(grid, where, 2.0);
        expectClosedSolid(terrainModel(adaptive, floor), adaptive.faces.size(), manifold);
        // Without a floor: the surface alone, every vertex the mesh's.
        const TerrainModel open = terrainModel(full, std::nullopt);
        EXPECT_EQ(open.parts.size(), 1u);
        EXPECT_EQ(open.positions.size(), full.vertices);
    }
}

// Positions are metres from the scene's origin, x east, y north, z the height drawn; --scale
// makes the wider side that many millimetres and scales heights alike.
TEST(TerrainModel, MetresFromTheOriginAndScaledToMillimetres) {
    geo::GeoGrid grid = hills({});
    const emit::ScenePlacement where = emit::placeTerrain(grid, scene::LookSpec{});
    const emit::Mesh mesh = emit::buildMesh(grid, where);
    TerrainModel m = terrainModel(mesh, std::nullopt);
    for (size_t node : {size_t{0}, size_t{16}, size_t{100}, size_t{220}}) {
        const Vec3& p = grid.grid.points[node];
        const Vec3& q = m.positions[mesh.vertexOf(node)];
        EXPECT_NEAR(q.x, p.x - where.originM.x, 1e-9);
        EXPECT_NEAR(q.y, p.y - where.originM.y, 1e-9);
        EXPECT_NEAR(q.z, p.z, 1e-9);
        EXPECT_EQ(m.colours[mesh.vertexOf(node)], where.paletteColors[emit::paletteIndex(where, p.z)]);
    }
    // The still's colours: a fade (net.unsupported = "fade") washes them here as there.
    emit::ScenePlacement faded = where;
    faded.fade = std::make_shared<const std::vector<std::uint8_t>>(grid.grid.points.size(), std::uint8_t{emit::kFadeLevels});
    const emit::Mesh fadedMesh = emit::buildMesh(grid, faded);
    const TerrainModel washed = terrainModel(fadedMesh, std::nullopt);
    const LinearRgb ramp = where.paletteColors[emit::paletteIndex(where, grid.grid.points[7].z)];
    EXPECT_EQ(washed.colours[fadedMesh.vertexOf(7)], mix(ramp, emit::kFadeColour, emit::kFadeOpacity));
    const double z = m.positions[0].z;
    scaleAcross(m, 150);  // 160 m across
    EXPECT_NEAR(m.unitsPerMetre, 150.0 / 160, 1e-12);
    double xmin = 1e300, xmax = -1e300;
    for (const Vec3& p : m.positions) xmin = std::min(xmin, p.x), xmax = std::max(xmax, p.x);
    EXPECT_NEAR(xmax - xmin, 150, 1e-9);
    EXPECT_NEAR(m.positions[0].z, z * 150 / 160, 1e-9);
}

// The formats by extension, any case; none for one relief does not write.
TEST(TerrainModel, FormatsByExtension) {
    EXPECT_EQ(modelFormatOf("a/b.GLB")->format, ModelFormat::Glb);
    EXPECT_EQ(modelFormatOf("x.stl")->format, ModelFormat::Stl);
    EXPECT_TRUE(modelFormatOf("x.stl")->solid);
    EXPECT_FALSE(modelFormatOf("x.ply")->yUp);
    EXPECT_EQ(modelFormatOf("x.3ds"), nullptr);
    EXPECT_EQ(modelFormatOf("glb"), nullptr);
    EXPECT_EQ(modelExtensionsListed(), "`.glb`, `.gltf`, `.stl`, `.obj` or `.ply`");
}

}  // namespace
}  // namespace relief::model
