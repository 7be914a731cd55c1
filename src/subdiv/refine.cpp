#include "subdiv/refine.h"

#include <algorithm>
#include <array>
#include <cassert>

#include <omp.h>

#include "subdiv/row_kernels.h"

namespace relief::subdiv {

namespace {

// The boundary rule, point reflection: the ghost beyond an edge point is
// 2 edge - mirror, the mirror being the point as far inside (doubles
// [eBegin, eEnd) of an element). Every refiner below makes its ghosts here.
void reflect(const double* edge, const double* mirror, double* ghost, size_t eBegin, size_t eEnd) {
    for (size_t e = eBegin; e < eEnd; ++e) ghost[e] = 2 * edge[e] - mirror[e];
}

// Refines one line of n elements of `width` doubles each (an element is one
// point's x, y, z, or a whole row of points when refining across rows), using
// only doubles [eBegin, eEnd) of every element so that threads can split a
// wide element. Ghost elements are made by point reflection into `ghosts`.
// The fused level (refineLevel) has its own row pass, refineRowFlat; this one
// serves the two-pass reference (refinePass) and curves.
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
        reflect(first, pj, g, eBegin, eEnd);
        rows[before - j] = g;
    }
    for (long k = 0; k < n; ++k) rows[before + k] = src + static_cast<size_t>(k) * width;
    for (int j = 1; j <= after; ++j) {  // P_{n-1+j} = 2 P_{n-1} - P_{n-1-j}
        double* g = ghosts.data() + static_cast<size_t>(before + j - 1) * width;
        const double* pj = src + static_cast<size_t>(n - 1 - j) * width;
        reflect(last, pj, g, eBegin, eEnd);
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

// The rules as the fused level applies them (Taps, row_kernels.h): nonzero
// weights only. A zero weight adds nothing (paper 000's rules at lambda = 0
// have two: the quintic B-spline's even rule is 3 points, not 5); dropping it
// changes no sum but the sign of an exact zero.
std::vector<Taps> nonzeroTaps(const Scheme& scheme) {
    std::vector<Taps> all(scheme.rules.size());
    for (size_t r = 0; r < scheme.rules.size(); ++r) {
        const Rule& rule = scheme.rules[r];
        for (size_t j = 0; j < rule.weights.size(); ++j)
            if (rule.weights[j] != 0.0) {
                all[r].weights.push_back(rule.weights[j]);
                all[r].offsets.push_back(rule.offset + static_cast<int>(j));
            }
    }
    return all;
}

// One row of points refined along itself, for the fused level: every rule is
// a weighted sum of whole shifted copies of the (ghost-extended) row, seen as
// flat doubles, so combineRows runs it as wide contiguous loops; the rules'
// new points are then interleaved into the refined row (m points per coarse
// point). Whole rows keep the loops long and contiguous, which is faster than
// refining point by point; pieces of 64 to 256 coarse points (to keep the
// rules' results in L1) measured no faster (bench/RESULTS.md). Where the CPU
// has AVX-512, the papers' schemes skip both steps (RowSweep, row_kernels.h).
struct RowScratch {
    std::vector<double> extended;  ///< ghosts before, the row, ghosts after (x, y, z each)
    std::array<std::vector<double>, kMaxArity> rule;  ///< each rule's new points, contiguous
    std::array<const double*, kMaxArity> streams{};   ///< each rule's new points, where they are
    std::vector<const double*> inputs;
};

void refineRowFlat(const Scheme& scheme, const std::vector<Taps>& taps, const RowSweep& sweep,
                   const Vec3* src, long n, double* out, RowScratch& s) {
    const int before = scheme.ghostsBefore(), after = scheme.ghostsAfter(), m = scheme.arity;
    // Zeros beyond the ghosts, so that the sweep can read a little past them
    // (with zero weights) and still run whole groups of points to the ends.
    constexpr long kPad = 12;
    s.extended.resize(static_cast<size_t>(before + n + after) * 3 + 2 * kPad);
    std::fill(s.extended.begin(), s.extended.begin() + kPad, 0.0);
    std::fill(s.extended.end() - kPad, s.extended.end(), 0.0);
    double* ext = s.extended.data() + kPad;
    std::copy(&src[0].x, &src[0].x + 3 * n, ext + 3 * before);
    const double* first = ext + 3 * before;
    const double* last = first + 3 * (n - 1);
    for (int j = 1; j <= before; ++j)  // P_{-j} = 2 P_0 - P_j
        reflect(first, first + 3 * j, ext + 3 * (before - j), 0, 3);
    for (int j = 1; j <= after; ++j)  // P_{n-1+j} = 2 P_{n-1} - P_{n-1-j}
        reflect(last, last - 3 * j, ext + 3 * (before + n - 1 + j), 0, 3);
    if (sweep.applies())
        return sweep.refine(out, first, kPad + 3 * before, 3 * (n + after) + kPad,
                            scheme.refinedCount(n));
    for (int r = 0; r < m; ++r) {
        const Taps& rule = taps[static_cast<size_t>(r)];
        const long count = r == 0 ? n : n - 1;  // new points of child position r
        s.inputs.resize(rule.offsets.size());
        for (size_t j = 0; j < rule.offsets.size(); ++j) s.inputs[j] = first + 3 * rule.offsets[j];
        if (rule.keepsOldPoint()) {
            s.streams[r] = s.inputs[0];  // an interpolating rule: no arithmetic
        } else {
            s.rule[r].resize(static_cast<size_t>(count) * 3);
            combineRows(s.rule[r].data(), s.inputs.data(), rule.weights,
                        static_cast<size_t>(count) * 3);
            s.streams[r] = s.rule[r].data();
        }
    }
    interleavePoints(out, s.streams.data(), m, scheme.refinedCount(n), 3 * (n - 1));
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

void refineLevel(const Scheme& scheme, const Grid& in, Grid& out, int threads) {
    const int m = scheme.arity;
    const long rows = in.rows, cols = in.cols;
    out.rows = static_cast<int>(scheme.refinedCount(rows));
    out.cols = static_cast<int>(scheme.refinedCount(cols));
    out.points.resize(static_cast<size_t>(out.rows) * static_cast<size_t>(out.cols));
    const size_t width = static_cast<size_t>(out.cols) * 3;  // doubles per refined row
    const std::vector<Taps> taps = nonzeroTaps(scheme);
    const RowSweep sweep(taps);

    // Coarse rows that output rows m i + r read: i + lowest .. i + highest.
    int lowest = 0, highest = 0;
    for (const Taps& t : taps) {
        lowest = std::min(lowest, t.offsets.front());
        highest = std::max(highest, t.offsets.back());
    }
    const long ringSize = highest - lowest + 1;

#pragma omp parallel num_threads(resolveThreads(threads))
    {
        const long t = omp_get_thread_num(), nt = omp_get_num_threads();
        const long iBegin = rows * t / nt, iEnd = rows * (t + 1) / nt;
        // Per-thread storage kept between calls (OpenMP reuses its threads):
        // a level allocates nothing once the sizes have been seen.
        thread_local std::vector<double> ring;
        thread_local std::vector<Vec3> reflected;
        thread_local RowScratch scratch;
        ring.resize(static_cast<size_t>(ringSize) * width);
        reflected.resize(static_cast<size_t>(cols));
        std::vector<const double*> inputs(static_cast<size_t>(ringSize));

        auto refinedRow = [&](long k) {
            const long slot = ((k % ringSize) + ringSize) % ringSize;
            return ring.data() + static_cast<size_t>(slot) * width;
        };
        // Row-refines coarse row k into the ring; beyond the edges, the point
        // reflection of coarse rows (linear, so the same as reflecting
        // row-refined rows).
        auto makeRow = [&](long k) {
            const Vec3* src = &in.points[0] + static_cast<size_t>(std::clamp(k, 0L, rows - 1)) * cols;
            if (k < 0 || k >= rows) {
                const long edge = k < 0 ? 0 : rows - 1;
                const long mirror = k < 0 ? -k : 2 * (rows - 1) - k;
                const Vec3* e = &in.points[0] + static_cast<size_t>(edge) * cols;
                const Vec3* q = &in.points[0] + static_cast<size_t>(mirror) * cols;
                reflect(&e->x, &q->x, &reflected[0].x, 0, 3 * static_cast<size_t>(cols));
                src = reflected.data();
            }
            refineRowFlat(scheme, taps, sweep, src, cols, refinedRow(k), scratch);
        };

        for (long k = iBegin + lowest; k < iBegin + highest; ++k) makeRow(k);
        for (long i = iBegin; i < iEnd; ++i) {
            makeRow(i + highest);  // the one row step i reads that step i - 1 did not
            for (int r = 0; r < m; ++r) {
                if (r > 0 && i == rows - 1) break;
                const Taps& rule = taps[static_cast<size_t>(r)];
                for (size_t j = 0; j < rule.offsets.size(); ++j)
                    inputs[j] = refinedRow(i + rule.offsets[j]);
                combineRowsStreaming(&out.points[0].x + static_cast<size_t>(m * i + r) * width,
                                     inputs.data(), rule.weights, width);
            }
        }
        streamingDone();
    }
}

bool rowPassInOneSweep(const Scheme& scheme) { return RowSweep(nonzeroTaps(scheme)).applies(); }

const Grid& Refiner::refine(const Scheme& scheme, const Grid& net, int levels, int threads) {
    if (levels == 0) {
        buffers_[0] = net;
        latest_ = 0;
        return buffers_[0];
    }
    const Grid* src = &net;
    for (int level = 0; level < levels; ++level) {
        latest_ = level % 2;
        refineLevel(scheme, *src, buffers_[latest_], threads);
        src = &buffers_[latest_];
    }
    return *src;
}

Grid Refiner::release() { return std::move(buffers_[latest_]); }

Grid refineGrid(const Scheme& scheme, const Grid& net, int levels, int threads) {
    Refiner refiner;
    refiner.refine(scheme, net, levels, threads);
    return refiner.release();
}

}  // namespace relief::subdiv
