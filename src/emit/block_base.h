#pragma once
// Stage 4, the block model ([base]): the terrain drawn as a solid, its side
// walls dropped from the surface's edge to a flat floor, in a darker tone of
// the ramp, as relief models and rayshader's renders show terrain. Written as
// a mesh2 of its own beside whichever geometry carries the surface.

#include <array>
#include <cstdint>
#include <cstdio>
#include <vector>

#include "emit/mesh.h"
#include "geo/geo_grid.h"

namespace relief::emit {

/// The block's triangles. A vertex is a grid node's top (on the surface, the
/// surface's own point) or its bottom (on the floor).
struct BlockGeometry {
    struct Vertex {
        size_t node;
        bool floor;
    };
    std::vector<Vertex> vertices;  ///< in the order first used
    std::vector<std::array<std::uint32_t, 3>> faces;
    long long wallTriangles = 0, floorTriangles = 0;
};

/// The block under `refined` (`where.baseElevationM` must be set): a
/// wall under every edge of the surface that only one triangle of the
/// lattice's cells has (cut along the south-east to north-west diagonal, as
/// the mesh2 and POV-Ray's height field cut them; nodes without data make
/// holes, and walls line them), and a floor at the base elevation under every
/// such triangle (cells in runs, two triangles a run). With the surface's triangles it closes a solid: every edge
/// belongs to two triangles.
BlockGeometry buildBlockBase(const geo::GeoGrid& refined);

/// Writes the block as a mesh2.
void writeBlockBase(std::FILE* out, const geo::GeoGrid& refined, const ScenePlacement& where);

/// The walls' one colour: the ramp's lowest half greyed (kBlockWallGrey),
/// darkened by kBlockWallShade.
LinearRgb blockWallColour(const ScenePlacement& where);

/// The factor the walls' colour is darkened by (linear RGB), and the share of
/// their light that is the even (ambient) light, so that the wall the sun
/// does not reach still reads as the block's side.
inline constexpr double kBlockWallShade = 0.6;
inline constexpr double kBlockWallGrey = 0.25;
inline constexpr double kBlockWallAmbient = 0.5;

}  // namespace relief::emit
