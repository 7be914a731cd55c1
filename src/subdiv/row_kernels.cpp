#include "subdiv/row_kernels.h"

#include <immintrin.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cstdint>
#include <numeric>
#include <utility>

namespace relief::subdiv {

namespace {

KernelIsa detectIsa() {
    __builtin_cpu_init();  // this runs during static initialisation
    if (!__builtin_cpu_supports("avx2")) return KernelIsa::Baseline;
    if (__builtin_cpu_supports("avx512f")) return KernelIsa::Avx512;
    return KernelIsa::Avx2;
}

const KernelIsa kBestIsa = detectIsa();
KernelIsa gIsa = kBestIsa;

// ---- Weighted sums of rows ------------------------------------------------
// One kernel per number of taps (the loop over taps unrolled) and instruction
// set; all of them compute v = w0 a0, then v += wj aj for j = 1, 2, ... per
// double, with no fused multiply-add, so they round alike.

using SumKernel = void (*)(double* out, const double* const* in, const double* w, size_t n);

// The rows and weights of one sum, copied into locals: a vector store may
// alias anything, and the compiler would otherwise reload them after every
// store.
template <int Taps>
struct LocalTaps {
    const double* row[Taps];
    double weight[Taps];
    LocalTaps(const double* const* in, const double* w) {
        for (int j = 0; j < Taps; ++j) row[j] = in[j], weight[j] = w[j];
    }
    [[gnu::always_inline]] double sum(size_t e) const {
        double v = weight[0] * row[0][e];
        for (int j = 1; j < Taps; ++j) v += weight[j] * row[j][e];
        return v;
    }
};

// One double stored: streamed with movnti (the line is not read first
// either), or an ordinary store.
template <bool Stream>
inline void storeOne(double* p, double v) {
    if (Stream)
        _mm_stream_si64(reinterpret_cast<long long*>(p), std::bit_cast<long long>(v));
    else
        *p = v;
}

// Plain C++ (the compiler vectorises it for SSE2), ordinary stores.
template <int Taps>
void sumBaseline(double* out, const double* const* in, const double* w, size_t n) {
    const LocalTaps<Taps> t(in, w);
    for (size_t e = 0; e < n; ++e) out[e] = t.sum(e);
}

// Streaming: vmovntpd where the address is aligned to the vector, movnti
// before and after, so that no output line is ever read into the cache.
// Measured in the same run against ordinary stores (257^2 refined to depth 3
// or 2, 1 thread): dlg4 11.0 -> 8.6 ms, binary-3p 14.0 -> 12.0 ms, ternary
// blend 11.7 -> 9.2 ms. An A/B comparison must time each variant after a
// warm-up: one timed straight after a 100 MB copy starts with cold caches.
template <int Taps, bool Stream>
__attribute__((target("avx2"))) void sumAvx2(double* out, const double* const* in,
                                             const double* w, size_t n) {
    const LocalTaps<Taps> t(in, w);
    size_t e = 0;
    if (Stream)
        for (; e < n && reinterpret_cast<std::uintptr_t>(out + e) % 32 != 0; ++e)
            storeOne<true>(out + e, t.sum(e));
    __m256d weight[Taps];
    for (int j = 0; j < Taps; ++j) weight[j] = _mm256_set1_pd(t.weight[j]);
    for (; e + 4 <= n; e += 4) {
        __m256d v = _mm256_mul_pd(weight[0], _mm256_loadu_pd(t.row[0] + e));
        for (int j = 1; j < Taps; ++j)
            v = _mm256_add_pd(v, _mm256_mul_pd(weight[j], _mm256_loadu_pd(t.row[j] + e)));
        if (Stream)
            _mm256_stream_pd(out + e, v);
        else
            _mm256_storeu_pd(out + e, v);
    }
    for (; e < n; ++e) storeOne<Stream>(out + e, t.sum(e));
}

constexpr int kUnrolledTaps = 9;  // the papers' rules have 1 to 5 taps; user masks may have more

template <bool Stream, size_t... T>
constexpr auto sumTable(KernelIsa isa, std::index_sequence<T...>) {
    using Table = std::array<SumKernel, sizeof...(T)>;
    switch (isa) {
        case KernelIsa::Avx2:
        case KernelIsa::Avx512: return Table{&sumAvx2<int(T) + 1, Stream>...};
        default: return Table{&sumBaseline<int(T) + 1>...};  // ordinary stores
    }
}

template <bool Stream>
SumKernel sumKernel(size_t taps) {
    static constexpr auto kTables = [] {
        std::array<std::array<SumKernel, kUnrolledTaps>, 3> t{};
        for (KernelIsa isa : {KernelIsa::Baseline, KernelIsa::Avx2, KernelIsa::Avx512})
            t[static_cast<size_t>(isa)] =
                sumTable<Stream>(isa, std::make_index_sequence<kUnrolledTaps>{});
        return t;
    }();
    if (taps < 1 || taps > kUnrolledTaps) return nullptr;
    return kTables[static_cast<size_t>(gIsa)][taps - 1];
}

// Rules longer than the unrolled kernels: tap by tap, the same sums.
void sumAnyTaps(double* out, const double* const* in, const std::vector<double>& w, size_t n) {
    for (size_t e = 0; e < n; ++e) out[e] = w[0] * in[0][e];
    for (size_t j = 1; j < w.size(); ++j)
        for (size_t e = 0; e < n; ++e) out[e] += w[j] * in[j][e];
}

}  // namespace

KernelIsa bestKernelIsa() { return kBestIsa; }
void useKernelIsa(KernelIsa isa) {
    gIsa = static_cast<int>(isa) <= static_cast<int>(kBestIsa) ? isa : kBestIsa;
}

void combineRows(double* out, const double* const* in, const std::vector<double>& w, size_t n) {
    if (SumKernel k = sumKernel<false>(w.size())) return k(out, in, w.data(), n);
    sumAnyTaps(out, in, w, n);
}

void combineRowsStreaming(double* out, const double* const* in, const std::vector<double>& w,
                          size_t n) {
    if (SumKernel k = sumKernel<true>(w.size())) return k(out, in, w.data(), n);
    sumAnyTaps(out, in, w, n);
}

void streamingDone() { _mm_sfence(); }

// ---- Interleaving the rules' points ---------------------------------------

namespace {

void interleavePointsScalar(double* out, const double* const* streams, int m, long pBegin,
                            long pEnd) {
    long i = pBegin / m;
    int r = static_cast<int>(pBegin % m);
    for (long p = pBegin; p < pEnd; ++p) {
        const double* v = streams[r] + 3 * i;
        double* o = out + 3 * p;
        o[0] = v[0] + 0.0, o[1] = v[1] + 0.0, o[2] = v[2] + 0.0;
        if (++r == m) r = 0, ++i;
    }
}

// Four consecutive output doubles touch at most two points (a point is three
// doubles), which are of different streams, and the doubles each stream gives
// are consecutive in it: every output vector is one blend of two unaligned
// loads. The pattern repeats every lcm(4, 3 M) output doubles; which loads and
// which blend, vector by vector, is worked out at compile time. Measured in the
// same run against the point-by-point copy (257^2 refined, 1 thread): dlg4
// 10.0 -> 8.6 ms, binary-3p 13.2 -> 12.0 ms, ternary blend 10.4 -> 9.2 ms.
template <int M>
struct InterleavePattern {
    static constexpr int kPeriod = std::lcm(4, 3 * M);  // output doubles
    static constexpr int kVectors = kPeriod / 4;
    static constexpr int kAdvance = kPeriod / M;  // doubles of each stream per period
    struct Vector {
        int stream[2] = {-1, -1};
        int offset[2] = {0, 0};  // first double loaded, from the period's start in the stream
        bool fromSecond[4] = {};
    };
    Vector vectors[kVectors];
    int lowest = 0, highest = 0;  // doubles read, from a period's start: [lowest, highest)

