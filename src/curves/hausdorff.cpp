#include "curves/hausdorff.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <queue>

namespace relief::curves {

const char* caseName(WitnessCase c) {
    switch (c) {
        case WitnessCase::EndpointOfA: return "endpoint of A";
        case WitnessCase::EndpointOfB: return "endpoint of B";
        case WitnessCase::Antipodal: return "antipodal";
        case WitnessCase::OneToTwo: return "one-to-two";
        case WitnessCase::Zero: return "zero";
    }
    return "?";
}

namespace {

// sqrt, not hypot: 3x faster, and squares of coordinates up to 1e150 do not overflow.
double dist(Point2 p, Point2 q) {
    const double dx = p.x - q.x, dy = p.y - q.y;
    return std::sqrt(dx * dx + dy * dy);
}

Point2 lerp(Point2 p, Point2 q, double t) { return {p.x + t * (q.x - p.x), p.y + t * (q.y - p.y)}; }

// The parameter of the point of the line p0 p1 nearest to a (not clamped;
// 0 for a degenerate segment).
double projectOntoLine(Point2 p0, Point2 p1, Point2 a) {
    const double ex = p1.x - p0.x, ey = p1.y - p0.y, len2 = ex * ex + ey * ey;
    return len2 > 0 ? ((a.x - p0.x) * ex + (a.y - p0.y) * ey) / len2 : 0.0;
}

double binomial(int n, int k) {
    double r = 1;
    for (int i = 1; i <= k; ++i) r = r * (n - k + i) / i;
    return r;
}

// Roots in [lo, hi] of the polynomial with Bernstein coefficients c: intervals
// whose coefficients share a strict sign hold none (convex hull property);
// the rest are halved by de Casteljau until they are tiny. `budget` caps the
// work where the polynomial is flat (a point equidistant from a whole arc):
// then any parameter there is as good as another.
void bernsteinRoots(const std::vector<double>& c, double lo, double hi, std::vector<double>& out,
                    int& budget) {
    double mn = c[0], mx = c[0];
    for (double v : c) mn = std::min(mn, v), mx = std::max(mx, v);
    if (mn > 0 || mx < 0) return;
    if (hi - lo < 1e-13 || --budget <= 0) {
        out.push_back(0.5 * (lo + hi));
        return;
    }
    const size_t n = c.size();
    std::vector<double> q = c, left(n), right(n);
    for (size_t r = 0; r < n; ++r) {
        left[r] = q[0];
        right[n - 1 - r] = q[n - 1 - r];
        for (size_t i = 0; i + r + 1 < n; ++i) q[i] = 0.5 * (q[i] + q[i + 1]);
    }
    const double mid = 0.5 * (lo + hi);
    bernsteinRoots(left, lo, mid, out, budget);
    bernsteinRoots(right, mid, hi, out, budget);
}

void segmentFeet(const Segment& s, size_t piece, size_t index, Point2 a, std::vector<Foot>& out) {
    const int d = static_cast<int>(s.control.size()) - 1;
    auto add = [&](double t) {
        Foot f;
        f.piece = piece;
        f.segment = index;
        f.t = std::clamp(t, 0.0, 1.0);
        f.point = evaluate(s, f.t);
        f.distance = dist(f.point, a);
        f.param = s.paramStart + f.t * (s.paramEnd - s.paramStart);
        out.push_back(f);
    };
    add(0.0);
    if (d == 0) return;
    add(1.0);
    if (d == 1) {  // a straight piece: the foot of the perpendicular, if inside
        const double t = projectOntoLine(s.control[0], s.control[1], a);
        if (t > 0 && t < 1) add(t);
        return;
    }
    // g(t) = (B(t) - a) . B'(t) in Bernstein form of degree 2d - 1.
    const int n = 2 * d - 1;
    std::vector<double> g(static_cast<size_t>(n + 1), 0.0);
    double scale = 0;
    for (int i = 0; i <= d; ++i) {
        const Point2 p{s.control[i].x - a.x, s.control[i].y - a.y};
        for (int j = 0; j < d; ++j) {
            const Point2 q{d * (s.control[j + 1].x - s.control[j].x), d * (s.control[j + 1].y - s.control[j].y)};
            const double w = binomial(d, i) * binomial(d - 1, j) / binomial(n, i + j);
            g[i + j] += w * (p.x * q.x + p.y * q.y);
            scale = std::max(scale, std::fabs(p.x * q.x + p.y * q.y));
        }
    }
    double gmax = 0;
    for (double v : g) gmax = std::max(gmax, std::fabs(v));
    if (gmax <= 1e-300 || gmax <= 1e-15 * scale) return;  // a point, or g identically 0
    std::vector<double> roots;
    int budget = 4000;
    bernsteinRoots(g, 0, 1, roots, budget);
    double last = -1;
    for (double t : roots) {
        if (t - last < 1e-11) continue;  // one root found in two adjacent intervals
        last = t;
        add(t);
    }
}

// Largest |A'(t)| on a segment: the hodograph's control points bound it.
double speedBound(const Segment& s) {
    const size_t d = s.control.size() - 1;
    double m = 0;
    for (size_t i = 0; i < d; ++i)
        m = std::max(m, d * dist(s.control[i + 1], s.control[i]));
    return m;
}

bool isEndpoint(const PiecewiseBezier& c, size_t seg, double t) {
    if (c.closed || c.segments.empty()) return false;
    return (seg == 0 && t <= 1e-12) || (seg + 1 == c.segments.size() && t >= 1 - 1e-12) ||
           (c.segments[seg].control.size() == 1);
}

double setSize(std::span<const PiecewiseBezier> curves) {
    Bounds2 b;
    for (const auto& c : curves)
        for (const auto& s : c.segments)
            for (const auto& p : s.control) b.add(p);
    return b.diagonal();
}

constexpr unsigned kLeafSize = 4;

}  // namespace

SegmentIndex::SegmentIndex(std::span<const PiecewiseBezier> curves) : curves_(curves) {
    for (size_t c = 0; c < curves.size(); ++c)
        for (size_t s = 0; s < curves[c].segments.size(); ++s) {
            // The control points' box holds the segment (convex hull property).
            Bounds2 b;
            for (const auto& q : curves[c].segments[s].control) b.add(q);
            entries_.push_back({static_cast<unsigned>(c), static_cast<unsigned>(s), b});
        }
    if (!entries_.empty()) {
        nodes_.reserve(2 * entries_.size() / kLeafSize + 2);
        build(0, static_cast<unsigned>(entries_.size()));
    }
}

// Median split along the longer side of the node's box: a balanced tree whose
// leaves hold neighbouring segments.
unsigned SegmentIndex::build(unsigned first, unsigned count) {
    Bounds2 box;
    for (unsigned i = first; i < first + count; ++i) box.add(entries_[i].box);
    const unsigned id = static_cast<unsigned>(nodes_.size());
    nodes_.push_back({box, first, count, 0, 0});
    if (count <= kLeafSize) return id;
    const bool alongX = box.xmax - box.xmin >= box.ymax - box.ymin;
    const unsigned half = count / 2;
    std::nth_element(entries_.begin() + first, entries_.begin() + first + half,
                     entries_.begin() + first + count, [alongX](const Entry& p, const Entry& q) {
                         return alongX ? p.box.xmin + p.box.xmax < q.box.xmin + q.box.xmax
                                       : p.box.ymin + p.box.ymax < q.box.ymin + q.box.ymax;
                     });
    const unsigned left = build(first, half);
    const unsigned right = build(first + half, count - half);
    nodes_[id].count = 0;
    nodes_[id].left = left;
    nodes_[id].right = right;
    return id;
}

std::vector<Foot> SegmentIndex::feet(Point2 a, double slack) const {
    std::vector<Foot> all;
    if (nodes_.empty()) return all;
    // Depth first, nearer child first; a node is skipped once its box is
    // beyond the best foot so far plus the slack.
    double best = 1e300;
    // The tree is balanced: its depth is below 64 for any curve that fits in memory.
    std::pair<double, unsigned> stack[128];
    int top = 0;
    stack[top++] = {nodes_[0].box.distance(a), 0u};
    while (top > 0) {
        const auto [lower, id] = stack[--top];
        if (lower > best + slack) continue;
        const Node& n = nodes_[id];
        if (n.count) {
            for (unsigned i = n.first; i < n.first + n.count; ++i) {
                const Entry& e = entries_[i];
                if (e.box.distance(a) > best + slack) continue;
                const size_t before = all.size();
                segmentFeet(curves_[e.piece].segments[e.segment], e.piece, e.segment, a, all);
                for (size_t k = before; k < all.size(); ++k) best = std::min(best, all[k].distance);
            }
            continue;
        }
        const double dl = nodes_[n.left].box.distance(a), dr = nodes_[n.right].box.distance(a);
        if (dl <= dr) {
            stack[top++] = {dr, n.right}, stack[top++] = {dl, n.left};
        } else {
            stack[top++] = {dl, n.left}, stack[top++] = {dr, n.right};
        }
    }
    std::sort(all.begin(), all.end(), [](const Foot& x, const Foot& y) { return x.distance < y.distance; });
    size_t keep = 0;
    while (keep < all.size() && all[keep].distance <= best + slack) ++keep;
    all.resize(keep);
    return all;
}

double SegmentIndex::distance(Point2 a) const {
    const auto f = feet(a, 0.0);
    return f.empty() ? 0.0 : f.front().distance;
}

std::vector<Foot> feet(const PiecewiseBezier& b, Point2 a, double slack) {
    return SegmentIndex({&b, 1}).feet(a, slack);
}

double distanceToCurve(const PiecewiseBezier& b, Point2 a) { return SegmentIndex({&b, 1}).distance(a); }

namespace {

// One search for sup over A of dist(., B): f(t) = dist(A(t), B) sampled on
// each segment of A, bounded on intervals, the intervals split where the
// bound could still beat the best value (branch and bound), the best
// candidates polished, and the witness classified.
class OneSidedSearch {
public:
    OneSidedSearch(std::span<const PiecewiseBezier> A, std::span<const PiecewiseBezier> B,
                   const HausdorffOptions& options)
        : A_(A), B_(B), indexB_(B), options_(options), size_(std::max({setSize(A), setSize(B), 1e-300})) {}

