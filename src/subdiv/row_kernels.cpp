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
    if (__builtin_cpu_supports("avx2")) return KernelIsa::Avx2;
    return KernelIsa::Baseline;
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
// blend 11.7 -> 9.2 ms. (Session 2 measured no gain: its A/B runs timed the
// plain variant first after a 100 MB copy, which leaves the caches cold.)
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
        case KernelIsa::Avx2: return Table{&sumAvx2<int(T) + 1, Stream>...};
        default: return Table{&sumBaseline<int(T) + 1>...};  // ordinary stores
    }
}

template <bool Stream>
SumKernel sumKernel(size_t taps) {
    static constexpr auto kTables = [] {
        std::array<std::array<SumKernel, kUnrolledTaps>, 2> t{};
        for (KernelIsa isa : {KernelIsa::Baseline, KernelIsa::Avx2})
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
        o[0] = v[0], o[1] = v[1], o[2] = v[2];
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
            _mm256_storeu_pd(o + 4 * v, a);
        }
    }
    interleavePointsScalar(out, streams, M, std::min(points, last * kPointsPerPeriod), points);
}

}  // namespace

void interleavePoints(double* out, const double* const* streams, int m, long points,
                      long readable) {
    if (gIsa == KernelIsa::Avx2) {
        if (m == 2) return interleavePointsAvx2<2>(out, streams, points, readable);
        if (m == 3) return interleavePointsAvx2<3>(out, streams, points, readable);
    }
    interleavePointsScalar(out, streams, m, 0, points);
}

}  // namespace relief::subdiv
