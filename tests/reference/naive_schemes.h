#pragma once
// Independent, deliberately naive references for every scheme family, written
// point by point from the papers' formulas (docs/schemes.md), not from the
// rule tables of src/subdiv/scheme.cpp: the refiner's tables, offsets,
// ghost counts and kernels are checked against these. Open curves, the
// boundary's point reflection written out by hand (reflectedAt).
#include <functional>
#include <vector>

#include "core/types.h"
#include "reference/naive_four_point.h"

namespace relief::reference {

/// One refinement of an open polyline: the new points between (and at) P_i.
using NaiveCurve = std::function<std::vector<Vec3>(const std::vector<Vec3>&)>;

// Binary schemes: an "old" point at 2i and a "new" point at 2i+1.
inline std::vector<Vec3> binary(const std::vector<Vec3>& p,
                                const std::function<Vec3(long)>& oldPoint,
                                const std::function<Vec3(long)>& newPoint) {
    std::vector<Vec3> out;
    const long n = static_cast<long>(p.size());
    for (long i = 0; i < n; ++i) {
        out.push_back(oldPoint(i));
        if (i + 1 < n) out.push_back(newPoint(i));
    }
    return out;
}

// Ternary schemes: three points per interval, the first at i.
inline std::vector<Vec3> ternary(const std::vector<Vec3>& p, const std::function<Vec3(long, int)>& point) {
    std::vector<Vec3> out;
    const long n = static_cast<long>(p.size());
    for (long i = 0; i < n; ++i) {
        out.push_back(point(i, 0));
        if (i + 1 < n) {
            out.push_back(point(i, 1));
            out.push_back(point(i, 2));
        }
    }
    return out;
}

/// Paper 001, eq. (1): P'_2i = lambda P_{i-1} + (1 - lambda - mu) P_i + mu P_{i+1};
/// P'_2i+1 = (P_i + P_{i+1}) / 2 + 2 omega (d_i + d_{i+1}), with
/// d_i = P_i - [nu P_{i-1} + (1 - nu) P_{i+1}] (at nu = 1/2 the classic
/// 4-point with w = omega).
inline NaiveCurve naiveFourPoint4p(double lambda, double mu, double nu, double omega) {
    return [=](const std::vector<Vec3>& p) {
        auto P = [&](long i) { return reflectedAt(p, i); };
        auto d = [&](long i) { return P(i) - (nu * P(i - 1) + (1 - nu) * P(i + 1)); };
        return binary(
            p, [&](long i) { return lambda * P(i - 1) + (1 - lambda - mu) * P(i) + mu * P(i + 1); },
            [&](long i) { return 0.5 * (P(i) + P(i + 1)) + (2 * omega) * (d(i) + d(i + 1)); });
    };
}

/// Paper 000, Definition 2: P'_2i = lambda (P_{i-2} + P_{i+2}) + mu (P_{i-1} + P_{i+1})
/// + (1 - 2 mu - 2 lambda) P_i; P'_2i+1 = omega (P_{i-1} + P_{i+2}) + (1/2 - omega)(P_i + P_{i+1}).
inline NaiveCurve naiveBinary3p(double lambda, double mu, double omega) {
    return [=](const std::vector<Vec3>& p) {
        auto P = [&](long i) { return reflectedAt(p, i); };
        return binary(
            p,
            [&](long i) {
                return lambda * (P(i - 2) + P(i + 2)) + mu * (P(i - 1) + P(i + 1)) +
                       (1 - 2 * mu - 2 * lambda) * P(i);
            },
            [&](long i) { return omega * (P(i - 1) + P(i + 2)) + (0.5 - omega) * (P(i) + P(i + 1)); });
    };
}

/// Paper 004, eq. (3): with Delta p_i = 2 p_i - p_{i-1} - p_{i+1},
/// p'_3i = p_i + alpha Delta p_i; p'_3i+1 = (2 p_i + p_{i+1}) / 3 + beta Delta p_i + gamma Delta p_{i+1};
/// p'_3i+2 = (p_i + 2 p_{i+1}) / 3 + gamma Delta p_i + beta Delta p_{i+1}.
inline NaiveCurve naiveTernaryBlend(double alpha, double beta, double gamma) {
    return [=](const std::vector<Vec3>& p) {
        auto P = [&](long i) { return reflectedAt(p, i); };
        auto D = [&](long i) { return 2.0 * P(i) - P(i - 1) - P(i + 1); };
        return ternary(p, [&](long i, int r) {
            if (r == 0) return P(i) + alpha * D(i);
            if (r == 1) return (1.0 / 3) * (2.0 * P(i) + P(i + 1)) + beta * D(i) + gamma * D(i + 1);
            return (1.0 / 3) * (P(i) + 2.0 * P(i + 1)) + gamma * D(i) + beta * D(i + 1);
        });
    };
}

/// Paper 004's 4-point ternary interpolating scheme: p'_3i = p_i; p'_3i+1 =
/// a p_{i-1} + b p_i + c p_{i+1} + d p_{i+2} with a = -theta/9, b = 5/9 + theta/3,
/// c = 5/9 - theta/3, d = -1/9 + theta/9; p'_3i+2 is its mirror image.
inline NaiveCurve naiveTernaryFourPoint(double theta) {
    return [=](const std::vector<Vec3>& p) {
        auto P = [&](long i) { return reflectedAt(p, i); };
        const double a = -theta / 9, b = 5.0 / 9 + theta / 3, c = 5.0 / 9 - theta / 3, d = -1.0 / 9 + theta / 9;
        return ternary(p, [&](long i, int r) {
            if (r == 0) return P(i);
            if (r == 1) return a * P(i - 1) + b * P(i) + c * P(i + 1) + d * P(i + 2);
            return d * P(i - 1) + c * P(i) + b * P(i + 1) + a * P(i + 2);
        });
    };
}

/// Paper 004's parametric cubic B-spline ternary scheme:
/// p'_3i = (1/9 + eta) p_{i-1} + (7/9 - 2 eta) p_i + (1/9 + eta) p_{i+1};
/// p'_3i+1 = eta p_{i-1} + (2/3 - 2 eta) p_i + (1/3 + eta) p_{i+1};
/// p'_3i+2 = (1/3 + eta) p_i + (2/3 - 2 eta) p_{i+1} + eta p_{i+2}.
inline NaiveCurve naiveTernaryBSpline(double eta) {
    return [=](const std::vector<Vec3>& p) {
        auto P = [&](long i) { return reflectedAt(p, i); };
        return ternary(p, [&](long i, int r) {
            if (r == 0) return (1.0 / 9 + eta) * P(i - 1) + (7.0 / 9 - 2 * eta) * P(i) + (1.0 / 9 + eta) * P(i + 1);
            if (r == 1) return eta * P(i - 1) + (2.0 / 3 - 2 * eta) * P(i) + (1.0 / 3 + eta) * P(i + 1);
            return (1.0 / 3 + eta) * P(i) + (2.0 / 3 - 2 * eta) * P(i + 1) + eta * P(i + 2);
        });
    };
}

/// Rows then columns, one point at a time, `levels` times, with any of the above.
inline Grid naiveGrid(const Grid& net, const NaiveCurve& refine, int levels) {
    Grid g = net;
    for (int level = 0; level < levels; ++level) {
        Grid rowsDone;
        rowsDone.rows = g.rows;
        for (int r = 0; r < g.rows; ++r) {
            const std::vector<Vec3> row(g.points.begin() + static_cast<long>(r) * g.cols,
                                        g.points.begin() + static_cast<long>(r + 1) * g.cols);
            const auto refined = refine(row);
            rowsDone.cols = static_cast<int>(refined.size());
            rowsDone.points.insert(rowsDone.points.end(), refined.begin(), refined.end());
        }
        Grid out;
        out.cols = rowsDone.cols;
        for (int c = 0; c < out.cols; ++c) {
            std::vector<Vec3> col;
            for (int r = 0; r < rowsDone.rows; ++r) col.push_back(rowsDone.at(r, c));
            const auto refined = refine(col);
            if (c == 0) {
                out.rows = static_cast<int>(refined.size());
                out.points.resize(static_cast<size_t>(out.rows) * out.cols);
            }
            for (int r = 0; r < out.rows; ++r) out.at(r, c) = refined[static_cast<size_t>(r)];
        }
        g = std::move(out);
    }
    return g;
}

}  // namespace relief::reference