    OneSided run() {
        polish(branchAndBound(seeded()));
        return witness();
    }

private:
    // f at t on one segment of A, and the B segment the nearest foot is on.
    struct Sample {
        double t, f;
        unsigned footPiece, footSeg;
    };
    struct Interval {
        double upper;
        unsigned piece, seg;
        Sample s0, s1;
        bool operator<(const Interval& o) const { return upper < o.upper; }
    };
    using Queue = std::priority_queue<Interval>;

    Sample sample(size_t piece, size_t seg, double t) {
        ++queries_;
        const auto fs = indexB_.feet(evaluate(A_[piece].segments[seg], t), 0.0);
        return Sample{t, fs.front().distance, static_cast<unsigned>(fs.front().piece),
                      static_cast<unsigned>(fs.front().segment)};
    }
    double f(size_t piece, size_t seg, double t) { return sample(piece, seg, t).f; }

    void consider(double v, size_t piece, size_t seg, double t) {
        if (v > best_) best_ = v, bestPiece_ = piece, bestSeg_ = seg, bestT_ = t;
    }

    // An upper bound of f on [s0.t, s1.t]. Lipschitz: f changes no faster
    // than A moves (M bounds |A'|). Convexity, where A's piece and a foot's B
    // segment are both straight: the distance to a segment is convex along a
    // line, so f <= max of that segment's distance at the two ends; where one
    // B segment is nearest at both ends this is max(f0, f1), exact, and
    // polylines need no splitting but around the kinks of f.
    double upperBound(const Segment& a, double M, const Sample& s0, const Sample& s1) const {
        double u = 0.5 * (s0.f + s1.f + M * (s1.t - s0.t));
        if (a.control.size() != 2) return u;
        for (const Sample* s : {&s0, &s1}) {
            const auto& b = B_[s->footPiece].segments[s->footSeg].control;
            if (b.size() > 2) continue;
            const Point2 q = evaluate(a, (s == &s0 ? s1 : s0).t);  // the interval's other end
            const Point2 nearest =
                b.size() == 1 ? b[0] : lerp(b[0], b[1], std::clamp(projectOntoLine(b[0], b[1], q), 0.0, 1.0));
            u = std::min(u, std::max(s->f, dist(q, nearest)));
        }
        return u;
    }

