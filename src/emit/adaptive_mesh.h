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
#include "emit/mesh.h"
#include "geo/geo_grid.h"

namespace relief::emit {

/// The adaptive mesh of the refined grid at `toleranceM` (true metres,
/// vertical): vertices are refined nodes with the full surface's normals
/// (central differences) and palette colours; `faces` lists the triangles.
Mesh buildAdaptiveMesh(const geo::GeoGrid& refined, const ScenePlacement& where, double toleranceM);
Mesh buildAdaptiveMesh(geo::GeoGrid&& refined, const ScenePlacement& where, double toleranceM) = delete;
/// The same, placed as placeTerrain places it.
inline Mesh buildAdaptiveMesh(const geo::GeoGrid& refined, const scene::LookSpec& look, double toleranceM) {
    return buildAdaptiveMesh(refined, placeTerrain(refined, look), toleranceM);
}
Mesh buildAdaptiveMesh(geo::GeoGrid&& refined, const scene::LookSpec& look, double toleranceM) = delete;

}  // namespace relief::emit
