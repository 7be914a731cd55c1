#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <map>
#include <numeric>
#include <set>
#include <utility>

#include "emit/adaptive_mesh.h"

namespace relief::emit {
namespace {

// rows x cols nodes 10 m apart, heights from f(x, y).
template <class F>
geo::GeoGrid lattice(int rows, int cols, F f) {
    geo::GeoGrid g;
    g.grid.rows = rows;
    g.grid.cols = cols;
    for (int r = 0; r < rows; ++r)
        for (int c = 0; c < cols; ++c) g.grid.points.push_back({10.0 * c, 10.0 * r, f(10.0 * c, 10.0 * r)});
    g.dx = g.dy = 10;
    return g;
}

struct Checked {
    double area = 0;          // in cells
    double worstError = 0;    // largest vertical distance of a node from its triangle, metres
    double worstRatio = 0;    // largest of a node's distance over its tolerance (check's `tolerance`)
    int nodesCovered = 0;
    bool manifold = true;     // every edge in one or two triangles, interior edges in two
    bool tJunction = false;   // a vertex inside another triangle's edge
};

// Walks every triangle: its area, the nodes it covers and their distance from its plane, its edges.
Checked check(const Mesh& m, const geo::GeoGrid& g, const std::function<double(const Vec3&)>& tolerance = {}) {
    Checked out;
    // Faces are grid nodes: node n is column n % cols, row n / cols.
    const auto nodeOf = [&](std::uint32_t n) { return std::pair<int, int>{int(n % g.cols()), int(n / g.cols())}; };
    std::set<std::pair<int, int>> vertices;
    for (int r = 0; r < g.rows(); ++r)
        for (int c = 0; c < g.cols(); ++c)
            if (m.isVertex(size_t(r) * g.cols() + c)) vertices.insert({c, r});
    EXPECT_EQ(vertices.size(), m.vertices);
    std::map<std::pair<std::uint32_t, std::uint32_t>, int> edges;
    for (const auto& f : m.faces) {
        const auto [x0, y0] = nodeOf(f[0]);
        const auto [x1, y1] = nodeOf(f[1]);
        const auto [x2, y2] = nodeOf(f[2]);
        const double twice = double(x1 - x0) * (y2 - y0) - double(y1 - y0) * (x2 - x0);
        EXPECT_GT(twice, 0) << "not counter-clockwise";
        out.area += 0.5 * twice;
        for (int k = 0; k < 3; ++k) {
            const auto a = f[k], b = f[(k + 1) % 3];
            ++edges[{std::min(a, b), std::max(a, b)}];
            // Lattice nodes strictly inside the edge must not be vertices (T-junctions).
            const auto [ax, ay] = nodeOf(a);
            const auto [bx, by] = nodeOf(b);
            const int steps = std::gcd(std::abs(bx - ax), std::abs(by - ay));
            for (int s = 1; s < steps; ++s)
                if (vertices.count({ax + (bx - ax) / steps * s, ay + (by - ay) / steps * s})) out.tJunction = true;
        }
        // Every node inside or on the triangle against the triangle's plane.
        const double z0 = g.grid.at(y0, x0).z, z1 = g.grid.at(y1, x1).z, z2 = g.grid.at(y2, x2).z;
        for (int y = std::min({y0, y1, y2}); y <= std::max({y0, y1, y2}); ++y)
            for (int x = std::min({x0, x1, x2}); x <= std::max({x0, x1, x2}); ++x) {
                const double w1 = (double(x - x0) * (y2 - y0) - double(y - y0) * (x2 - x0)) / twice;
                const double w2 = (double(x1 - x0) * (y - y0) - double(y1 - y0) * (x - x0)) / twice;
                const double w0 = 1 - w1 - w2;
                if (w0 < -1e-12 || w1 < -1e-12 || w2 < -1e-12) continue;
                ++out.nodesCovered;
                const double error = std::fabs(g.grid.at(y, x).z - (w0 * z0 + w1 * z1 + w2 * z2));
                out.worstError = std::max(out.worstError, error);
                if (tolerance) out.worstRatio = std::max(out.worstRatio, error / tolerance(g.grid.at(y, x)));
            }
    }
    for (const auto& [edge, count] : edges)
        if (count > 2) out.manifold = false;
    return out;
}

// A grey ramp is linear in height, so only the geometry decides.
scene::LookSpec grey() {
    scene::LookSpec look;
    look.texture.ramp.preset = "grey";
    return look;
}

// A plane needs no more than the lattice's outline: two triangles for a 2^k + 1 square. With the
// terrain ramp, whose colours bend with height, the triangles split where a bend would be smeared.
TEST(AdaptiveMesh, APlaneIsTwoTrianglesUnlessItsColoursBend) {
    const auto g = lattice(17, 17, [](double x, double y) { return 100 + 0.1 * x - 0.05 * y; });
    const Mesh m = buildAdaptiveMesh(g, grey(), 0.01);
    EXPECT_EQ(m.faces.size(), 2u);
    EXPECT_EQ(m.vertices, 4u);
    EXPECT_GT(buildAdaptiveMesh(g, scene::LookSpec{}, 0.01).faces.size(), 2u);
}

// Hills on a lattice of no special size: the mesh covers every cell once, has no cracks or
// T-junctions, keeps every node within the tolerance, and needs far fewer triangles.
TEST(AdaptiveMesh, CoversTheLatticeWithinTheTolerance) {
    const auto g = lattice(45, 70, [](double x, double y) { return 50 * std::sin(x / 120) * std::cos(y / 90); });
    for (const double tol : {0.05, 0.5, 5.0}) {
        const Mesh m = buildAdaptiveMesh(g, grey(), tol);
        const Checked c = check(m, g);
        EXPECT_DOUBLE_EQ(c.area, 44.0 * 69.0) << tol;
        EXPECT_TRUE(c.manifold) << tol;
        EXPECT_FALSE(c.tJunction) << tol;
        EXPECT_LE(c.worstError, tol) << tol;
        EXPECT_LT(m.faces.size(), 2u * 44 * 69) << tol;
        EXPECT_EQ(m.triangles, static_cast<long long>(m.faces.size()));
    }
    EXPECT_LT(buildAdaptiveMesh(g, grey(), 5.0).faces.size(), buildAdaptiveMesh(g, grey(), 0.05).faces.size() / 4);
}

// A perspective view's tolerance follows its pixels (PixelTolerance), swept over the camera's
// elevation and azimuth: every node within the tolerance at its own place (the nearest terrain's
// there, wider with a pixel's footprint beyond), no cracks, and far fewer triangles than the
// nearest terrain's tolerance everywhere would keep.
TEST(AdaptiveMesh, APerspectiveViewsToleranceFollowsItsPixels) {
    const auto g = lattice(129, 129, [](double x, double y) { return 80 * std::sin(x / 90) * std::cos(y / 70); });
    const scene::LookSpec look = grey();
    const ScenePlacement where = placeTerrain(g, look);
    scene::RenderSpec render;
    render.width = 400;
    render.height = 300;
    for (const double elevation : {5.0, 20.0, 45.0})
        for (const double azimuth : {0.0, 135.0, 270.0}) {
            scene::CameraSpec camera;
            camera.elevationDeg = elevation;
            camera.azimuthDeg = azimuth;
            const CameraView view = placeCamera(where, camera, {}, render);
            const PixelTolerance perPixel{&view, render.width, render.height};
            constexpr double kNearestM = 0.05;
            const Mesh m = buildAdaptiveMesh(g, where, kNearestM, &perPixel);
            const auto tolerance = [&](const Vec3& p) { return adaptiveToleranceAt(p, where, kNearestM, &perPixel); };
            const Checked c = check(m, g, tolerance);
            const std::string at = "elevation " + std::to_string(elevation) + ", azimuth " + std::to_string(azimuth);
            EXPECT_DOUBLE_EQ(c.area, 128.0 * 128.0) << at;
            EXPECT_TRUE(c.manifold) << at;
            EXPECT_FALSE(c.tJunction) << at;
            EXPECT_LE(c.worstRatio, 1 + 1e-6) << at;
            EXPECT_LT(m.faces.size(), buildAdaptiveMesh(g, where, kNearestM).faces.size()) << at;
            // Nowhere looser than the nearest's times the widest footprint over it, nor tighter than it.
            for (const auto& p : g.grid.points) EXPECT_GE(tolerance(p), kNearestM) << at;
        }
    // An orbit's eye is far off, the footprint a few times wider across the terrain at most; an eye at
    // a place, low over one corner and looking across, sees the far ground many footprints wider:
    // far fewer triangles, each node still within the tolerance at its place.
    CameraPoints atCorner;
    atCorner.eyeM = Vec3{30, 30, 100};
    atCorner.targetM = Vec3{900, 900, 0};
    const CameraView view = placeCamera(where, scene::CameraSpec{}, atCorner, render);
    const PixelTolerance perPixel{&view, render.width, render.height};
    const Mesh near = buildAdaptiveMesh(g, where, 0.05, &perPixel);
    EXPECT_LT(near.faces.size(), buildAdaptiveMesh(g, where, 0.05).faces.size() / 3);
    EXPECT_LE(check(near, g, [&](const Vec3& p) { return adaptiveToleranceAt(p, where, 0.05, &perPixel); }).worstRatio,
              1 + 1e-6);
}

// Masked nodes leave holes: no triangle touches one, and every cell with data at its corners and
// away from the hole is still covered.
TEST(AdaptiveMesh, MaskedNodesLeaveHoles) {
    auto g = lattice(33, 33, [](double x, double y) { return 0.01 * x * y; });
    g.masked.assign(33 * 33, 0);
    for (int r = 10; r < 15; ++r)
        for (int c = 12; c < 20; ++c) g.masked[r * 33 + c] = 1;
    const Mesh m = buildAdaptiveMesh(g, grey(), 0.1);
    for (int i = 0; i < 33 * 33; ++i)
        if (g.masked[i]) {
            EXPECT_EQ(m.vertexOfNode[i], Mesh::kNoVertex);
        }
    const Checked c = check(m, g);
    // 32 x 32 cells, less the 6 x 9 that touch the 5 x 8 masked block; cut south-east to
    // north-west, the cells at the block's south-west and north-east corners keep one triangle each.
    EXPECT_DOUBLE_EQ(c.area, 32.0 * 32 - 6 * 9 + 2 * 0.5);
    EXPECT_FALSE(c.tJunction);
}

}  // namespace
}  // namespace relief::emit