    // Every segment of A sampled to start; a straight piece needs only its
    // ends: the bounds do the rest.
    Queue seeded() {
        Queue queue;
        for (unsigned p = 0; p < A_.size(); ++p)
            for (unsigned s = 0; s < A_[p].segments.size(); ++s) {
                const Segment& seg = A_[p].segments[s];
                const double M = speedBound(seg);
                const int n = seg.control.size() <= 2 ? 1 : 8 * static_cast<int>(seg.control.size());
                Sample prev = sample(p, s, 0);
                consider(prev.f, p, s, 0);
                for (int k = 1; k <= n && seg.control.size() > 1; ++k) {
                    const Sample next = sample(p, s, static_cast<double>(k) / n);
                    consider(next.f, p, s, next.t);
                    queue.push({upperBound(seg, M, prev, next), p, s, prev, next});
                    prev = next;
                }
            }
        return queue;
    }

    // Branch and bound: split intervals whose bound could still beat the best
    // value by more than the tolerance, down to intervals of `shortest`
    // (M * (t1 - t0)); where f is flat at its maximum (parallel or coincident
    // pieces) every interval would stay a candidate, and any is as good as
    // another: the polish takes the best candidates to full precision.
    std::vector<Interval> branchAndBound(Queue queue) {
        const double tolerance = options_.tolerance > 0 ? options_.tolerance : 1e-6 * size_;
        auto bar = [&] { return std::max(best_, options_.floor); };
        const double shortest = std::min(1e-3 * size_, 1e3 * tolerance);
        std::vector<Interval> finalists;
        while (!queue.empty()) {
            Interval iv = queue.top();
            queue.pop();
            const Segment& seg = A_[iv.piece].segments[iv.seg];
            const double M = speedBound(seg);
            if (iv.upper <= bar() + tolerance || M * (iv.s1.t - iv.s0.t) < shortest) {
                if (iv.upper > bar() - tolerance) finalists.push_back(iv);
                continue;
            }
            const Sample mid = sample(iv.piece, iv.seg, 0.5 * (iv.s0.t + iv.s1.t));
            consider(mid.f, iv.piece, iv.seg, mid.t);
            queue.push({upperBound(seg, M, iv.s0, mid), iv.piece, iv.seg, iv.s0, mid});
            queue.push({upperBound(seg, M, mid, iv.s1), iv.piece, iv.seg, mid, iv.s1});
        }
        return finalists;
    }

