#pragma once
// Linear interpolation of scattered samples on their Delaunay triangulation
// (GDAL's `linear` gridding), computed in bands of grid rows that are
// triangulated side by side on every core. The triangulation dominates the
// cost (qhull, about 12 us a sample); one band triangulates only the samples
// near it, and a node's value is kept only when it is provably the global
// triangulation's, so the result is GDAL's, in a fraction of the time.
#include <functional>
#include <string>
#include <vector>

namespace relief::geo {

/// A grid of nodes as GDALGridCreate lays it out: `cols` x `rows` pixel
/// centres of the box [xmin, xmax] x [ymin, ymax], row 0 at ymin.
struct GridLayout {
    double xmin = 0, xmax = 0, ymin = 0, ymax = 0;
    int cols = 0, rows = 0;
    double x(int col) const { return xmin + (col + 0.5) * ((xmax - xmin) / cols); }
    double y(int row) const { return ymin + (row + 0.5) * ((ymax - ymin) / rows); }
};

struct LinearGriddingStats {
    int bands = 0;              ///< bands triangulated in parallel
    int widenedBands = 0;       ///< re-triangulations with a wider margin
    size_t outsideHull = 0;     ///< nodes outside the samples' convex hull (left as noData)
};

/// Heights at every node of `grid` (row-major, row 0 first) by linear
/// interpolation in the samples' Delaunay triangle that holds it; `noData`
/// outside the samples' convex hull. `threads` 0: every core. Returns "" or
/// the error (a triangulation GDAL cannot build: all samples on a line).
///
/// Why it is exact: a band triangulates the samples whose y lies within a
/// margin of its rows. A triangle of that triangulation whose circumcircle,
/// where it meets the samples' bounding box, stays inside that slab has no
/// sample of the whole set inside its circle, so it is a triangle of the
/// global Delaunay triangulation. Nodes in any other triangle, or outside the
/// band's hull but inside the global one, are computed again with a margin
/// four times wider, up to the whole set.
std::string gridLinear(const std::vector<double>& xs, const std::vector<double>& ys,
                       const std::vector<double>& zs, const GridLayout& grid, double noData,
                       std::vector<double>& out, LinearGriddingStats* stats = nullptr,
                       int threads = 0, const std::function<void(double)>& progress = {});

}  // namespace relief::geo
