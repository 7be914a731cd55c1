#include "curves/bezier.h"

#include <algorithm>
#include <cmath>

namespace relief::curves {

PiecewiseBezier toBezier(const CurveFile& c) {
    PiecewiseBezier out;
    out.closed = c.closed;
    const auto& p = c.points;
    const size_t n = p.size();
    if (c.type == "bezier") {
        out.segments.push_back({p, 0, 1});
        out.closed = false;  // one Bézier curve: its ends are its ends
    } else if (c.type == "polyline") {
        if (n == 1) out.segments.push_back({{p[0]}, 0, 0});
        const size_t edges = c.closed ? n : n - 1;
        for (size_t k = 0; k < edges && n > 1; ++k)
            out.segments.push_back({{p[k], p[(k + 1) % n]}, double(k), double(k + 1)});
    } else {  // bspline3: each knot interval's B-spline points to Bézier points
        const size_t segs = c.closed ? n : n - 3;
        for (size_t k = 0; k < segs; ++k) {
            const Point2 &P0 = p[k % n], &P1 = p[(k + 1) % n], &P2 = p[(k + 2) % n], &P3 = p[(k + 3) % n];
            auto mix = [](std::initializer_list<std::pair<double, Point2>> terms) {
                Point2 r{0, 0};
                for (const auto& [w, q] : terms) r.x += w * q.x, r.y += w * q.y;
                return r;
            };
            out.segments.push_back({{mix({{1.0 / 6, P0}, {4.0 / 6, P1}, {1.0 / 6, P2}}),
                                     mix({{2.0 / 3, P1}, {1.0 / 3, P2}}),
                                     mix({{1.0 / 3, P1}, {2.0 / 3, P2}}),
                                     mix({{1.0 / 6, P1}, {4.0 / 6, P2}, {1.0 / 6, P3}})},
                                    double(k), double(k + 1)});
        }
    }
    return out;
}

Point2 evaluate(const Segment& s, double t) {
    if (s.control.size() == 2) {  // polylines: no copy
        const Point2 p = s.control[0], q = s.control[1];
        return {p.x + t * (q.x - p.x), p.y + t * (q.y - p.y)};
    }
    std::vector<Point2> q = s.control;
    for (size_t r = 1; r < q.size(); ++r)
        for (size_t i = 0; i + r < q.size(); ++i)
            q[i] = {q[i].x + t * (q[i + 1].x - q[i].x), q[i].y + t * (q[i + 1].y - q[i].y)};
    return q[0];
}

Point2 derivative(const Segment& s, double t) {
    const size_t d = s.control.size() - 1;
    if (d == 0) return {0, 0};
    Segment h;
    for (size_t i = 0; i < d; ++i)
        h.control.push_back({d * (s.control[i + 1].x - s.control[i].x), d * (s.control[i + 1].y - s.control[i].y)});
    return evaluate(h, t);
}

void split(const std::vector<Point2>& c, double t, std::vector<Point2>& left, std::vector<Point2>& right) {
    std::vector<Point2> q = c;
    const size_t n = c.size();
    left.assign(n, {});
    right.assign(n, {});
    for (size_t r = 0; r < n; ++r) {
        left[r] = q[0];
        right[n - 1 - r] = q[n - 1 - r];
        for (size_t i = 0; i + r + 1 < n; ++i)
            q[i] = {q[i].x + t * (q[i + 1].x - q[i].x), q[i].y + t * (q[i + 1].y - q[i].y)};
    }
}

double curveSize(const PiecewiseBezier& c) {
    Bounds2 b;
    for (const auto& s : c.segments)
        for (const auto& p : s.control) b.add(p);
    return b.diagonal();
}

}  // namespace relief::curves