    // Polish: golden section on f around the best candidates (a local
    // maximum, or the kink where two feet are equally near, is unimodal
    // there), highest bound first: this takes the answer from the tolerance
    // to full precision. Where f is flat, the 24 highest bounds are enough.
    void polish(std::vector<Interval> finalists) {
        std::sort(finalists.begin(), finalists.end(),
                  [](const Interval& x, const Interval& y) { return x.upper > y.upper; });
        if (finalists.size() > 24) finalists.resize(24);
        for (const Interval& iv : finalists) {
            const double w = iv.s1.t - iv.s0.t;
            double lo = std::max(0.0, iv.s0.t - w), hi = std::min(1.0, iv.s1.t + w);
            const double g = 0.5 * (std::sqrt(5.0) - 1);
            double x1 = hi - g * (hi - lo), x2 = lo + g * (hi - lo);
            double f1 = f(iv.piece, iv.seg, x1), f2 = f(iv.piece, iv.seg, x2);
            for (int it = 0; it < 80 && hi - lo > 1e-15; ++it) {
                if (f1 < f2) {
                    lo = x1, x1 = x2, f1 = f2, x2 = lo + g * (hi - lo), f2 = f(iv.piece, iv.seg, x2);
                } else {
                    hi = x2, x2 = x1, f2 = f1, x1 = hi - g * (hi - lo), f1 = f(iv.piece, iv.seg, x1);
                }
            }
            consider(f1, iv.piece, iv.seg, x1);
            consider(f2, iv.piece, iv.seg, x2);
            for (double t : {lo, hi}) consider(f(iv.piece, iv.seg, t), iv.piece, iv.seg, t);
        }
    }

