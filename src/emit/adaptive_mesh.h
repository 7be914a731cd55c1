#pragma once
// Stage 4 of 6, the adaptive geometry kind: a mesh2 of far fewer triangles
// where the refined surface is smooth, with no vertex of the full surface
// further than a tolerance from it. The method is the right-triangulated
// irregular network (RTIN; Evans, Kirkpatrick and Townsend, "Right-Triangulated
// Irregular Networks", Algorithmica 30, 2001): the refined lattice is covered
// by the hierarchy of right isosceles triangles that bisect their hypotenuses;
// each hypotenuse midpoint carries the largest vertical error of interpolating
// there, taken over every triangle that shares it and, level by level, over
// their descendants, so that splitting a triangle whenever that error exceeds
// the tolerance splits its neighbour across the hypotenuse too: no cracks,
// and only right isosceles triangles (no slivers). It is chosen over greedy
// insertion (Garland and Heckbert) because it is linear in the grid, needs no
// triangulation library and its triangles nest, so the mesh is the same
// on every run and thread count.
//
// Any lattice size works: the hierarchy is laid over the smallest 2^k + 1
// square that holds it; triangles that reach outside the lattice, or over a
// masked node, count as infinitely wrong, so they split down to single cells,
// which are kept when all three corners have data.
#include "emit/camera.h"
#include "emit/mesh.h"
#include "geo/geo_grid.h"

namespace relief::emit {

/// A tolerance that follows the still's pixels (a perspective view): at each
/// point, the tolerance at the terrain's nearest point times how many times
/// wider a pixel's footprint is there (its depth before the eye over the
/// nearest's), and 16 times that outside the view (terrain seen only in its
/// shadows) or behind the eye: the far ground, which a pixel shows as one,
/// is not carried in triangles a pixel apart.
struct PixelTolerance {
    const CameraView* camera = nullptr;
    int widthPx = 0, heightPx = 0;
};

/// The adaptive mesh of the refined grid at `toleranceM` (true metres,
/// vertical; with `perPixel`, where a pixel's footprint is finest): vertices
/// are refined nodes with the full surface's normals (central differences)
/// and palette colours; `faces` lists the triangles.
Mesh buildAdaptiveMesh(const geo::GeoGrid& refined, const ScenePlacement& where, double toleranceM,
                       const PixelTolerance* perPixel = nullptr);
Mesh buildAdaptiveMesh(geo::GeoGrid&& refined, const ScenePlacement& where, double toleranceM,
                       const PixelTolerance* perPixel = nullptr) = delete;
/// The tolerance `perPixel` gives at frame point `p`, metres (toleranceM without one).
double adaptiveToleranceAt(const Vec3& p, const ScenePlacement& where, double toleranceM,
                           const PixelTolerance* perPixel);
/// The same, placed as placeTerrain places it.
inline Mesh buildAdaptiveMesh(const geo::GeoGrid& refined, const scene::LookSpec& look, double toleranceM) {
    return buildAdaptiveMesh(refined, placeTerrain(refined, look), toleranceM);
}
Mesh buildAdaptiveMesh(geo::GeoGrid&& refined, const scene::LookSpec& look, double toleranceM) = delete;

}  // namespace relief::emit
