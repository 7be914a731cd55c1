#pragma once
// Automatic subdivision depth: how far one more level moves the terrain,
// measured as the exact Hausdorff distance (src/curves) between successive
// refinements of the control net's rows and columns, taken as planar curves
// (x, z) and (y, z) in metres. For a convergent scheme these distances shrink
// geometrically, by about arity^-min(alpha, 2) per level (alpha: the scheme's
// Hölder exponent; polylines follow a smooth curve only to second order).
#include <string>
#include <vector>

#include "geo/geo_grid.h"
#include "subdiv/scheme.h"

namespace relief::measure {

/// What step `level` (from level - 1 to level) moved: the largest Hausdorff
/// distance over every row and column curve, and where.
struct LevelChange {
    int level = 0;
    double distanceM = 0;
    std::string curve;      ///< "row 12" or "column 3" (net indices, row 0 south)
    double x = 0, y = 0, z = 0;  ///< the witness on the finer curve, in the net's frame
    double seconds = 0;
};

struct DepthChoice {
    int depth = 0;          ///< the smallest level whose change is <= the tolerance
    bool reached = false;   ///< false: even maxDepth moves more than the tolerance
    std::vector<LevelChange> levels;  ///< levels 1 .. depth (or maxDepth)
};

/// The change per level for levels 1 .. maxDepth, stopping at the first one
/// at or below `toleranceM`. The curves are refined with the same boundary
/// rule as the surface. Rows and columns are measured in parallel
/// (`threads` <= 0: all cores); the result does not depend on the threads.
DepthChoice chooseDepth(const subdiv::Scheme& scheme, const geo::GeoGrid& net,
                        double toleranceM, int maxDepth, int threads = 0);

/// The observed convergence rate of step k: log_arity(d_{k-1} / d_k)
/// (compare with min(Hölder, 2)); NaN for the first level or a zero distance.
double observedRate(const DepthChoice& choice, size_t index, int arity);

}  // namespace relief::measure
