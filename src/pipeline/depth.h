#pragma once
// The depth a surface is refined to: the scene's, the one depth = "auto"
// finds, or the still's (no more detail than its pixels show), held to the
// job's budget. Automatic depth measures how far one more level moves the terrain,
// measured as the exact Hausdorff distance (src/curves) between successive
// refinements of the control net's rows and columns, taken as planar curves
// (x, z) and (y, z) in metres. For a convergent scheme these distances shrink
// geometrically, by about arity^-min(alpha, 2) per level (alpha: the scheme's
// Hölder exponent; polylines follow a smooth curve only to second order).
#include <optional>
#include <string>
#include <vector>

#include "core/diagnostics.h"
#include "emit/geometry_kind.h"
#include "geo/geo_grid.h"
#include "geo/normalize.h"
#include "pipeline/load.h"
#include "subdiv/budget.h"
#include "subdiv/scheme.h"

namespace relief {

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

/// "depth 3" or "depth auto (tolerance_m = 5)".
std::string depthLabel(const scene::SubdivisionSpec& subdivision);

/// For depth = "auto": "depth 4 chosen: level 1 moved the terrain 220 m, ..., 4: 4.1 m <= 5 m".
std::string autoDepthSummary(const DepthChoice& choice, double toleranceM);

/// The net a surface refines, by its size. The net's own; or, for relief
/// info's estimate (surface.h), a net too large to read, whose heights a
/// coarser net over the same extent stands in for.
struct NetSize {
    int rows = 0, cols = 0;
    double x0 = 0, y0 = 0, dx = 0, dy = 0;
    static NetSize of(const geo::GeoGrid& net) { return {net.rows(), net.cols(), net.x0, net.y0, net.dx, net.dy}; }
    double xMax() const { return x0 + (cols - 1) * dx; }
    double yMax() const { return y0 + (rows - 1) * dy; }
};

/// The depth a surface is refined to, and why.
struct SurfaceDepth {
    int depth = 0;
    std::string reason;  ///< "subdivision.depth", the auto summary, or how the still chose it
    std::optional<DepthChoice> autoDepth;  ///< the change per level, for depth = "auto"
};

/// The scene's depth; depth = "auto": the smallest whose last level moves the
/// terrain by at most tolerance_m, searched up to the deepest the budget
/// allows (an error when not reached); no depth: the shallowest whose refined
/// spacing is within sqrt(arity) of one pixel where the terrain is nearest the
/// camera, lowered until the budget allows it (a default never refuses a scene
/// that fits at depth 0). `net`'s heights, refined at `size`.
std::optional<SurfaceDepth> chooseSurfaceDepth(const LoadedScene& loaded, const geo::ControlNet& net,
                                               const NetSize& size, int threads, Diagnostics& diags);

/// The geometry the net refined `depth` times becomes, and what it costs.
struct DepthCost {
    emit::GeometryChoice geometry;
    subdiv::OutputEstimate estimate;
};
std::optional<DepthCost> costAt(const LoadedScene& loaded, const geo::ControlNet& net, const NetSize& size, int depth,
                                Diagnostics& diags);

}  // namespace relief