    // The witness and its case.
    OneSided witness() const {
        Point2 anyPoint{};
        for (const auto& c : A_)
            if (!c.segments.empty()) anyPoint = c.segments[0].control[0];
        const double scaleRef = std::max(size_, std::fabs(anyPoint.x) + std::fabs(anyPoint.y));
        OneSided result;
        result.value = std::max(best_, 0.0);
        const Segment& sa = A_[bestPiece_].segments[bestSeg_];
        result.a = evaluate(sa, bestT_);
        result.pieceA = bestPiece_;
        result.paramA = sa.paramStart + bestT_ * (sa.paramEnd - sa.paramStart);
        const auto fs = indexB_.feet(result.a, 1e-7 * scaleRef);
        result.foot = fs.front();
        result.footQueries = queries_;
        if (result.value <= 1e-12 * scaleRef) {
            result.kind = WitnessCase::Zero;
        } else if (isEndpoint(A_[bestPiece_], bestSeg_, bestT_)) {
            result.kind = WitnessCase::EndpointOfA;
        } else {
            // A second foot, as near, elsewhere on B: the witness is on B's medial axis.
            for (size_t k = 1; k < fs.size(); ++k)
                if (dist(fs[k].point, result.foot.point) > 1e-6 * size_) {
                    result.secondFoot = fs[k];
                    result.kind = WitnessCase::OneToTwo;
                    break;
                }
            if (result.kind != WitnessCase::OneToTwo)
                result.kind = isEndpoint(B_[result.foot.piece], result.foot.segment, result.foot.t)
                                  ? WitnessCase::EndpointOfB
                                  : WitnessCase::Antipodal;
        }
        return result;
    }

    std::span<const PiecewiseBezier> A_, B_;
    const SegmentIndex indexB_;
    const HausdorffOptions& options_;
    const double size_;
    long long queries_ = 0;
    double best_ = -1;
    size_t bestPiece_ = 0, bestSeg_ = 0;
    double bestT_ = 0;
};

}  // namespace

OneSided oneSidedHausdorff(std::span<const PiecewiseBezier> A, std::span<const PiecewiseBezier> B,
                           const HausdorffOptions& options) {
    auto hasSegments = [](std::span<const PiecewiseBezier> set) {
        return std::any_of(set.begin(), set.end(), [](const auto& c) { return !c.segments.empty(); });
    };
    OneSided result;
    if (!hasSegments(A)) return result;
    if (!hasSegments(B)) {
        result.value = std::numeric_limits<double>::infinity();
        return result;
    }
    return OneSidedSearch(A, B, options).run();
}

HausdorffResult hausdorff(std::span<const PiecewiseBezier> a, std::span<const PiecewiseBezier> b,
                          const HausdorffOptions& options) {
    HausdorffResult r;
    r.ab = oneSidedHausdorff(a, b, options);
    r.ba = oneSidedHausdorff(b, a, options);
    r.H = std::max(r.ab.value, r.ba.value);
    return r;
}

OneSided oneSidedHausdorff(const PiecewiseBezier& a, const PiecewiseBezier& b,
                           const HausdorffOptions& options) {
    return oneSidedHausdorff({&a, 1}, {&b, 1}, options);
}

HausdorffResult hausdorff(const PiecewiseBezier& a, const PiecewiseBezier& b,
                          const HausdorffOptions& options) {
    return hausdorff({&a, 1}, {&b, 1}, options);
}

double vertexHausdorff(std::span<const PiecewiseBezier> a, std::span<const PiecewiseBezier> b) {
    auto oneSided = [](std::span<const PiecewiseBezier> from, std::span<const PiecewiseBezier> to) {
        const SegmentIndex index(to);
        double h = 0;
        for (const auto& c : from)
            for (const auto& s : c.segments) {
                h = std::max(h, index.distance(s.control.front()));
                h = std::max(h, index.distance(s.control.back()));
            }
        return h;
    };
    return std::max(oneSided(a, b), oneSided(b, a));
}

}  // namespace relief::curves
