#include "emit/adaptive_mesh.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <optional>
#include <vector>

namespace relief::emit {

namespace {

struct Node {
    int x, y;  // column and row in the lattice
};

// The error hierarchy over the (S + 1)^2 square holding the lattice (S a power of two).
class Rtin {
public:
    // `colour(z)`: the ramp's colour at height z. A mesh2 interpolates its vertex
    // colours linearly across a triangle; where the ramp bends (a coastline's
    // blue to green) a large triangle would smear it, so a midpoint whose colour
    // the interpolation misses by more than kColourTolerance forces a split as a
    // node without data does.
    // Heights are the drawn ones (ScenePlacement::drawnHeight), colours by elevation.
    // `toleranceAt(m)`, if given: each midpoint's error is in units of the tolerance there (split
    // above 1), which keeps the hierarchy nested (a parent's is the largest of its children's).
    Rtin(const geo::GeoGrid& grid, const ScenePlacement& where, std::function<LinearRgb(double)> colour,
         std::function<double(const Vec3&)> toleranceAt = {})
        : grid_(grid), where_(where), cols_(grid.cols()), rows_(grid.rows()), colour_(std::move(colour)),
          toleranceAt_(std::move(toleranceAt)) {
        size_ = 1;
        while (size_ < std::max(cols_ - 1, rows_ - 1)) size_ *= 2;
        error_.assign(static_cast<size_t>(size_ + 1) * (size_ + 1), 0.0f);
        computeErrors();
    }

    int size() const { return size_; }
    float error(Node m) const { return error_[index(m)]; }
    bool hasData(Node n) const {
        return n.x < cols_ && n.y < rows_ && !grid_.isMasked(n.y, n.x);
    }

private:
    size_t index(Node n) const { return static_cast<size_t>(n.y) * (size_ + 1) + n.x; }
    double z(Node n) const { return where_.drawnHeight(grid_.grid.at(n.y, n.x)); }
    double toleranceAt(Node n) const { return toleranceAt_(grid_.grid.at(n.y, n.x)); }
    LinearRgb colourOf(Node n) const { return colour_(where_.elevation(grid_.grid.at(n.y, n.x))); }

    // The vertical error at midpoint m of hypotenuse (a, b); infinite when the
    // triangle pair around it touches a node without data (the right-angle
    // corners c1, c2 of the two triangles included).
    float localError(Node a, Node b, Node m, Node c1, Node c2) const {
        constexpr float kInf = std::numeric_limits<float>::infinity();
        if (!hasData(a) || !hasData(b) || !hasData(m)) return kInf;
        const bool in1 = c1.x >= 0 && c1.y >= 0 && c1.x <= size_ && c1.y <= size_;
        const bool in2 = c2.x >= 0 && c2.y >= 0 && c2.x <= size_ && c2.y <= size_;
        if ((in1 && !hasData(c1)) || (in2 && !hasData(c2))) return kInf;
        const LinearRgb ca = colourOf(a), cb = colourOf(b), cm = colourOf(m);
        const double miss = std::max({std::fabs(cm.r - 0.5 * (ca.r + cb.r)), std::fabs(cm.g - 0.5 * (ca.g + cb.g)),
                                      std::fabs(cm.b - 0.5 * (ca.b + cb.b))});
        if (miss > kColourTolerance) return kInf;
        const double error = std::fabs(z(m) - 0.5 * (z(a) + z(b)));
        if (!toleranceAt_) return static_cast<float>(error);
        // The least tolerance over the triangle pair's corners: a node inside keeps to its own.
        double least = std::min({toleranceAt(a), toleranceAt(b), toleranceAt(m)});
        if (in1 && c1.x < cols_ && c1.y < rows_) least = std::min(least, toleranceAt(c1));
        if (in2 && c2.x < cols_ && c2.y < rows_) least = std::min(least, toleranceAt(c2));
        return static_cast<float>(error / least);
    }
    static constexpr double kColourTolerance = 0.01;  // linear RGB, 0..1

    void raise(Node m, float e) {
        float& slot = error_[index(m)];
        slot = std::max(slot, e);
    }
    float at(Node n) const {
        return n.x >= 0 && n.y >= 0 && n.x <= size_ && n.y <= size_ ? error_[index(n)] : 0.0f;
    }

