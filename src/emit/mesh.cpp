#include "emit/mesh.h"

#include <algorithm>
#include <cmath>

#include "scene/color_ramp.h"

namespace relief::emit {

Mesh buildMesh(const geo::GeoGrid& refined, const scene::LookSpec& look) {
    const Grid& g = refined.grid;
    Mesh mesh;
    mesh.rows = g.rows;
    mesh.cols = g.cols;
    mesh.exaggeration = look.exaggeration;

    double xmin = 1e300, xmax = -1e300, ymin = 1e300, ymax = -1e300, zmin = 1e300, zmax = -1e300;
    for (const Vec3& p : g.points) {
        xmin = std::min(xmin, p.x), xmax = std::max(xmax, p.x);
        ymin = std::min(ymin, p.y), ymax = std::max(ymax, p.y);
        zmin = std::min(zmin, p.z), zmax = std::max(zmax, p.z);
    }
    mesh.zMinM = zmin;
    mesh.zMaxM = zmax;
    const double extent = std::max(xmax - xmin, ymax - ymin);
    mesh.metresPerUnit = std::pow(10.0, std::floor(std::log10(std::max(extent, 1e-3))) - 1);
    // Whole metres-per-unit keep the origin's digits exact in the header.
    mesh.originM = {std::round(0.5 * (xmin + xmax)), std::round(0.5 * (ymin + ymax)), 0};

    const double s = 1.0 / mesh.metresPerUnit;
    const double zs = look.exaggeration * s;
    mesh.positions.resize(g.points.size());
    for (size_t i = 0; i < g.points.size(); ++i) {
        const Vec3& p = g.points[i];
        mesh.positions[i] = {(p.x - mesh.originM.x) * s, p.z * zs, (p.y - mesh.originM.y) * s};
    }
    mesh.boundsMin = {(xmin - mesh.originM.x) * s, zmin * zs, (ymin - mesh.originM.y) * s};
    mesh.boundsMax = {(xmax - mesh.originM.x) * s, zmax * zs, (ymax - mesh.originM.y) * s};

    // Normals in scene axes from the exaggerated surface. d/dcol runs east,
    // d/drow north; cross(north, east) points up in POV-Ray's (x, y, z) = (E, U, N).
    mesh.normals.resize(g.points.size());
    const auto& P = mesh.positions;
    auto at = [&](int r, int c) { return P[static_cast<size_t>(r) * g.cols + c]; };
    for (int r = 0; r < g.rows; ++r) {
        const int r0 = std::max(r - 1, 0), r1 = std::min(r + 1, g.rows - 1);
        for (int c = 0; c < g.cols; ++c) {
            const int c0 = std::max(c - 1, 0), c1 = std::min(c + 1, g.cols - 1);
            const Vec3 east = at(r, c1) - at(r, c0);
            const Vec3 north = at(r1, c) - at(r0, c);
            Vec3 n = cross(north, east);
            const double len = length(n);
            mesh.normals[static_cast<size_t>(r) * g.cols + c] =
                len > 0 ? (1.0 / len) * n : Vec3{0, 1, 0};
        }
    }

    // Palette over the true (not exaggerated) elevation range.
    const auto stops = scene::resolveRamp(look.ramp, zmin, zmax);
    const double span = zmax > zmin ? zmax - zmin : 1.0;
    mesh.paletteColors.resize(kPaletteSize);
    for (int k = 0; k < kPaletteSize; ++k)
        mesh.paletteColors[k] = scene::sampleRamp(stops, zmin + span * k / (kPaletteSize - 1));
    mesh.palette.resize(g.points.size());
    for (size_t i = 0; i < g.points.size(); ++i) {
        const double t = (g.points[i].z - zmin) / span;
        mesh.palette[i] = static_cast<unsigned char>(
            std::clamp(std::lround(t * (kPaletteSize - 1)), 0L, long{kPaletteSize - 1}));
    }
    return mesh;
}

}  // namespace relief::emit
