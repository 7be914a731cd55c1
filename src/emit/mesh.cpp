#include "emit/mesh.h"

#include <algorithm>
#include <cmath>

#include "scene/color_ramp.h"

namespace relief::emit {

ScenePlacement placeTerrain(const geo::GeoGrid& refined, const scene::LookSpec& look) {
    const Grid& g = refined.grid;
    ScenePlacement where;
    where.exaggeration = look.vertical.exaggeration;
    if (refined.frame.kind == scene::FrameKind::Local)
        where.curvature = std::make_shared<geo::CurvatureDrop>(refined.frame, refined.x0, refined.y0, refined.xMax(),
                                                               refined.yMax());
    double xmin = 1e300, xmax = -1e300, ymin = 1e300, ymax = -1e300, zmin = 1e300, zmax = -1e300;
    double drawnMin = 1e300, drawnMax = -1e300;
    for (size_t i = 0; i < g.points.size(); ++i) {
        if (!refined.masked.empty() && refined.masked[i]) continue;
        const Vec3& p = g.points[i];
        xmin = std::min(xmin, p.x), xmax = std::max(xmax, p.x);
        ymin = std::min(ymin, p.y), ymax = std::max(ymax, p.y);
        const double elevation = where.elevation(p), drawn = where.drawnHeight(p);
        zmin = std::min(zmin, elevation), zmax = std::max(zmax, elevation);
        drawnMin = std::min(drawnMin, drawn), drawnMax = std::max(drawnMax, drawn);
    }
    if (flatRange(zmin, zmax)) zmax = zmin;
    where.zMinM = zmin;
    where.zMaxM = zmax;
    const double extent = std::max(xmax - xmin, ymax - ymin);
    where.metresPerUnit = std::pow(10.0, std::floor(std::log10(std::max(extent, 1e-3))) - 1);
    // Whole metres-per-unit keep the origin's digits exact in the header.
    where.originM = {std::round(0.5 * (xmin + xmax)), std::round(0.5 * (ymin + ymax)), 0};
    const double s = 1.0 / where.metresPerUnit, zs = where.exaggeration * s;
    where.boundsMin = {(xmin - where.originM.x) * s, drawnMin * zs, (ymin - where.originM.y) * s};
    where.boundsMax = {(xmax - where.originM.x) * s, drawnMax * zs, (ymax - where.originM.y) * s};

    // The block model's floor: a tenth of the relief below the lowest point
    // by default (a flat terrain: a hundredth of its width).
    if (look.base.enabled) {
        const double thickness = look.base.thicknessM ? *look.base.thicknessM
                                 : zmax > zmin       ? 0.1 * (zmax - zmin)
                                                     : 0.01 * extent;
        where.baseElevationM = zmin - thickness;
    }

    // The terrain as the camera frames it: every stride-th node with data,
    // and the last row and column; with a block, the floor under each too.
    const int stride = std::max(1, std::max(g.rows, g.cols) / 100);
    const auto next = [stride](int i, int n) { return i == n - 1 ? n : std::min(i + stride, n - 1); };
    for (int r = 0; r < g.rows; r = next(r, g.rows))
        for (int c = 0; c < g.cols; c = next(c, g.cols))
            if (!refined.isMasked(r, c)) {
                where.outline.push_back(where.scenePoint(g.at(r, c)));
                if (where.baseElevationM) {
                    const SceneVec3 floor = where.scenePointAtElevation(g.at(r, c), *where.baseElevationM);
                    where.outline.push_back(floor);
                    where.boundsMin.y = std::min(where.boundsMin.y, floor.y);
                }
            }

    // Palette over the true (not exaggerated) elevation range.
    const auto stops = scene::resolveRamp(look.texture.ramp, zmin, zmax);
    const double span = zmax > zmin ? zmax - zmin : 1.0;
    where.paletteColors.resize(kPaletteSize);
    for (int k = 0; k < kPaletteSize; ++k)
        where.paletteColors[k] = scene::sampleRamp(stops, zmin + span * k / (kPaletteSize - 1));
    where.colouring = look.texture.colouring;
    where.rockFromDeg = look.texture.rockFromDeg;
    where.rockToDeg = look.texture.rockToDeg;
    const LinearRgb& rock = look.texture.rockColour;
    using C = scene::TextureSpec::Colouring;
    if (look.texture.colouring == C::Blend) {
        const std::vector<LinearRgb> ground = where.paletteColors;
        for (int k = 1; k < kBlendClasses; ++k)
            for (const auto& colour : ground)
                where.paletteColors.push_back(mix(colour, rock, double(k) / (kBlendClasses - 1)));
    } else if (look.texture.colouring == C::Slope) {
        // Pale on the flat, tan where rock begins, the rock colour where it has
        // taken over, darker on cliffs.
        const LinearRgb pale{0.90, 0.87, 0.79}, tan{0.58, 0.52, 0.40};
        const LinearRgb cliff = mix(rock, {0, 0, 0}, 0.35);
        for (int k = 0; k < kPaletteSize; ++k) {
            const double slope = kSlopePaletteMaxDeg * k / (kPaletteSize - 1);
            where.paletteColors[k] =
                slope < look.texture.rockFromDeg ? mix(pale, tan, slope / look.texture.rockFromDeg)
                : slope < look.texture.rockToDeg
                    ? mix(tan, rock,
                          (slope - look.texture.rockFromDeg) / (look.texture.rockToDeg - look.texture.rockFromDeg))
                    : mix(rock, cliff,
                          std::min(1.0, (slope - look.texture.rockToDeg) /
                                            std::max(kSlopePaletteMaxDeg - look.texture.rockToDeg, 1.0)));
        }
    }
    return where;
}

SceneVec3 surfaceNormal(const geo::GeoGrid& refined, const ScenePlacement& where, int r, int c) {
    const Grid& g = refined.grid;
    auto at = [&](int row, int col) { return where.scenePoint(g.at(row, col)); };
    const int c0 = c > 0 && !refined.isMasked(r, c - 1) ? c - 1 : c;
    const int c1 = c + 1 < g.cols && !refined.isMasked(r, c + 1) ? c + 1 : c;
    const int r0 = r > 0 && !refined.isMasked(r - 1, c) ? r - 1 : r;
    const int r1 = r + 1 < g.rows && !refined.isMasked(r + 1, c) ? r + 1 : r;
    const SceneVec3 n = cross(at(r1, c) - at(r0, c), at(r, c1) - at(r, c0));
    const double len = length(n);
    return len > 0 ? (1.0 / len) * n : SceneVec3{0, 1, 0};
}

double slopeDeg(const geo::GeoGrid& refined, const ScenePlacement& where, int r, int c) {
    const Grid& g = refined.grid;
    const int c0 = c > 0 && !refined.isMasked(r, c - 1) ? c - 1 : c;
    const int c1 = c + 1 < g.cols && !refined.isMasked(r, c + 1) ? c + 1 : c;
    const int r0 = r > 0 && !refined.isMasked(r - 1, c) ? r - 1 : r;
    const int r1 = r + 1 < g.rows && !refined.isMasked(r + 1, c) ? r + 1 : r;
    const auto e = [&](int row, int col) { return where.elevation(g.at(row, col)); };
    const double dzdx = c1 > c0 ? (e(r, c1) - e(r, c0)) / ((c1 - c0) * refined.dx) : 0.0;
    const double dzdy = r1 > r0 ? (e(r1, c) - e(r0, c)) / ((r1 - r0) * refined.dy) : 0.0;
    return std::atan(std::hypot(dzdx, dzdy)) * 180 / 3.14159265358979323846;
}

SceneVec3 Mesh::normal(size_t node) const {
    return surfaceNormal(*grid, *this, static_cast<int>(node / static_cast<size_t>(cols)),
                         static_cast<int>(node % static_cast<size_t>(cols)));
}

Mesh buildMesh(const geo::GeoGrid& refined, const ScenePlacement& where) {
    const Grid& g = refined.grid;
    Mesh mesh;
    static_cast<ScenePlacement&>(mesh) = where;
    mesh.grid = &refined;
    mesh.rows = g.rows;
    mesh.cols = g.cols;
    const size_t nodes = g.points.size();
    auto kept = [&](size_t i) { return refined.masked.empty() || refined.masked[i] == 0; };

    mesh.vertices = nodes;
    if (!refined.masked.empty()) {
        mesh.vertexOfNode.resize(nodes);
        std::uint32_t next = 0;
        for (size_t i = 0; i < nodes; ++i) mesh.vertexOfNode[i] = kept(i) ? next++ : Mesh::kNoVertex;
        mesh.vertices = next;
    }
    for (int r = 0; r + 1 < g.rows; ++r)
        for (int c = 0; c + 1 < g.cols; ++c) {
            const size_t sw = static_cast<size_t>(r) * g.cols + c, se = sw + 1, nw = sw + g.cols, ne = nw + 1;
            mesh.triangles += (kept(sw) && kept(se) && kept(nw)) + (kept(se) && kept(ne) && kept(nw));
        }
    return mesh;
}

}  // namespace relief::emit