    constexpr InterleavePattern() {
        for (int v = 0; v < kVectors; ++v)
            for (int lane = 0; lane < 4; ++lane) {
                const int q = 4 * v + lane, point = q / 3;
                const int r = point % M, at = 3 * (point / M) + q % 3;
                Vector& vec = vectors[v];
                const int k = vec.stream[0] < 0 || vec.stream[0] == r ? 0 : 1;
                vec.stream[k] = r;
                vec.offset[k] = at - lane;
                vec.fromSecond[lane] = k == 1;
                lowest = std::min(lowest, at - lane);
                highest = std::max(highest, at - lane + 4);
            }
    }
};

template <int M>
__attribute__((target("avx2"))) void interleavePointsAvx2(double* out,
                                                          const double* const* streams,
                                                          long points, long readable) {
    using Pattern = InterleavePattern<M>;
    static constexpr Pattern kPattern;
    const __m256d zero = _mm256_setzero_pd();
    __m256d mask[Pattern::kVectors];
    for (int v = 0; v < Pattern::kVectors; ++v) {
        const bool* f = kPattern.vectors[v].fromSecond;
        mask[v] = _mm256_castsi256_pd(_mm256_setr_epi64x(-f[0], -f[1], -f[2], -f[3]));
    }
    // Whole periods whose loads stay inside every stream and whose stores stay
    // inside the row; the points before and after them one by one.
    const long first = (-kPattern.lowest + Pattern::kAdvance - 1) / Pattern::kAdvance;
    const long byStreams =
        readable < kPattern.highest ? 0 : (readable - kPattern.highest) / Pattern::kAdvance + 1;
    const long byOut = 3 * points / Pattern::kPeriod;
    const long last = std::max(first, std::min(byStreams, byOut));
    constexpr long kPointsPerPeriod = Pattern::kPeriod / 3;
    interleavePointsScalar(out, streams, M, 0, std::min(points, first * kPointsPerPeriod));
    for (long k = first; k < last; ++k) {
        double* o = out + k * Pattern::kPeriod;
        const long base = k * Pattern::kAdvance;
        for (int v = 0; v < Pattern::kVectors; ++v) {
            const auto& vec = kPattern.vectors[v];
            __m256d a = _mm256_loadu_pd(streams[vec.stream[0]] + base + vec.offset[0]);
            if (vec.stream[1] >= 0)
                a = _mm256_blendv_pd(
                    a, _mm256_loadu_pd(streams[vec.stream[1]] + base + vec.offset[1]), mask[v]);
            _mm256_storeu_pd(o + 4 * v, _mm256_add_pd(a, zero));
        }
    }
    interleavePointsScalar(out, streams, M, std::min(points, last * kPointsPerPeriod), points);
}

// ---- A row refined in one sweep (AVX-512) --------------------------------
// Two refined points per 8-double vector (x, y, z of each in lanes 0-2 and
// 3-5; lanes 6-7 weigh 0 and are not stored): point p, of rule p % m and
// coarse point i = p / m, needs the coarse doubles 3 (i + offsets[j]) + c; with
// the vector loaded at 3 i + 3 u, lane c of p reads u = offsets[j] and lane
// 3 + c of p + 1 reads u = (i' - i - 1) + offsets'[j]. One load per u over
// the union of the two points' taps, each with a weight per lane (0 where the
// lane does not use that u). The lanes' own terms come in their rule's order
// and the others add exact zeros, so a lane's sum is its rule's sum up to the
// sign of a zero, which the final + 0.0 makes +0, as interleavePoints does.
// The pairs repeat every m pairs (2 m points, 2 coarse points).
// Against the rules' AVX2 sums and the interleave, the whole refiner (257^2,
// the two alternated in one process, minimum of 60, 1 thread; 2 threads
// alike): four-point-4p 8.9 -> 7.5 ms, binary-3p 8.2 -> 6.9, dlg4 7.1 -> 6.6,
// ternary blend 7.55 -> 6.8, ternary 4-point 7.05 -> 6.55. Three full vectors
// per 24 doubles (every lane used, each vector its own weights) was faster in
// cache for binary rules but only 5 % in the refiner.
constexpr int kSweepMaxTaps = 8;   // union taps of a pair (coarse points one vector reads)
constexpr int kSweepMaxArity = 3;  // binary and ternary rules

}  // namespace

// The pairs of one group: pair k is refined points 2 k and 2 k + 1.
struct SweepPattern {
    int taps = 0;                        // per pair (the same for all)
    long firstTap[kSweepMaxArity] = {};  // doubles, from the group's start; taps are 3 apart
    alignas(64) double weight[kSweepMaxArity][kSweepMaxTaps][8] = {};  // per lane
    long lowestRead = 0, highestRead = 0;  // doubles [lowest, highest) from the group's start
};

namespace {

bool buildSweep(const std::vector<Taps>& rules, SweepPattern& pattern) {
    const int m = static_cast<int>(rules.size());
    int lo[kSweepMaxArity], hi[kSweepMaxArity];
    // The taps of point q (of the pair starting at point p), as u.
    auto forTaps = [&](int p, int q, auto&& visit) {
        const Taps& rule = rules[static_cast<size_t>(q % m)];
        const int shift = q == p ? 0 : q / m - p / m - 1;
        for (size_t j = 0; j < rule.offsets.size(); ++j) visit(shift + rule.offsets[j], rule.weights[j]);
    };
    for (int pair = 0; pair < m; ++pair) {
        const int p = 2 * pair;
        lo[pair] = 1 << 20, hi[pair] = -(1 << 20);
        for (int q : {p, p + 1})
            forTaps(p, q, [&](int u, double) {
                lo[pair] = std::min(lo[pair], u);
                hi[pair] = std::max(hi[pair], u);
            });
        pattern.taps = std::max(pattern.taps, hi[pair] - lo[pair] + 1);
    }
    if (pattern.taps > kSweepMaxTaps) return false;
    pattern.lowestRead = 1 << 20;
    pattern.highestRead = -(1 << 20);
    for (int pair = 0; pair < m; ++pair) {
        const int p = 2 * pair;
        pattern.firstTap[pair] = 3 * (p / m + lo[pair]);
        pattern.lowestRead = std::min(pattern.lowestRead, pattern.firstTap[pair]);
        pattern.highestRead =
            std::max(pattern.highestRead, pattern.firstTap[pair] + 3 * (pattern.taps - 1) + 8);
        for (int q : {p, p + 1})
            forTaps(p, q, [&](int u, double w) {
                for (int c = 0; c < 3; ++c) pattern.weight[pair][u - lo[pair]][3 * (q - p) + c] = w;
            });
    }
    return true;
}

// Refined points [pBegin, pEnd), one by one: the rules' sums (+ 0.0, as the
// interleave writes them).
void sweepScalar(double* out, const double* first, const std::vector<Taps>& rules, long pBegin,
                 long pEnd) {
    const long m = static_cast<long>(rules.size());
    for (long p = pBegin; p < pEnd; ++p) {
        const Taps& rule = rules[static_cast<size_t>(p % m)];
        const double* at = first + 3 * (p / m);
        for (int c = 0; c < 3; ++c) {
            double v = rule.weights[0] * at[3 * rule.offsets[0] + c];
            for (size_t j = 1; j < rule.weights.size(); ++j)
                v += rule.weights[j] * at[3 * rule.offsets[j] + c];
            out[3 * p + c] = v + 0.0;
        }
    }
}

// Groups [gBegin, gEnd) of m pairs: group g is refined points [2 m g, 2 m (g + 1)),
// from coarse doubles 6 g on.
template <int M, int T>
__attribute__((target("avx512f"))) void sweepAvx512(double* out, const double* first,
                                                   const SweepPattern& pattern, long gBegin,
                                                   long gEnd) {
    __m512d weight[M][T];
    // A pair's taps are 3 doubles apart: one position each (in a local: a
    // store could alias the pattern), the rest constant displacements. (Each
    // tap's position loaded from memory, 15 of them for ternary rules, cost
    // those all of their gain.)
    long firstTap[M];
    for (int pair = 0; pair < M; ++pair) {
        firstTap[pair] = pattern.firstTap[pair];
        for (int k = 0; k < T; ++k) weight[pair][k] = _mm512_load_pd(pattern.weight[pair][k]);
    }
    const __m512d zero = _mm512_setzero_pd();
    constexpr __mmask8 kTwoPoints = 0x3f;
    for (long g = gBegin; g < gEnd; ++g) {
        const double* at = first + 6 * g;
        double* o = out + 6 * M * g;
        for (int pair = 0; pair < M; ++pair) {
            const double* taps = at + firstTap[pair];
            __m512d sum = _mm512_mul_pd(weight[pair][0], _mm512_loadu_pd(taps));
            for (int k = 1; k < T; ++k)
                sum = _mm512_add_pd(sum, _mm512_mul_pd(weight[pair][k], _mm512_loadu_pd(taps + 3 * k)));
            _mm512_mask_storeu_pd(o + 6 * pair, kTwoPoints, _mm512_add_pd(sum, zero));
        }
    }
}

using SweepKernel = void (*)(double*, const double*, const SweepPattern&, long, long);

template <int M, size_t... T>
constexpr auto sweepTable(std::index_sequence<T...>) {
    return std::array<SweepKernel, sizeof...(T)>{&sweepAvx512<M, int(T) + 1>...};
}

}  // namespace

void interleavePoints(double* out, const double* const* streams, int m, long points,
                      long readable) {
    if (gIsa != KernelIsa::Baseline) {
        if (m == 2) return interleavePointsAvx2<2>(out, streams, points, readable);
        if (m == 3) return interleavePointsAvx2<3>(out, streams, points, readable);
    }
    interleavePointsScalar(out, streams, m, 0, points);
}

RowSweep::RowSweep(const std::vector<Taps>& rules) : rules_(rules) {
    if (gIsa != KernelIsa::Avx512 || rules.size() < 2 || rules.size() > kSweepMaxArity) return;
    auto pattern = std::make_shared<SweepPattern>();
    if (buildSweep(rules, *pattern)) pattern_ = std::move(pattern);
}

void RowSweep::refine(double* out, const double* first, long readableBefore, long readableAfter,
                      long points) const {
    static constexpr auto kBinary = sweepTable<2>(std::make_index_sequence<kSweepMaxTaps>{});
    static constexpr auto kTernary = sweepTable<3>(std::make_index_sequence<kSweepMaxTaps>{});
    const SweepPattern& pattern = *pattern_;
    const long m = static_cast<long>(rules_.size());
    // Whole groups whose loads stay in the readable doubles and whose stores
    // stay in the row; the points before and after them one by one.
    const long gBegin = std::max(0L, (-readableBefore - pattern.lowestRead + 5) / 6);
    const long byReads =
        readableAfter < pattern.highestRead ? 0 : (readableAfter - pattern.highestRead) / 6 + 1;
    const long gEnd = std::max(gBegin, std::min(byReads, points / (2 * m)));
    sweepScalar(out, first, rules_, 0, std::min(points, gBegin * 2 * m));
    const auto& kernels = m == 2 ? kBinary : kTernary;
    kernels[static_cast<size_t>(pattern.taps - 1)](out, first, pattern, gBegin, gEnd);
    sweepScalar(out, first, rules_, std::min(points, gEnd * 2 * m), points);
}

}  // namespace relief::subdiv
