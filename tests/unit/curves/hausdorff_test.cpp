#include "curves/hausdorff.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "curves/curve_file.h"

#include <cmath>
#include <algorithm>
#include <functional>
#include <random>

namespace relief::curves {
namespace {

PiecewiseBezier curve(const std::string& type, bool closed, std::vector<Point2> pts) {
    return toBezier(CurveFile{type, closed, std::move(pts)});
}

// An independent reference: dense sampling of both curves; every local
// minimum of the sampled distance is refined by ternary search (the foot),
// and every local maximum of the sampled f near the best (the maximum).
double ternary(double lo, double hi, const std::function<double(double)>& g, bool maximise) {
    for (int it = 0; it < 100; ++it) {
        const double m1 = lo + (hi - lo) / 3, m2 = hi - (hi - lo) / 3;
        const bool firstBetter = maximise ? g(m1) > g(m2) : g(m1) < g(m2);
        if (firstBetter) hi = m2;
        else lo = m1;
    }
    return g(0.5 * (lo + hi));
}

double bruteForce(const PiecewiseBezier& A, const PiecewiseBezier& B, int perSegment = 200) {
    auto nearest = [&](Point2 a) {
        double best = 1e300;
        for (size_t s = 0; s < B.segments.size(); ++s) {
            auto d = [&](double t) {
                const Point2 p = evaluate(B.segments[s], std::clamp(t, 0.0, 1.0));
                return std::hypot(p.x - a.x, p.y - a.y);
            };
            std::vector<double> v(perSegment + 1);
            for (int k = 0; k <= perSegment; ++k) v[k] = d(double(k) / perSegment);
            double step = 0;  // the control polygon's length bounds the arc's
            const auto& c = B.segments[s].control;
            for (size_t i = 0; i + 1 < c.size(); ++i) step += std::hypot(c[i + 1].x - c[i].x, c[i + 1].y - c[i].y);
            step /= perSegment;
            for (int k = 0; k <= perSegment; ++k) {
                best = std::min(best, v[k]);
                const bool localMin = (k == 0 || v[k] <= v[k - 1]) && (k == perSegment || v[k] <= v[k + 1]);
                // A sample is at most step (the arc between samples) above the
                // minimum next to it.
                if (localMin && v[k] - step < best)
                    best = std::min(best, ternary(std::max(0.0, (k - 1.0) / perSegment),
                                                  std::min(1.0, (k + 1.0) / perSegment), d, false));
            }
        }
        return best;
    };
    double best = -1;
    std::vector<std::pair<size_t, double>> peaks;
    for (size_t s = 0; s < A.segments.size(); ++s) {
        std::vector<double> v(perSegment + 1);
        for (int k = 0; k <= perSegment; ++k) v[k] = nearest(evaluate(A.segments[s], double(k) / perSegment));
        for (int k = 0; k <= perSegment; ++k) {
            best = std::max(best, v[k]);
            if ((k == 0 || v[k] >= v[k - 1]) && (k == perSegment || v[k] >= v[k + 1])) peaks.emplace_back(s, double(k) / perSegment);
        }
    }
    for (const auto& [s, t] : peaks) {
        auto f = [&, s = s](double u) { return nearest(evaluate(A.segments[s], std::clamp(u, 0.0, 1.0))); };
        if (f(t) < best - 1e-2) continue;
        best = std::max(best, ternary(std::max(0.0, t - 1.0 / perSegment), std::min(1.0, t + 1.0 / perSegment), f, true));
    }
    return best;
}

TEST(Hausdorff, SegmentEndpointCase) {
    const auto A = curve("polyline", false, {{0, 0}, {2, 0}});
    const auto B = curve("polyline", false, {{0, 0}, {1, 0}});
    const auto r = hausdorff(A, B);
    EXPECT_NEAR(r.ab.value, 1.0, 1e-12);
    EXPECT_EQ(r.ab.kind, WitnessCase::EndpointOfA);
    EXPECT_NEAR(r.ab.a.x, 2.0, 1e-12);
    EXPECT_NEAR(r.ba.value, 0.0, 1e-12);
    EXPECT_NEAR(r.H, 1.0, 1e-12);
}

// A quadratic bump over a line: apex (0, 1), foot (0, 0) inside the line: antipodal.
TEST(Hausdorff, AntipodalCase) {
    const auto A = curve("bezier", false, {{-1, 0}, {0, 2}, {1, 0}});
    const auto B = curve("polyline", false, {{-2, 0}, {2, 0}});
    const auto r = oneSidedHausdorff(A, B);
    EXPECT_NEAR(r.value, 1.0, 1e-10);
    EXPECT_EQ(r.kind, WitnessCase::Antipodal);
    EXPECT_NEAR(r.a.x, 0.0, 1e-6);
    EXPECT_NEAR(r.paramA, 0.5, 1e-6);
    EXPECT_NEAR(r.foot.point.x, 0.0, 1e-6);
}

// A line over a notch in B: the worst point (0, 1) is equidistant (sqrt 2) from
// the notch's two corners: a one-to-two point.
TEST(Hausdorff, OneToTwoCase) {
    const auto A = curve("polyline", false, {{-2, 1}, {2, 1}});
    const auto B = curve("polyline", false, {{-2, 0}, {-1, 0}, {-1, -10}, {1, -10}, {1, 0}, {2, 0}});
    const auto r = oneSidedHausdorff(A, B);
    EXPECT_NEAR(r.value, std::sqrt(2.0), 1e-10);
    EXPECT_EQ(r.kind, WitnessCase::OneToTwo);
    EXPECT_NEAR(r.a.x, 0.0, 1e-9);
    EXPECT_NEAR(std::fabs(r.foot.point.x), 1.0, 1e-9);
    EXPECT_NEAR(r.secondFoot.point.x, -r.foot.point.x, 1e-9);
}

// The parabola y = x^2 (x in [-1, 1]) against the x axis segment [-1, 1].
TEST(Hausdorff, ParabolaAgainstLine) {
    const auto A = curve("bezier", false, {{-1, 1}, {0, -1}, {1, 1}});
    const auto B = curve("polyline", false, {{-1, 0}, {1, 0}});
    const auto r = hausdorff(A, B);
    EXPECT_NEAR(r.ab.value, 1.0, 1e-12);  // the parabola's ends, straight above the line's
    EXPECT_EQ(r.ab.kind, WitnessCase::EndpointOfA);
    // From (1, 0), the nearest point of the parabola minimises (x-1)^2 + x^4:
    // 2(x-1) + 4x^3 = 0, x = 0.5897545...
    double x = 0.5;
    for (int i = 0; i < 50; ++i) x -= (2 * (x - 1) + 4 * x * x * x) / (2 + 12 * x * x);
    const double expected = std::sqrt((x - 1) * (x - 1) + x * x * x * x);
    EXPECT_NEAR(r.ba.value, expected, 1e-10);
    EXPECT_EQ(r.ba.kind, WitnessCase::EndpointOfA);
}

TEST(Hausdorff, TranslatedCopiesAndProperties) {
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> u(-1, 1);
    std::vector<Point2> pts;
    for (int i = 0; i < 12; ++i) pts.push_back({u(rng), u(rng)});
    const auto A = curve("bspline3", true, pts);
    auto moved = pts;
    for (auto& p : moved) p.x += 0.3, p.y -= 0.1;
    const auto B = curve("bspline3", true, moved);
    const auto r = hausdorff(A, B), q = hausdorff(B, A);
    EXPECT_NEAR(r.H, q.H, 1e-12);                       // symmetric
    EXPECT_LE(r.H, std::hypot(0.3, 0.1) + 1e-12);      // never more than the shift
    EXPECT_NEAR(r.H, bruteForce(A, B, 100), 1e-9);
    EXPECT_NEAR(oneSidedHausdorff(A, A).value, 0.0, 1e-12);
    // At least the vertex-only (sampled) value.
    double sampled = 0;
    for (const auto& s : A.segments) sampled = std::max(sampled, distanceToCurve(B, s.control[0]));
    EXPECT_GE(r.H, sampled - 1e-15);
}

// Random curves against the brute-force reference, including two closed cubic
// B-splines of 90 control points each, as in the paper's examples.
TEST(Hausdorff, AgainstBruteForceOnRandomCurves) {
    std::mt19937 rng(20251123);
    std::normal_distribution<double> n(0, 1);
    auto randomPoints = [&](int count, double radius) {
        std::vector<Point2> p;
        for (int i = 0; i < count; ++i) {
            const double a = 2 * M_PI * i / count;
            const double r = radius * (1 + 0.15 * n(rng));
            p.push_back({r * std::cos(a), r * std::sin(a)});
        }
        return p;
    };
    const auto A = curve("bspline3", true, randomPoints(90, 10));
    const auto B = curve("bspline3", true, randomPoints(90, 10.5));
    const auto r = hausdorff(A, B);
    EXPECT_NEAR(r.ab.value, bruteForce(A, B, 30), 1e-9);
    EXPECT_NEAR(r.ba.value, bruteForce(B, A, 30), 1e-9);
    const auto bez = curve("bezier", false, randomPoints(7, 5));
    const auto rb = hausdorff(bez, B);
    EXPECT_NEAR(rb.ab.value, bruteForce(bez, B, 200), 1e-9);
    EXPECT_NEAR(rb.ba.value, bruteForce(B, bez, 30), 1e-9);
}

// Long polylines, as the terrain uses give it (rows of a refined net against
// the level before; contour lines): the convexity bound for straight pieces
// must keep the answer exact.
TEST(Hausdorff, PolylinesAgainstBruteForce) {
    std::mt19937 rng(7);
    std::normal_distribution<double> n(0, 1);
    std::vector<Point2> row, finer, zigzag;
    double z = 0;
    for (int i = 0; i < 60; ++i) row.push_back({10.0 * i, z += 5 * n(rng)});
    for (size_t i = 0; i + 1 < row.size(); ++i) {
        finer.push_back(row[i]);
        finer.push_back({0.5 * (row[i].x + row[i + 1].x), 0.5 * (row[i].y + row[i + 1].y) + 2 * n(rng)});
    }
    finer.push_back(row.back());
    for (int i = 0; i < 40; ++i) zigzag.push_back({15.0 * i + 20 * n(rng), 30 * n(rng)});
    const auto A = curve("polyline", false, row), B = curve("polyline", false, finer),
               C = curve("polyline", false, zigzag);
    for (const auto& [a, b] : {std::pair{&A, &B}, std::pair{&B, &A}, std::pair{&A, &C}, std::pair{&C, &B}}) {
        const double reference = bruteForce(*a, *b, 12);
        EXPECT_NEAR(oneSidedHausdorff(*a, *b).value, reference, 1e-9);
        // With a floor below the answer, the answer is unchanged; above it, at most the floor.
        EXPECT_NEAR(oneSidedHausdorff(*a, *b, {0, 0.5 * reference}).value, reference, 1e-9);
        EXPECT_LE(oneSidedHausdorff(*a, *b, {0, 2 * reference}).value, 2 * reference);
    }
    EXPECT_LE(vertexHausdorff({&A, 1}, {&B, 1}), hausdorff(A, B).H);
}

// Curve sets (contour lines at one elevation): the same point set as one
// curve made of all the pieces, and the witness names its piece.
TEST(Hausdorff, CurveSets) {
    auto circle = [](double cx, double cy, double r) {
        std::vector<Point2> p;
        for (int i = 0; i < 64; ++i) p.push_back({cx + r * std::cos(2 * M_PI * i / 64), cy + r * std::sin(2 * M_PI * i / 64)});
        return curve("polyline", true, p);
    };
    const CurveSet A{circle(0, 0, 1), circle(10, 0, 2)};
    const CurveSet B{circle(0.1, 0, 1), circle(10, 0, 2.5)};
    PiecewiseBezier a, b;
    for (const auto& c : A) a.segments.insert(a.segments.end(), c.segments.begin(), c.segments.end());
    for (const auto& c : B) b.segments.insert(b.segments.end(), c.segments.begin(), c.segments.end());
    const auto sets = hausdorff(A, B);
    EXPECT_NEAR(sets.H, hausdorff(a, b).H, 1e-12);
    EXPECT_NEAR(sets.ba.value, 0.5, 1e-9);  // the larger circle grew by 0.5
    EXPECT_EQ(sets.ba.pieceA, 1u);
    EXPECT_EQ(sets.ba.foot.piece, 1u);
    const CurveSet none;
    EXPECT_TRUE(std::isinf(hausdorff(A, none).H));
    EXPECT_EQ(hausdorff(none, none).H, 0.0);
}

TEST(Hausdorff, DegenerateInputs) {
    const auto point = curve("polyline", false, {{1, 1}});
    const auto seg = curve("polyline", false, {{0, 0}, {2, 0}});
    EXPECT_NEAR(hausdorff(point, seg).ab.value, 1.0, 1e-12);
    EXPECT_NEAR(hausdorff(point, seg).ba.value, std::hypot(1.0, 1.0), 1e-12);
    // Coincident control points and a cusp (a cubic whose hodograph passes through 0).
    const auto cusp = curve("bezier", false, {{0, 0}, {2, 2}, {0, 2}, {2, 0}});
    const auto doubled = curve("bezier", false, {{0, 0}, {0, 0}, {2, 0}, {2, 0}});
    const auto r = hausdorff(cusp, doubled);
    EXPECT_NEAR(r.H, bruteForce(cusp, doubled, 400), 1e-9);
    EXPECT_NEAR(hausdorff(cusp, cusp).H, 0.0, 1e-10 * 2.9);  // 1e-10 of the curve's size
    // Huge offsets and tiny scales: the same answer, scaled.
    auto shifted = [](std::vector<Point2> p, double s, double o) {
        for (auto& q : p) q = {q.x * s + o, q.y * s + o};
        return p;
    };
    const std::vector<Point2> a{{-1, 0}, {0, 2}, {1, 0}}, b{{-2, 0}, {2, 0}};
    EXPECT_NEAR(hausdorff(curve("bezier", false, shifted(a, 1, 1e6)), curve("polyline", false, shifted(b, 1, 1e6))).H,
                1.0, 1e-9);
    EXPECT_NEAR(hausdorff(curve("bezier", false, shifted(a, 1e-6, 0)), curve("polyline", false, shifted(b, 1e-6, 0))).H,
                1e-6, 1e-16);
}

// Every file of curves relief reads (curve files, relief test's kept
// geometry) holds its points so: two finite numbers each, within 1e15.
TEST(CurveFile, PointsAreReadWithinTheLimits) {
    using nlohmann::json;
    std::vector<Point2> points;
    std::string problem;
    EXPECT_EQ(readPoints(json::parse("[[1, 2], [3e14, -1e15]]"), "points", points, problem), PointsFault::None);
    ASSERT_EQ(points.size(), 2u);
    EXPECT_EQ(points[1].y, -1e15);
    EXPECT_EQ(readPoints(json::parse("[[1, 2], [1e300, 0]]"), "levels[0].lines[1]", points, problem),
              PointsFault::BeyondRange);
    EXPECT_EQ(problem, "levels[0].lines[1][1] = [1e+300, 0] is beyond the 1e+15 a coordinate may be (in metres, "
                       "1e15 is a thousand times the distance to the Sun)");
    EXPECT_EQ(readPoints(json::parse("[[1, 2, 3]]"), "points", points, problem), PointsFault::NotPoints);
    EXPECT_EQ(problem, "points[0] must be [x, y] with two numbers");
    EXPECT_EQ(readPoints(json::parse("[[\"1\", 2]]"), "points", points, problem), PointsFault::NotPoints);
    EXPECT_EQ(readPoints(json::parse("{}"), "points", points, problem), PointsFault::NotPoints);
    EXPECT_EQ(problem, "points must be a list of points [[x, y], ...]");
    EXPECT_TRUE(points.empty());
}

}  // namespace
}  // namespace relief::curves
