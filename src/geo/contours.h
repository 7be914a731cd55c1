#pragma once
// Contour lines of a refined surface, by GDAL's contour generator.
#include <string>
#include <vector>

#include "curves/hausdorff.h"
#include "geo/geo_grid.h"

namespace relief::geo {

/// The contour lines at each level (GDALContourGenerate on an in-memory
/// raster whose pixel centres are the nodes; marching squares, linear along
/// cell edges), in the frame's metres: one polyline per line, closed when it
/// closes on itself. result[i] holds levels[i]'s lines (empty when the
/// surface does not reach it). `error` is set when GDAL fails.
std::vector<curves::CurveSet> contourLines(const geo::GeoGrid& grid, const std::vector<double>& levels,
                                           std::string& error);

/// The parts of polylines inside the box [xmin, xmax] x [ymin, ymax] (each
/// segment clipped, Liang–Barsky); a line that leaves and re-enters becomes
/// several lines. Lines wholly inside are kept as they are.
curves::CurveSet clipToBox(const curves::CurveSet& lines, double xmin, double ymin, double xmax,
                           double ymax);

/// Round levels inside [lo, hi]: about `count` of them at a 1, 2 or 5 x 10^k
/// spacing, none at the extremes.
std::vector<double> niceLevels(double lo, double hi, int count);

}  // namespace relief::geo
