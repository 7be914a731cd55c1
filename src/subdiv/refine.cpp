#include "subdiv/refine.h"

#include <algorithm>
#include <cassert>

#include <omp.h>

namespace relief::subdiv {

namespace {

// Refines one line of n elements of `width` doubles each (an element is one
// point's x, y, z, or a whole row of points when refining across rows), using
// only doubles [eBegin, eEnd) of every element so that threads can split a
// wide element. Ghost elements are made by point reflection into `ghosts`.
void refineLine(const Scheme& scheme, const double* src, long n, size_t width, size_t eBegin,
                size_t eEnd, double* dst, std::vector<double>& ghosts,
                std::vector<const double*>& rows) {
    const int before = scheme.ghostsBefore(), after = scheme.ghostsAfter();
    const int m = scheme.arity;
    ghosts.resize(static_cast<size_t>(before + after) * width);
    rows.resize(static_cast<size_t>(n + before + after));
    const double* first = src;
    const double* last = src + static_cast<size_t>(n - 1) * width;
    for (int j = 1; j <= before; ++j) {  // P_{-j} = 2 P_0 - P_j
        double* g = ghosts.data() + static_cast<size_t>(j - 1) * width;
        const double* pj = src + static_cast<size_t>(j) * width;
        for (size_t e = eBegin; e < eEnd; ++e) g[e] = 2 * first[e] - pj[e];
        rows[before - j] = g;
    }
    for (long k = 0; k < n; ++k) rows[before + k] = src + static_cast<size_t>(k) * width;
    for (int j = 1; j <= after; ++j) {  // P_{n-1+j} = 2 P_{n-1} - P_{n-1-j}
        double* g = ghosts.data() + static_cast<size_t>(before + j - 1) * width;
        const double* pj = src + static_cast<size_t>(n - 1 - j) * width;
        for (size_t e = eBegin; e < eEnd; ++e) g[e] = 2 * last[e] - pj[e];
        rows[before + n - 1 + j] = g;
    }

    for (long i = 0; i < n; ++i) {
        for (int r = 0; r < m; ++r) {
            if (r > 0 && i == n - 1) break;
            const Rule& rule = scheme.rules[r];
            double* out = dst + static_cast<size_t>(m * i + r) * width;
            const double* const* in = rows.data() + before + i + rule.offset;
            const size_t nw = rule.weights.size();
            const double w0 = rule.weights[0];
            const double* p0 = in[0];
            for (size_t e = eBegin; e < eEnd; ++e) out[e] = w0 * p0[e];
            for (size_t j = 1; j < nw; ++j) {
                const double wj = rule.weights[j];
                const double* pj = in[j];
                for (size_t e = eBegin; e < eEnd; ++e) out[e] += wj * pj[e];
            }
        }
    }
}

int resolveThreads(int threads) { return threads > 0 ? threads : omp_get_num_procs(); }

}  // namespace

int minPoints(const Scheme& scheme) {
    return std::max({scheme.ghostsBefore(), scheme.ghostsAfter(), 1}) + 1;
}

std::vector<Vec3> refineCurve(const Scheme& scheme, std::span<const Vec3> points) {
    assert(static_cast<int>(points.size()) >= minPoints(scheme));
    const long n = static_cast<long>(points.size());
    std::vector<Vec3> out(static_cast<size_t>(scheme.refinedCount(n)));
    std::vector<double> ghosts;
    std::vector<const double*> rows;
    refineLine(scheme, &points[0].x, n, 3, 0, 3, &out[0].x, ghosts, rows);
    return out;
}

std::vector<Vec3> refineClosedCurve(const Scheme& scheme, std::span<const Vec3> points) {
    const long n = static_cast<long>(points.size());
    const int m = scheme.arity;
    std::vector<Vec3> out(static_cast<size_t>(m * n));
    for (long i = 0; i < n; ++i)
        for (int r = 0; r < m; ++r) {
            const Rule& rule = scheme.rules[r];
            Vec3 v;
            for (size_t j = 0; j < rule.weights.size(); ++j) {
                const long k = ((i + rule.offset + static_cast<long>(j)) % n + n) % n;
                v = v + rule.weights[j] * points[static_cast<size_t>(k)];
            }
            out[static_cast<size_t>(m * i + r)] = v;
        }
    return out;
}

std::vector<Vec3> refineCurveLevels(const Scheme& scheme, std::vector<Vec3> points, bool closed,
                                    int levels) {
    for (int l = 0; l < levels; ++l)
        points = closed ? refineClosedCurve(scheme, points) : refineCurve(scheme, points);
    return points;
}

Grid refinePass(const Scheme& scheme, const Grid& in, Axis axis, int threads) {
    static_assert(sizeof(Vec3) == 3 * sizeof(double));
    const int nThreads = resolveThreads(threads);
    Grid out;
    if (axis == Axis::AlongRows) {
        out.rows = in.rows;
        out.cols = static_cast<int>(scheme.refinedCount(in.cols));
        out.points.resize(static_cast<size_t>(out.rows) * out.cols);
#pragma omp parallel num_threads(nThreads)
        {
            std::vector<double> ghosts;
            std::vector<const double*> rows;
#pragma omp for schedule(static)
            for (int r = 0; r < in.rows; ++r)
                refineLine(scheme, &in.at(r, 0).x, in.cols, 3, 0, 3, &out.at(r, 0).x, ghosts,
                           rows);
        }
    } else {
        out.rows = static_cast<int>(scheme.refinedCount(in.rows));
        out.cols = in.cols;
        out.points.resize(static_cast<size_t>(out.rows) * out.cols);
        const size_t width = static_cast<size_t>(in.cols) * 3;
        // Each thread takes a band of columns through every row: the whole
        // pass is then a few streaming sweeps over the rows.
#pragma omp parallel num_threads(nThreads)
        {
            const size_t t = static_cast<size_t>(omp_get_thread_num());
            const size_t nt = static_cast<size_t>(omp_get_num_threads());
            const size_t begin = width * t / nt, end = width * (t + 1) / nt;
            std::vector<double> ghosts;
            std::vector<const double*> rows;
            refineLine(scheme, &in.points[0].x, in.rows, width, begin, end, &out.points[0].x,
                       ghosts, rows);
        }
    }
    return out;
}

Grid refineGrid(const Scheme& scheme, const Grid& net, int levels, int threads) {
    Grid g = net;
    for (int level = 0; level < levels; ++level) {
        g = refinePass(scheme, g, Axis::AlongRows, threads);
        g = refinePass(scheme, g, Axis::AlongColumns, threads);
    }
    return g;
}

}  // namespace relief::subdiv