    // Finest level first: edge midpoints of squares of side s (their triangles'
    // children are the diagonals of the squares of side s / 2), then the
    // centres of squares of side s (children: the squares' sides), s = 2, 4, ...
    void computeErrors() {
        for (int s = 2; s <= size_; s *= 2) {
            const int h = s / 2, q = s / 4;
            // Edges of length s: horizontal (x + h, y) and vertical (x, y + h).
            for (int y = 0; y <= size_; y += s)
                for (int x = 0; x < size_; x += s) edge({x, y}, {x + s, y}, {x + h, y}, {0, h}, q);
            for (int y = 0; y < size_; y += s)
                for (int x = 0; x <= size_; x += s) edge({x, y}, {x, y + s}, {x, y + h}, {h, 0}, q);
            // Centres of squares of side s: the diagonal radiates from the centre of
            // the square of side 2s around it (the top square: from (0, 0)).
            for (int y = 0; y < size_; y += s)
                for (int x = 0; x < size_; x += s) {
                    const Node m{x + h, y + h};
                    Node a, b;
                    if (s == size_) {
                        a = {0, 0}, b = {size_, size_};
                    } else {
                        const Node centre{x / (2 * s) * (2 * s) + s, y / (2 * s) * (2 * s) + s};
                        a = centre, b = {2 * x + s - centre.x, 2 * y + s - centre.y};
                    }
                    // The other diagonal's ends are the two triangles' right-angle corners.
                    const Node c1{a.x, b.y}, c2{b.x, a.y};
                    float e = localError(a, b, m, c1, c2);
                    for (const Node child : {Node{x + h, y}, Node{x + h, y + s}, Node{x, y + h}, Node{x + s, y + h}})
                        e = std::max(e, at(child));
                    raise(m, e);
                }
        }
    }

    // An axis-aligned hypotenuse (a, b) with midpoint m; `across` points from m
    // to the right-angle corners on either side; the children's midpoints are
    // the centres of the squares of side s / 2 beside the edge (q = s / 4).
    void edge(Node a, Node b, Node m, Node across, int q) {
        const Node c1{m.x + across.x, m.y + across.y}, c2{m.x - across.x, m.y - across.y};
        float e = localError(a, b, m, c1, c2);
        if (q > 0) {
            const int ax = across.x ? 1 : 0, ay = across.y ? 1 : 0;  // which way is across
            for (int side : {-1, 1})
                for (int along : {-1, 1})
                    e = std::max(e, at({m.x + side * q * ax + along * q * ay, m.y + side * q * ay + along * q * ax}));
        }
        raise(m, e);
    }

