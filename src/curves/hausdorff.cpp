#include "curves/hausdorff.h"

#include <algorithm>
#include <cmath>
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

double dist(Point2 p, Point2 q) { return std::hypot(p.x - q.x, p.y - q.y); }

double binomial(int n, int k) {
    double r = 1;
    for (int i = 1; i <= k; ++i) r = r * (n - k + i) / i;
    return r;
}

// Distance from p to the control points' bounding box: a lower bound of the
// distance to the segment (convex hull property).
double boxDistance(const Segment& s, Point2 p) {
    double xmin = 1e300, xmax = -1e300, ymin = 1e300, ymax = -1e300;
    for (const auto& q : s.control) {
        xmin = std::min(xmin, q.x), xmax = std::max(xmax, q.x);
        ymin = std::min(ymin, q.y), ymax = std::max(ymax, q.y);
    }
    const double dx = std::max({xmin - p.x, 0.0, p.x - xmax});
    const double dy = std::max({ymin - p.y, 0.0, p.y - ymax});
    return std::hypot(dx, dy);
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

void segmentFeet(const Segment& s, size_t index, Point2 a, std::vector<Foot>& out) {
    const int d = static_cast<int>(s.control.size()) - 1;
    auto add = [&](double t) {
        Foot f;
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

Point2 pointOf(const PiecewiseBezier& c, size_t seg, double t) { return evaluate(c.segments[seg], t); }

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

}  // namespace

std::vector<Foot> feet(const PiecewiseBezier& b, Point2 a, double slack) {
    // Visit segments nearest-box first; stop once a box is beyond the best + slack.
    std::vector<std::pair<double, size_t>> order;
    order.reserve(b.segments.size());
    for (size_t i = 0; i < b.segments.size(); ++i) order.emplace_back(boxDistance(b.segments[i], a), i);
    std::sort(order.begin(), order.end());
    std::vector<Foot> all;
    double best = 1e300;
    for (const auto& [lower, i] : order) {
        if (lower > best + slack) break;
        const size_t before = all.size();
        segmentFeet(b.segments[i], i, a, all);
        for (size_t k = before; k < all.size(); ++k) best = std::min(best, all[k].distance);
    }
    std::sort(all.begin(), all.end(), [](const Foot& x, const Foot& y) { return x.distance < y.distance; });
    std::vector<Foot> out;
    for (const auto& f : all) {
        if (f.distance > best + slack) break;
        out.push_back(f);
    }
    return out;
}

double distanceToCurve(const PiecewiseBezier& b, Point2 a) {
    const auto f = feet(b, a, 0.0);
    return f.empty() ? 0.0 : f.front().distance;
}

OneSided oneSidedHausdorff(const PiecewiseBezier& A, const PiecewiseBezier& B) {
    OneSided result;
    if (A.segments.empty() || B.segments.empty()) return result;
    const double size = std::max({curveSize(A), curveSize(B), 1e-300});
    const double scaleRef = std::max(size, std::fabs(A.segments[0].control[0].x) + std::fabs(A.segments[0].control[0].y));
    long long queries = 0;
    auto f = [&](size_t seg, double t) {
        ++queries;
        return distanceToCurve(B, pointOf(A, seg, t));
    };

    // Samples and the Lipschitz bound per interval.
    struct Interval {
        double upper;
        size_t seg;
        double t0, t1, f0, f1;
        bool operator<(const Interval& o) const { return upper < o.upper; }
    };
    double best = -1;
    size_t bestSeg = 0;
    double bestT = 0;
    std::priority_queue<Interval> queue;
    for (size_t s = 0; s < A.segments.size(); ++s) {
        const Segment& seg = A.segments[s];
        const double M = speedBound(seg);
        const int n = seg.control.size() == 1 ? 1 : 8 * static_cast<int>(seg.control.size());
        double tPrev = 0, fPrev = f(s, 0);
        if (fPrev > best) best = fPrev, bestSeg = s, bestT = 0;
        for (int k = 1; k <= n && seg.control.size() > 1; ++k) {
            const double t = static_cast<double>(k) / n, v = f(s, t);
            if (v > best) best = v, bestSeg = s, bestT = t;
            queue.push({0.5 * (fPrev + v + M * (t - tPrev)), s, tPrev, t, fPrev, v});
            tPrev = t, fPrev = v;
        }
    }
    // Branch and bound: split intervals whose Lipschitz bound could still beat
    // the best value by more than the discovery tolerance (1e-6 of the curves'
    // size), down to intervals of 1e-3 of the size. Where f is flat at its
    // maximum (parallel or coincident pieces) every interval stays a candidate:
    // the polish below takes the best candidates to full precision.
    const double tolerance = 1e-6 * size;
    const double shortest = 1e-3 * size;  // M * (t1 - t0) below this: left to the polish
    std::vector<Interval> finalists;
    while (!queue.empty()) {
        Interval iv = queue.top();
        queue.pop();
        const double M = speedBound(A.segments[iv.seg]);
        if (iv.upper <= best + tolerance || M * (iv.t1 - iv.t0) < shortest) {
            if (iv.upper > best - tolerance) finalists.push_back(iv);
            continue;
        }
        const double tm = 0.5 * (iv.t0 + iv.t1), fm = f(iv.seg, tm);
        if (fm > best) best = fm, bestSeg = iv.seg, bestT = tm;
        queue.push({0.5 * (iv.f0 + fm + M * (tm - iv.t0)), iv.seg, iv.t0, tm, iv.f0, fm});
        queue.push({0.5 * (fm + iv.f1 + M * (iv.t1 - tm)), iv.seg, tm, iv.t1, fm, iv.f1});
    }
    // Polish: golden section on f around the best candidates (a local maximum,
    // or the kink where two feet are equally near, is unimodal there). Where f
    // is flat, any candidate is as good: the 24 with the highest bounds are
    // enough.
    std::sort(finalists.begin(), finalists.end(),
              [](const Interval& x, const Interval& y) { return x.upper > y.upper; });
    if (finalists.size() > 24) finalists.resize(24);
    for (const Interval& iv : finalists) {
        const double w = iv.t1 - iv.t0;
        double lo = std::max(0.0, iv.t0 - w), hi = std::min(1.0, iv.t1 + w);
        const double g = 0.5 * (std::sqrt(5.0) - 1);
        double x1 = hi - g * (hi - lo), x2 = lo + g * (hi - lo);
        double f1 = f(iv.seg, x1), f2 = f(iv.seg, x2);
        for (int it = 0; it < 80 && hi - lo > 1e-15; ++it) {
            if (f1 < f2) {
                lo = x1, x1 = x2, f1 = f2, x2 = lo + g * (hi - lo), f2 = f(iv.seg, x2);
            } else {
                hi = x2, x2 = x1, f2 = f1, x1 = hi - g * (hi - lo), f1 = f(iv.seg, x1);
            }
        }
        for (double t : {x1, x2, lo, hi}) {
            const double v = f(iv.seg, t);
            if (v > best) best = v, bestSeg = iv.seg, bestT = t;
        }
    }

    // The witness and its case.
    result.value = std::max(best, 0.0);
    result.a = pointOf(A, bestSeg, bestT);
    const Segment& sa = A.segments[bestSeg];
    result.paramA = sa.paramStart + bestT * (sa.paramEnd - sa.paramStart);
    const auto fs = feet(B, result.a, 1e-7 * scaleRef);
    result.foot = fs.front();
    result.footQueries = queries;
    if (result.value <= 1e-12 * scaleRef) {
        result.kind = WitnessCase::Zero;
    } else if (isEndpoint(A, bestSeg, bestT)) {
        result.kind = WitnessCase::EndpointOfA;
    } else {
        // A second foot, as near, elsewhere on B: the witness is on B's medial axis.
        for (size_t k = 1; k < fs.size(); ++k)
            if (dist(fs[k].point, result.foot.point) > 1e-6 * size) {
                result.secondFoot = fs[k];
                result.kind = WitnessCase::OneToTwo;
                break;
            }
        if (result.kind != WitnessCase::OneToTwo)
            result.kind = isEndpoint(B, result.foot.segment, result.foot.t) ? WitnessCase::EndpointOfB
                                                                            : WitnessCase::Antipodal;
    }
    return result;
}

HausdorffResult hausdorff(const PiecewiseBezier& a, const PiecewiseBezier& b) {
    HausdorffResult r;
    r.ab = oneSidedHausdorff(a, b);
    r.ba = oneSidedHausdorff(b, a);
    r.H = std::max(r.ab.value, r.ba.value);
    return r;
}

}  // namespace relief::curves
