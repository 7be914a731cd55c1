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
// The foot search walks a bounding-volume hierarchy over B's segments, so a
// query costs about log n segment tests: terrain rows and contour lines have
// thousands of segments.
// Accuracy: the branch and bound stops when no interval's bound beats the
// best value by more than the tolerance (default 1e-6 of the curves' size),
// or when an interval is shorter (in arc length) than 1000 tolerances, which
// only happens where f is flat at its maximum; the best candidates are then
// polished to full precision (tests: 1e-9 against a brute-force reference).
#include <span>
#include <string>
#include <vector>

#include "curves/bezier.h"

namespace relief::curves {

enum class WitnessCase { EndpointOfA, EndpointOfB, Antipodal, OneToTwo, Zero };
const char* caseName(WitnessCase c);

/// Several curves taken as one point set (the contour lines at one elevation).
using CurveSet = std::vector<PiecewiseBezier>;

struct Foot {
    double distance = 0;
    size_t piece = 0;  ///< which curve of a set
    size_t segment = 0;
    double t = 0;      ///< in the segment
    double param = 0;  ///< the curve file's parameter
    Point2 point;
};

struct OneSided {
    double value = 0;
    Point2 a;              ///< the witness on the first curve
    size_t pieceA = 0;     ///< which curve of the first set
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

/// A bounding-volume hierarchy over the segments of a curve set: nearest-foot
/// queries visit only the segments whose boxes could hold a nearer point.
/// Keeps a pointer to `curves`, which must outlive it.
class SegmentIndex {
public:
    explicit SegmentIndex(std::span<const PiecewiseBezier> curves);

    /// Every locally nearest foot of `a` within `slack` of the nearest,
    /// nearest first (at least one unless there is no segment).
    std::vector<Foot> feet(Point2 a, double slack) const;
    /// min over the set of |a - b|.
    double distance(Point2 a) const;

private:
    struct Node {
        Bounds2 box;
        unsigned first, count;  ///< a leaf: entries_[first, first + count)
        unsigned left, right;   ///< an inner node (count == 0)
    };
    struct Entry {
        unsigned piece, segment;
        Bounds2 box;
    };
    unsigned build(unsigned first, unsigned count);

    std::span<const PiecewiseBezier> curves_;
    std::vector<Entry> entries_;
    std::vector<Node> nodes_;
};

/// One-off queries on a single curve (each builds its index: for many
/// queries against one curve, keep a SegmentIndex).
std::vector<Foot> feet(const PiecewiseBezier& b, Point2 a, double slack);
double distanceToCurve(const PiecewiseBezier& b, Point2 a);

struct HausdorffOptions {
    double tolerance = 0;  ///< absolute; <= 0: 1e-6 of the curves' size
    /// Only values above this matter (the largest of many distances is
    /// wanted and one is already known): parts of A that cannot beat it are
    /// skipped, and when h <= floor the result is some value <= floor.
    double floor = 0;
};

OneSided oneSidedHausdorff(const PiecewiseBezier& a, const PiecewiseBezier& b,
                           const HausdorffOptions& options = {});
HausdorffResult hausdorff(const PiecewiseBezier& a, const PiecewiseBezier& b,
                          const HausdorffOptions& options = {});

/// The same between curve sets (each set's curves taken as one point set).
/// An empty set is at distance 0 from anything only if both are empty; one
/// empty set gives +infinity.
OneSided oneSidedHausdorff(std::span<const PiecewiseBezier> a, std::span<const PiecewiseBezier> b,
                           const HausdorffOptions& options = {});
HausdorffResult hausdorff(std::span<const PiecewiseBezier> a, std::span<const PiecewiseBezier> b,
                          const HausdorffOptions& options = {});

/// The vertex-only (sampled) Hausdorff distance: segment ends of each set
/// against the other set exactly. A lower bound of H, and cheap.
double vertexHausdorff(std::span<const PiecewiseBezier> a, std::span<const PiecewiseBezier> b);

}  // namespace relief::curves
