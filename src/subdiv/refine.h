#pragma once
// Stage 3 of 6 (part 2). Input: a Grid (control net, metres) and a Scheme.
// Output: the refined Grid. One generic refiner for every scheme: a tensor
// product, rows first, then columns, `levels` times.
#include <span>
#include <vector>

#include "core/types.h"
#include "subdiv/scheme.h"

namespace relief::subdiv {

/// Refines an open curve once. Needs at least max(ghosts) + 1 points.
std::vector<Vec3> refineCurve(const Scheme& scheme, std::span<const Vec3> points);

/// Refines a closed curve once: indices wrap around, n points -> m n points.
std::vector<Vec3> refineClosedCurve(const Scheme& scheme, std::span<const Vec3> points);

/// `levels` steps on an open (point reflection at the ends) or closed curve.
std::vector<Vec3> refineCurveLevels(const Scheme& scheme, std::vector<Vec3> points, bool closed,
                                    int levels);

/// Which axis a single pass refines.
enum class Axis { AlongRows, AlongColumns };

/// One pass: refines every row (AlongRows: cols -> m(cols-1)+1) or every
/// column (AlongColumns: rows -> m(rows-1)+1). `threads` <= 0: all cores.
Grid refinePass(const Scheme& scheme, const Grid& in, Axis axis, int threads = 0);

/// One level, rows and columns fused (equal to refinePass along rows, then
/// along columns, up to rounding: ghost rows are reflected before the row
/// pass, not after it): each output row combines
/// row-refined input rows, which are made once each into a small ring buffer
/// that stays in cache, so the grid is read once and written once, with
/// streaming stores (row_kernels.h). `out` is resized (its storage reused; new
/// points are not zeroed first, see BigBufferAllocator).
void refineLevel(const Scheme& scheme, const Grid& in, Grid& out, int threads = 0);

/// Whether refineLevel makes the scheme's row-refined rows in one sweep on
/// this CPU (RowSweep, row_kernels.h), not by its rules' sums and an
/// interleave: for tests and benchmarks.
bool rowPassInOneSweep(const Scheme& scheme);

/// Repeated refinement with reusable storage: calling refine() again with
/// grids of the same sizes allocates nothing (a new 100 MB grid costs the
/// kernel as much time as refining into it).
class Refiner {
public:
    /// `levels` steps. Preconditions: rows and cols >= minPoints(scheme).
    /// The result lives until the next call.
    const Grid& refine(const Scheme& scheme, const Grid& net, int levels, int threads = 0);
    /// Moves the latest result out (its storage is then no longer reused).
    Grid release();

private:
    Grid buffers_[2];
    int latest_ = 0;
};

/// `levels` steps of rows-then-columns. Preconditions: rows and cols are at
/// least minPoints(scheme). `threads` <= 0: all cores.
Grid refineGrid(const Scheme& scheme, const Grid& net, int levels, int threads = 0);

/// Smallest number of points along an axis that the boundary rule supports.
int minPoints(const Scheme& scheme);

}  // namespace relief::subdiv
