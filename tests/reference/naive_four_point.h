#pragma once
// An independent, deliberately naive reference for the classic 4-point
// scheme: one point at a time, with the boundary's point reflection written
// out by hand. Used by the differential test and as the benchmark baseline.
#include <vector>

#include "core/types.h"

namespace relief::reference {

inline Vec3 reflectedAt(const std::vector<Vec3>& p, long i) {
    const long n = static_cast<long>(p.size());
    if (i < 0) return 2.0 * p[0] - p[static_cast<size_t>(-i)];
    if (i >= n) return 2.0 * p[n - 1] - p[static_cast<size_t>(2 * (n - 1) - i)];
    return p[static_cast<size_t>(i)];
}

inline std::vector<Vec3> naiveFourPointCurve(const std::vector<Vec3>& p, double w) {
    std::vector<Vec3> out;
    const long n = static_cast<long>(p.size());
    for (long i = 0; i < n; ++i) {
        out.push_back(p[static_cast<size_t>(i)]);
        if (i + 1 == n) break;
        out.push_back((-w) * reflectedAt(p, i - 1) + (0.5 + w) * reflectedAt(p, i) +
                      (0.5 + w) * reflectedAt(p, i + 1) + (-w) * reflectedAt(p, i + 2));
    }
    return out;
}

/// Rows then columns, one point at a time, `levels` times.
inline Grid naiveFourPointGrid(const Grid& net, double w, int levels) {
    Grid g = net;
    for (int level = 0; level < levels; ++level) {
        Grid rowsDone;
        rowsDone.rows = g.rows;
        rowsDone.cols = 2 * g.cols - 1;
        for (int r = 0; r < g.rows; ++r) {
            std::vector<Vec3> row(g.points.begin() + static_cast<long>(r) * g.cols,
                                  g.points.begin() + static_cast<long>(r + 1) * g.cols);
            auto refined = naiveFourPointCurve(row, w);
            rowsDone.points.insert(rowsDone.points.end(), refined.begin(), refined.end());
        }
        Grid out;
        out.rows = 2 * g.rows - 1;
        out.cols = rowsDone.cols;
        out.points.resize(static_cast<size_t>(out.rows) * out.cols);
        for (int c = 0; c < out.cols; ++c) {
            std::vector<Vec3> col;
            for (int r = 0; r < rowsDone.rows; ++r) col.push_back(rowsDone.at(r, c));
            auto refined = naiveFourPointCurve(col, w);
            for (int r = 0; r < out.rows; ++r) out.at(r, c) = refined[static_cast<size_t>(r)];
        }
        g = std::move(out);
    }
    return g;
}

}  // namespace relief::reference
