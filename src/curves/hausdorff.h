#pragma once
// Exact Hausdorff distance between planar curves (paper 003, Cao, Dong, Cao
// 2014): h(A, B) = max over a in A of min over b in B of |a - b|, and
// H = max(h(A, B), h(B, A)).
//
// Step 1, feet: the nearest points on B of a point a are among B's segment
// ends and the roots of the orthogonality polynomial (B(t) - a) . B'(t),
// found in Bernstein form by convex-hull pruning and de Casteljau subdivision.
// Step 2, the maximum over A: f(s) = dist(A(s), B) is Lipschitz with the
// speed bound of A's hodograph, so sampling A and discarding every interval
// whose Lipschitz upper bound is below the best sample (branch and bound)
// leaves the intervals where the maximum can be; each is refined to full
// precision (golden section on f), and the witness is classified as one of
// the four cases: an endpoint of A, an endpoint of B (foot at B's end), an
// antipodal pair (both points feet of a common normal), or a one-to-two point
// (two feet at the same distance: a point of B's medial axis).
// Limitations: a maximum narrower than the sampling between two samples is
// still found (the bound is rigorous) but refined only to the branch-and-bound
// tolerance (1e-9 of the curves' size) before the final polish.
#include <string>
#include <vector>

#include "curves/bezier.h"

namespace relief::curves {

enum class WitnessCase { EndpointOfA, EndpointOfB, Antipodal, OneToTwo, Zero };
const char* caseName(WitnessCase c);

struct Foot {
    double distance = 0;
    size_t segment = 0;
    double t = 0;      ///< in the segment
    double param = 0;  ///< the curve file's parameter
    Point2 point;
};

struct OneSided {
    double value = 0;
    Point2 a;              ///< the witness on the first curve
    double paramA = 0;
    Foot foot;             ///< its nearest point on the second curve
    Foot secondFoot;       ///< the other foot, for one-to-two points
    WitnessCase kind = WitnessCase::Zero;
    long long footQueries = 0;  ///< distance evaluations used (for the benchmark)
};

struct HausdorffResult {
    OneSided ab, ba;
    double H = 0;
};

/// Every locally nearest foot of `a` on `b` within `slack` of the nearest,
/// nearest first (at least one unless `b` has no segment).
std::vector<Foot> feet(const PiecewiseBezier& b, Point2 a, double slack);

/// dist(a, b) = min over b of |a - b|.
double distanceToCurve(const PiecewiseBezier& b, Point2 a);

OneSided oneSidedHausdorff(const PiecewiseBezier& a, const PiecewiseBezier& b);
HausdorffResult hausdorff(const PiecewiseBezier& a, const PiecewiseBezier& b);

}  // namespace relief::curves
