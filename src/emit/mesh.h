#pragma once
// Stage 4 of 5 (part 1). Input: the refined GeoGrid (frame metres) and the
// LookSpec. Output: Mesh,
// in POV-Ray scene units and axes, with normals and an elevation palette.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <memory>
#include <vector>

#include "core/types.h"
#include "geo/curvature_drop.h"
#include "geo/geo_grid.h"
#include "scene/scene_spec.h"

namespace relief::emit {

inline constexpr int kPaletteSize = 256;

/// Where the terrain sits in POV-Ray's scene, whatever geometry carries it.
/// POV-Ray's axes: x = east, y = up, z = north (left-handed, so the map is
/// not mirrored). One scene unit is `metresPerUnit` metres, a power of ten
/// chosen so the terrain spans 10-100 units: POV-Ray stores vertices as
/// 32-bit floats and treats bounding boxes over ~2e10 cubic units as infinite.
struct ScenePlacement {
    double metresPerUnit = 1;
    Vec3 originM;                 ///< frame position (metres) of the scene origin (x, y; z = 0)
    double exaggeration = 1;
    double zMinM = 0, zMaxM = 0;  ///< elevation range of the nodes with data, metres
    Vec3 boundsMin, boundsMax;    ///< scene units, scene axes
    std::vector<scene::ColorStop> paletteColors;  ///< kPaletteSize entries (linear RGB) over zMinM..zMaxM
    /// The Earth's fall below a local frame's tangent plane; null in UTM.
    std::shared_ptr<const geo::CurvatureDrop> curvature;

    double fallAt(const Vec3& p) const { return curvature ? curvature->at(p.x, p.y) : 0.0; }
    /// A frame point's elevation: its height above the ellipsoid (in UTM, its z).
    double elevation(const Vec3& p) const { return p.z - fallAt(p); }
    /// Its height as drawn, in metres before exaggeration: the elevation plus
    /// the fall divided by the exaggeration, so that exaggerating it scales the
    /// elevation and keeps the Earth's curvature as it is.
    double drawnHeight(const Vec3& p) const {
        const double fall = fallAt(p);
        return p.z - fall + fall / exaggeration;
    }
    /// A frame point (metres) in scene units and axes, exaggerated.
    Vec3 scenePoint(const Vec3& p) const {
        const double s = 1.0 / metresPerUnit, zs = exaggeration * s;
        return {(p.x - originM.x) * s, drawnHeight(p) * zs, (p.y - originM.y) * s};
    }
};

/// An elevation range this narrow is flat: refining a flat net leaves
/// rounding noise (~1e-13 m) that a ramp or a 16-bit quantization spread over
/// their whole range would show as speckles.
inline bool flatRange(double zMinM, double zMaxM) {
    return !(zMaxM - zMinM > 1e-9 * std::max({1.0, std::fabs(zMinM), std::fabs(zMaxM)}));
}

/// The placement of the refined grid's nodes with data: scene unit, origin
/// (centred), bounds, elevation range (collapsed to one height when flat) and
/// the ramp's palette over it.
ScenePlacement placeTerrain(const geo::GeoGrid& refined, const scene::LookSpec& look);

/// The full surface's normal at node (r, c), in scene axes: central
/// differences over the refined lattice (one-sided at its edges and next to
/// masked nodes); d/dcol runs east, d/drow north, and cross(north, east)
/// points up in POV-Ray's (x, y, z) = (E, U, N).
Vec3 surfaceNormal(const geo::GeoGrid& refined, const ScenePlacement& where, int r, int c);

/// The terrain as one mesh2: a vertex per refined node with data.
struct Mesh : ScenePlacement {
    static constexpr std::uint32_t kNoVertex = 0xffffffffu;
    int rows = 0, cols = 0;       ///< the refined grid's lattice
    /// Per grid node: its vertex, or kNoVertex for a masked node (no data);
    /// empty when every node is a vertex, node i being vertex i.
    std::vector<std::uint32_t> vertexOfNode;
    long long triangles = 0;      ///< two per cell, less those touching a masked node (or faces.size())
    /// Explicit triangles (vertex indices, counter-clockwise from above), for a
    /// mesh that is not the lattice's cells (the adaptive kind); empty: two per cell.
    std::vector<std::array<std::uint32_t, 3>> faces;
    std::vector<Vec3> positions;  ///< per vertex: scene units, relative to `originM`
    std::vector<Vec3> normals;    ///< unit length, scene axes
    std::vector<unsigned char> palette;  ///< per vertex: index into paletteColors
};

/// Builds the mesh: centres the terrain on the origin, applies the vertical
/// exaggeration, computes normals from the grid (central differences, one-sided
/// at the edges and next to masked nodes) and maps each vertex's true
/// elevation to the palette. Masked nodes are left out, with every triangle
/// that touches one; bounds and the palette's range are those of the rest.
Mesh buildMesh(const geo::GeoGrid& refined, const scene::LookSpec& look);

}  // namespace relief::emit