    const geo::GeoGrid& grid_;
    const ScenePlacement& where_;
    int cols_, rows_;
    std::function<LinearRgb(double)> colour_;
    std::function<double(const Vec3&)> toleranceAt_;
    int size_ = 1;
    std::vector<float> error_;
};

}  // namespace

namespace {

bool followsPixels(const PixelTolerance* perPixel) {
    return perPixel && perPixel->camera && perPixel->camera->perspective && !perPixel->camera->wide;
}

// The tolerance at each point of a perspective view (PixelTolerance), with
// what every point shares worked out once.
class ToleranceField {
public:
    ToleranceField(const ScenePlacement& where, double toleranceM, const PixelTolerance& perPixel)
        : where_(where), view_(*perPixel.camera), toleranceM_(toleranceM), W_(perPixel.widthPx), H_(perPixel.heightPx) {
        forward_ = (1.0 / length(view_.target - view_.eye)) * (view_.target - view_.eye);
        // The depth before the eye at which a pixel's footprint is the finest's.
        nearestDepth_ = finestMetresPerPixel(view_, where, W_) * W_ / (2 * view_.tanHalfFov * where.metresPerUnit);
    }
    double at(const Vec3& p) const {
        const SceneVec3 q = where_.scenePoint(p);
        const double depth = dot(q - view_.eye, forward_);
        const auto onImage = projectToImage(view_, q, W_, H_);
        const bool seen = depth > 0 && onImage[0] >= -0.1 * W_ && onImage[0] <= 1.1 * W_ && onImage[1] >= -0.1 * H_ &&
                          onImage[1] <= 1.1 * H_;
        const double wider = std::max(1.0, (depth > 0 ? depth : length(q - view_.eye)) / nearestDepth_);
        return toleranceM_ * wider * (seen ? 1 : 16);
    }

private:
    const ScenePlacement& where_;
    const CameraView& view_;
    double toleranceM_;
    double W_, H_;
    SceneVec3 forward_;
    double nearestDepth_ = 1;
};

}  // namespace

double adaptiveToleranceAt(const Vec3& p, const ScenePlacement& where, double toleranceM,
                           const PixelTolerance* perPixel) {
    return followsPixels(perPixel) ? ToleranceField(where, toleranceM, *perPixel).at(p) : toleranceM;
}

Mesh buildAdaptiveMesh(const geo::GeoGrid& refined, const ScenePlacement& where, double toleranceM,
                       const PixelTolerance* perPixel) {
    const Grid& g = refined.grid;
    Mesh mesh;
    static_cast<ScenePlacement&>(mesh) = where;
    mesh.grid = &refined;
    mesh.rows = g.rows;
    mesh.cols = g.cols;
    // The colour each vertex gets (its palette entry), as a function of height.
    const bool perPoint = followsPixels(perPixel);
    std::optional<ToleranceField> field;
    std::function<double(const Vec3&)> toleranceAt;
    if (perPoint) {
        field.emplace(where, toleranceM, *perPixel);
        toleranceAt = [&field](const Vec3& p) { return field->at(p); };
    }
    const Rtin rtin(refined, mesh, [&](double z) { return mesh.paletteColors[paletteIndex(mesh, z)]; }, toleranceAt);
    const int S = rtin.size();

    // Top down: split while the midpoint's error exceeds the tolerance.
    std::vector<std::array<Node, 3>> kept;
    struct Item {
        Node a, b, c;  // hypotenuse a-b, right angle at c
    };
    std::vector<Item> stack{{{0, 0}, {S, S}, {S, 0}}, {{S, S}, {0, 0}, {0, S}}};
    while (!stack.empty()) {
        const Item t = stack.back();
        stack.pop_back();
        const int dx = t.b.x - t.a.x, dy = t.b.y - t.a.y;
        const bool splittable = dx % 2 == 0 && dy % 2 == 0;
        const Node m{(t.a.x + t.b.x) / 2, (t.a.y + t.b.y) / 2};
        // Wholly beyond the lattice (the rest of the 2^k square): nothing to keep.
        if (std::min({t.a.x, t.b.x, t.c.x}) >= mesh.cols || std::min({t.a.y, t.b.y, t.c.y}) >= mesh.rows) continue;
        if (splittable && !(rtin.error(m) <= (perPoint ? 1 : toleranceM))) {
            stack.push_back({t.c, t.a, m});
            stack.push_back({t.b, t.c, m});
        } else if (rtin.hasData(t.a) && rtin.hasData(t.b) && rtin.hasData(t.c)) {
            kept.push_back({t.a, t.b, t.c});
        }
    }

    // Vertices: the nodes the triangles use, in lattice order (deterministic).
    mesh.vertexOfNode.assign(g.points.size(), Mesh::kNoVertex);
    for (const auto& tri : kept)
        for (const Node& n : tri) mesh.vertexOfNode[static_cast<size_t>(n.y) * g.cols + n.x] = 0;
    std::uint32_t next = 0;
    for (auto& v : mesh.vertexOfNode)
        if (v != Mesh::kNoVertex) v = next++;
    mesh.vertices = next;

    // Faces counter-clockwise seen from above (x east, y north), in a fixed order.
    mesh.faces.reserve(kept.size());
    for (const auto& tri : kept) {
        std::array<std::uint32_t, 3> f;
        for (int k = 0; k < 3; ++k) f[k] = static_cast<std::uint32_t>(static_cast<size_t>(tri[k].y) * g.cols + tri[k].x);
        const long cross2 = static_cast<long>(tri[1].x - tri[0].x) * (tri[2].y - tri[0].y) -
                            static_cast<long>(tri[1].y - tri[0].y) * (tri[2].x - tri[0].x);
        if (cross2 < 0) std::swap(f[1], f[2]);
        mesh.faces.push_back(f);
    }
    mesh.triangles = static_cast<long long>(mesh.faces.size());
    return mesh;
}

}  // namespace relief::emit
