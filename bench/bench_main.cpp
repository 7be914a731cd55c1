// Benchmarks (never timed unit tests). Each figure has a baseline measured in
// the same run: the refiner against a naive per-point loop, the mesh2 writer
// against fprintf("%.9g").
#include <benchmark/benchmark.h>
#include <cpl_conv.h>
#include <gdalgrid.h>
#include <fmt/format.h>
#include <immintrin.h>
#include <omp.h>

#include <cmath>
#include <algorithm>
#include <array>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "core/atomic_file.h"
#include "emit/mesh.h"
#include "emit/write_scene.h"
#include "geo/normalize.h"
#include "geo/samples.h"
#include "geo/sky_view.h"
#include "reference/naive_four_point.h"
#include "subdiv/refine.h"
#include "subdiv/row_kernels.h"

namespace {

using namespace relief;

Grid terrainNet(int n) {
    Grid g;
    g.rows = g.cols = n;
    for (int r = 0; r < n; ++r)
        for (int c = 0; c < n; ++c)
            g.points.push_back({30.0 * c, 30.0 * r,
                                500 + 300 * std::sin(0.05 * r) * std::cos(0.07 * c)});
    return g;
}

const Grid& net257() {
    static const Grid g = terrainNet(257);
    return g;
}

// Bytes each level reads and writes in memory (the fused level reads the
// coarse grid once and writes the fine one once; the row-refined rows stay in
// cache). The refiner is memory-bound: hold this against the STREAM copy.
double bytesMoved(const subdiv::Scheme& s, int rows, int cols, int levels) {
    double bytes = 0;
    long long r = rows, c = cols;
    for (int l = 0; l < levels; ++l) {
        const long long c2 = s.refinedCount(c), r2 = s.refinedCount(r);
        bytes += static_cast<double>(r * c + r2 * c2) * sizeof(Vec3);
        r = r2;
        c = c2;
    }
    return bytes;
}

void setVertexCounters(benchmark::State& state, const Grid& out, double bytes = 0) {
    state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(out.points.size()));
    state.counters["out_vertices"] = static_cast<double>(out.points.size());
    if (bytes > 0) state.SetBytesProcessed(static_cast<int64_t>(bytes * static_cast<double>(state.iterations())));
}

// STREAM-style kernels on a buffer the size of the refined grid, on range(0)
// threads (each takes its share, as STREAM's OpenMP loops do): the machine's
// memory bandwidth, measured in the same binary and run.
//   copy:  std::copy, i.e. glibc's memmove, which streams large copies with
//          non-temporal stores;
//   scale: STREAM's b[i] = q a[i] as a plain loop: ordinary stores (each
//          destination line is read before it is written), as the refiner's;
//   fill:  b[i] = q, writes only: the ceiling for a kernel that mostly writes,
//          as a refinement level does (arity^2 points written per point read);
//   fill_streaming: the same with streaming (non-temporal) stores, as the
//          refiner writes its output rows.
// Bytes: read plus written.
enum class StreamKernel { Copy, Scale, Fill, FillStreaming };

__attribute__((target("avx2"))) void fillStreaming(double* b, size_t n, double q) {
    size_t i = 0;
    for (; i < n && reinterpret_cast<std::uintptr_t>(b + i) % 32 != 0; ++i) b[i] = q;
    const __m256d v = _mm256_set1_pd(q);
    for (; i + 4 <= n; i += 4) _mm256_stream_pd(b + i, v);
    for (; i < n; ++i) b[i] = q;
    _mm_sfence();
}

struct StreamArrays {
    static constexpr size_t n = static_cast<size_t>(2049) * 2049 * 3;
    using Buffer = std::vector<double, BigBufferAllocator<double>>;
    Buffer a = Buffer(n, 1.0), b = Buffer(n, 0.0);

    static double bytes(StreamKernel kernel) {
        const size_t arrays = kernel == StreamKernel::Fill || kernel == StreamKernel::FillStreaming ? 1 : 2;
        return static_cast<double>(arrays * n * sizeof(double));
    }

    void run(StreamKernel kernel, int threads) {
        const double q = 1.000001;
        double* __restrict__ pb = b.data();
        const double* __restrict__ pa = a.data();
#pragma omp parallel num_threads(threads)
        {
            const size_t t = omp_get_thread_num(), nt = omp_get_num_threads();
            const size_t begin = n * t / nt, end = n * (t + 1) / nt;
            switch (kernel) {
                case StreamKernel::Copy: std::copy(pa + begin, pa + end, pb + begin); break;
                case StreamKernel::Scale: for (size_t i = begin; i < end; ++i) pb[i] = q * pa[i]; break;
                case StreamKernel::Fill: for (size_t i = begin; i < end; ++i) pb[i] = q; break;
                case StreamKernel::FillStreaming: fillStreaming(pb + begin, end - begin, q); break;
            }
        }
        benchmark::DoNotOptimize(b.data());
        benchmark::ClobberMemory();
    }
};

void BM_Stream(benchmark::State& state, StreamKernel kernel) {
    const int threads = static_cast<int>(state.range(0));
    StreamArrays arrays;
    for (auto _ : state) arrays.run(kernel, threads);
    state.SetBytesProcessed(static_cast<int64_t>(static_cast<double>(state.iterations()) * StreamArrays::bytes(kernel)));
}
BENCHMARK_CAPTURE(BM_Stream, copy, StreamKernel::Copy)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(BM_Stream, scale, StreamKernel::Scale)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(BM_Stream, fill, StreamKernel::Fill)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(BM_Stream, fill_streaming, StreamKernel::FillStreaming)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();

// Binary: 257 x 257 -> 2049 x 2049 (three levels); ternary: -> 2305 x 2305
// (two levels, 5.3 M vertices; a third would be 48 M). Rows then columns.
void BM_RefineTable(benchmark::State& state, subdiv::Scheme scheme) {
    const int threads = static_cast<int>(state.range(0));
    const int levels = scheme.arity == 2 ? 3 : 2;
    subdiv::Refiner refiner;  // storage reused across iterations, as STREAM's arrays are
    const Grid* out = &refiner.refine(scheme, net257(), levels, threads);  // pages touched, as STREAM's
    for (auto _ : state) {
        out = &refiner.refine(scheme, net257(), levels, threads);
        benchmark::DoNotOptimize(out->points.data());
    }
    setVertexCounters(state, *out, bytesMoved(scheme, 257, 257, levels));
}

// The refiner and the copy timed in turn, one of each per iteration (in
// alternating order), each rate taken as its best, as STREAM reports its
// kernels. The host is shared, and another tenant only ever slows a run:
// medians of BM_RefineTable and BM_Stream/copy, run a minute apart, have moved
// by 25-70 %, the refiner (arithmetic as well as memory traffic) more than the
// copy. A copy slowed for a whole benchmark would flatter the refiner, so the
// copy's best is over every pair timed so far in the process at that thread
// count. The time reported is the refiner's mean; counters: refine_ms, its
// best; copy_ms, the copy's best; ratio_to_copy, the copy's best bytes/s over
// the refiner's.
std::map<int, double> bestCopySeconds;  // by thread count

void BM_RefineAgainstCopy(benchmark::State& state, subdiv::Scheme scheme) {
    using Clock = std::chrono::steady_clock;
    const int threads = static_cast<int>(state.range(0));
    const int levels = scheme.arity == 2 ? 3 : 2;
    const double refineBytes = bytesMoved(scheme, 257, 257, levels);
    const double copyBytes = StreamArrays::bytes(StreamKernel::Copy);
    subdiv::Refiner refiner;
    StreamArrays arrays;
    const Grid* out = &refiner.refine(scheme, net257(), levels, threads);
    arrays.run(StreamKernel::Copy, threads);
    auto seconds = [](auto&& work) {
        const auto start = Clock::now();
        work();
        return std::chrono::duration<double>(Clock::now() - start).count();
    };
    auto copy = [&] { arrays.run(StreamKernel::Copy, threads); };
    auto refine = [&] {
        out = &refiner.refine(scheme, net257(), levels, threads);
        benchmark::DoNotOptimize(out->points.data());
    };
    double& copyBest = bestCopySeconds.try_emplace(threads, 1e300).first->second;
    double refineBest = 1e300;
    bool copyFirst = true;
    for (auto _ : state) {
        double copyS = 0, refineS = 0;
        if (copyFirst) {
            copyS = seconds(copy);
            refineS = seconds(refine);
        } else {
            refineS = seconds(refine);
            copyS = seconds(copy);
        }
        copyFirst = !copyFirst;
        state.SetIterationTime(refineS);
        copyBest = std::min(copyBest, copyS);
        refineBest = std::min(refineBest, refineS);
    }
    setVertexCounters(state, *out, refineBytes);
    state.counters["copy_ms"] = 1e3 * copyBest;
    state.counters["refine_ms"] = 1e3 * refineBest;
    state.counters["ratio_to_copy"] = (copyBytes / copyBest) / (refineBytes / refineBest);
}

// Each scheme of the papers at the parameters of their examples: every
// refiner benchmark takes its scheme from here, so that they compare alike.
const std::vector<std::pair<std::string, subdiv::Scheme>>& exampleSchemes() {
    static const std::vector<std::pair<std::string, subdiv::Scheme>> schemes = {
        {"dlg4", subdiv::dlgFourPoint(1.0 / 16)},
        {"four_point_4p", subdiv::fourPoint4p(7.0 / 32, 7.0 / 32, 0.5, 3.0 / 64)},
        {"binary_3p", subdiv::binary3p(0, 3.0 / 16, 1.0 / 32)},
        {"ternary_4point", subdiv::ternaryFourPoint(19.0 / 30)},
        {"ternary_blend", subdiv::ternaryBlend(-2.0 / 27, 1.0 / 81, 2.0 / 81)},
    };
    return schemes;
}

const subdiv::Scheme& exampleScheme(std::string_view name) {
    for (const auto& [n, scheme] : exampleSchemes())
        if (n == name) return scheme;
    std::abort();  // a name missing from the list above
}

// Both refiner benchmarks on every example (in this order: the table, then the pairs).
const int refinerBenchmarks = [] {
    for (const auto& [name, scheme] : exampleSchemes())
        benchmark::RegisterBenchmark(fmt::format("BM_RefineTable/{}", name).c_str(), BM_RefineTable, scheme)
            ->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();
    for (const auto& [name, scheme] : exampleSchemes())
        benchmark::RegisterBenchmark(fmt::format("BM_RefineAgainstCopy/{}", name).c_str(), BM_RefineAgainstCopy,
                                     scheme)
            ->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseManualTime();
    return 0;
}();

// The same refiner with the kernels of a smaller instruction set (where the
// CPU has the larger one): what the AVX-512 one-sweep row pass buys, and what
// AVX2 and streaming stores buy over plain C++ with ordinary stores.
void BM_RefineKernels(benchmark::State& state, subdiv::Scheme scheme, subdiv::KernelIsa isa) {
    subdiv::useKernelIsa(isa);
    BM_RefineTable(state, std::move(scheme));
    subdiv::useKernelIsa(subdiv::bestKernelIsa());
}
BENCHMARK_CAPTURE(BM_RefineKernels, four_point_4p_avx2, exampleScheme("four_point_4p"), subdiv::KernelIsa::Avx2)
    ->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(BM_RefineKernels, binary_3p_avx2, exampleScheme("binary_3p"), subdiv::KernelIsa::Avx2)
    ->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(BM_RefineKernels, dlg4_avx2, exampleScheme("dlg4"), subdiv::KernelIsa::Avx2)
    ->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(BM_RefineKernels, ternary_blend_avx2, exampleScheme("ternary_blend"), subdiv::KernelIsa::Avx2)
    ->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(BM_RefineKernels, dlg4_plain, exampleScheme("dlg4"), subdiv::KernelIsa::Baseline)
    ->Arg(1)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(BM_RefineKernels, ternary_blend_plain, exampleScheme("ternary_blend"), subdiv::KernelIsa::Baseline)
    ->Arg(1)->Unit(benchmark::kMillisecond)->UseRealTime();

// Baseline: the naive per-point 4-point loop (tests/reference), same net and depth.
void BM_RefineNaiveLoop(benchmark::State& state) {
    Grid out;
    for (auto _ : state) {
        out = reference::naiveFourPointGrid(net257(), 1.0 / 16, 3);
        benchmark::DoNotOptimize(out.points.data());
    }
    setVertexCounters(state, out);
}
BENCHMARK(BM_RefineNaiveLoop)->Unit(benchmark::kMillisecond)->UseRealTime();

const emit::Mesh& benchMesh() {
    static const geo::GeoGrid refined = [] {
        geo::GeoGrid g;
        g.grid = subdiv::refineGrid(subdiv::dlgFourPoint(1.0 / 16), terrainNet(129), 2);
        return g;
    }();
    static const emit::Mesh m = emit::buildMesh(refined, scene::LookSpec{});
    return m;
}

// The mesh2 writer, into /dev/null: bytes per second of SDL.
void BM_Mesh2Writer(benchmark::State& state) {
    std::FILE* devnull = std::fopen("/dev/null", "wb");
    size_t bytes = 0;
    for (auto _ : state) bytes = emit::writeMesh2(benchMesh(), devnull);
    std::fclose(devnull);
    state.SetBytesProcessed(state.iterations() * static_cast<int64_t>(bytes));
}
BENCHMARK(BM_Mesh2Writer)->Unit(benchmark::kMillisecond)->UseRealTime();

// Baseline: the same vertex, normal and face data (computed as the writer
// computes them) through fprintf("%.9g").
void BM_Mesh2Fprintf(benchmark::State& state) {
    std::FILE* devnull = std::fopen("/dev/null", "wb");
    const emit::Mesh& m = benchMesh();
    int64_t bytes = 0;
    for (auto _ : state) {
        bytes = 0;
        for (size_t i = 0; i < m.vertices; ++i) {
            const SceneVec3 p = m.position(i);
            bytes += std::fprintf(devnull, ",\n<%.9g,%.9g,%.9g>", p.x, p.y, p.z);
        }
        for (size_t i = 0; i < m.vertices; ++i) {
            const SceneVec3 n = m.normal(i);
            bytes += std::fprintf(devnull, ",\n<%.9g,%.9g,%.9g>", n.x, n.y, n.z);
        }
        const size_t cols = static_cast<size_t>(m.cols);
        for (size_t r = 0; r + 1 < static_cast<size_t>(m.rows); ++r)
            for (size_t c = 0; c + 1 < cols; ++c) {
                const size_t sw = r * cols + c, se = sw + 1, nw = sw + cols, ne = nw + 1;
                bytes += std::fprintf(devnull, ",\n<%zu,%zu,%zu>,%d,%d,%d", sw, se, ne, m.palette(sw),
                                      m.palette(se), m.palette(ne));
                bytes += std::fprintf(devnull, ",\n<%zu,%zu,%zu>,%d,%d,%d", sw, ne, nw, m.palette(sw),
                                      m.palette(ne), m.palette(nw));
            }
    }
    std::fclose(devnull);
    state.SetBytesProcessed(state.iterations() * bytes);
}
BENCHMARK(BM_Mesh2Fprintf)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

// ---- Hausdorff distance (paper 003): exact method against dense sampling ----
#include <cmath>
#include <random>

#include "curves/hausdorff.h"

namespace {

using relief::curves::Point2;
using relief::curves::PiecewiseBezier;

PiecewiseBezier randomClosedBSpline(unsigned seed, double radius) {
    std::mt19937 rng(seed);
    std::normal_distribution<double> n(0, 1);
    std::vector<Point2> p;
    for (int i = 0; i < 90; ++i) {
        const double a = 2 * M_PI * i / 90, r = radius * (1 + 0.15 * n(rng));
        p.push_back({r * std::cos(a), r * std::sin(a)});
    }
    return relief::curves::toBezier({"bspline3", true, p});
}

PiecewiseBezier randomOpenBezier(unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(-8, 8);
    std::vector<Point2> p;
    for (int i = 0; i < 8; ++i) p.push_back({u(rng), u(rng)});
    return relief::curves::toBezier({"bezier", false, p});
}

std::vector<Point2> sample(const PiecewiseBezier& c, int total) {
    std::vector<Point2> out;
    const int per = std::max(1, total / static_cast<int>(c.segments.size()));
    for (const auto& s : c.segments)
        for (int k = 0; k < per; ++k) out.push_back(relief::curves::evaluate(s, double(k) / per));
    return out;
}

// The sampled answer: max over A's samples of the distance to the nearest of
// B's samples, with a 2-d tree for the nearest-point search (built once per
// call, as a sampling approach must).
struct KdTree {
    std::vector<Point2> pts;  // reordered: each subtree is a contiguous range, its median in the middle
    explicit KdTree(std::vector<Point2> p) : pts(std::move(p)) { build(0, pts.size(), 0); }
    void build(size_t lo, size_t hi, int axis) {
        if (hi - lo <= 1) return;
        const size_t mid = (lo + hi) / 2;
        std::nth_element(pts.begin() + long(lo), pts.begin() + long(mid), pts.begin() + long(hi),
                         [axis](const Point2& u, const Point2& v) { return axis ? u.y < v.y : u.x < v.x; });
        build(lo, mid, 1 - axis);
        build(mid + 1, hi, 1 - axis);
    }
    void nearest(Point2 q, size_t lo, size_t hi, int axis, double& best) const {
        if (lo >= hi) return;
        const size_t mid = (lo + hi) / 2;
        const Point2& m = pts[mid];
        best = std::min(best, std::hypot(q.x - m.x, q.y - m.y));
        const double d = axis ? q.y - m.y : q.x - m.x;
        if (d < 0) {
            nearest(q, lo, mid, 1 - axis, best);
            if (-d < best) nearest(q, mid + 1, hi, 1 - axis, best);
        } else {
            nearest(q, mid + 1, hi, 1 - axis, best);
            if (d < best) nearest(q, lo, mid, 1 - axis, best);
        }
    }
};

double sampledOneSided(const std::vector<Point2>& A, const std::vector<Point2>& B) {
    const KdTree tree(B);
    double h = 0;
    for (const auto& a : A) {
        double best = 1e300;
        tree.nearest(a, 0, tree.pts.size(), 0, best);
        h = std::max(h, best);
    }
    return h;
}

struct CurvePair {
    PiecewiseBezier a, b;
};
const CurvePair& pairFor(int which) {
    static const CurvePair openVsClosed{randomOpenBezier(7), randomClosedBSpline(11, 6)};
    static const CurvePair closedVsClosed{randomClosedBSpline(5, 10), randomClosedBSpline(6, 10.5)};
    return which == 0 ? openVsClosed : closedVsClosed;
}

void BM_HausdorffExact(benchmark::State& state) {
    const auto& p = pairFor(static_cast<int>(state.range(0)));
    for (auto _ : state) {
        const auto r = relief::curves::hausdorff(p.a, p.b);
        benchmark::DoNotOptimize(r.H);
    }
    state.SetLabel(fmt::format("H={:.12f}", relief::curves::hausdorff(p.a, p.b).H));
}
BENCHMARK(BM_HausdorffExact)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

// Dense sampling with range(1) points per curve; the counter "error" is the
// sampled H minus the exact H (the sampled answer is never above it).
void BM_HausdorffSampled(benchmark::State& state) {
    const auto& p = pairFor(static_cast<int>(state.range(0)));
    const int n = static_cast<int>(state.range(1));
    const double exact = relief::curves::hausdorff(p.a, p.b).H;
    double H = 0;
    for (auto _ : state) {
        const auto sa = sample(p.a, n), sb = sample(p.b, n);
        H = std::max(sampledOneSided(sa, sb), sampledOneSided(sb, sa));
        benchmark::DoNotOptimize(H);
    }
    state.SetLabel(fmt::format("H={:.12f} error={:+.3e}", H, H - exact));
}
BENCHMARK(BM_HausdorffSampled)->Args({0, 10000})->Args({0, 100000})->Args({1, 10000})->Args({1, 100000})
    ->Unit(benchmark::kMillisecond);

}  // namespace

// ---- Hausdorff distance on terrain-sized polylines ----
// A random-walk profile of 1537 points (a level-6 row of the mountain net) and
// its next refinement (classic 4-point, 3073 points), as depth = "auto" compares
// them; the vertex-only distance (a lower bound: every vertex against the other
// polyline, exactly) in the same run as the baseline.
namespace {

struct PolylinePair {
    relief::curves::PiecewiseBezier coarse, fine;
};
const PolylinePair& terrainRows() {
    static const PolylinePair p = [] {
        std::mt19937 rng(3);
        std::normal_distribution<double> n(0, 1);
        std::vector<relief::Vec3> row;
        double z = 1000;
        for (int i = 0; i < 1537; ++i) row.push_back({52.0 * i, z += 20 * n(rng), 0});
        const auto finer = relief::subdiv::refineCurve(relief::subdiv::dlgFourPoint(1.0 / 16), row);
        auto line = [](const std::vector<relief::Vec3>& v) {
            std::vector<Point2> pts;
            for (const auto& q : v) pts.push_back({q.x, q.y});
            return relief::curves::toBezier({"polyline", false, pts});
        };
        return PolylinePair{line(row), line(finer)};
    }();
    return p;
}

// Labels are computed outside the timed loop: google-benchmark 1.7.1's
// DoNotOptimize(double&) corrupts the variable it is given.
void BM_HausdorffTerrainRow(benchmark::State& state) {
    const auto& p = terrainRows();
    for (auto _ : state) {
        const auto r = relief::curves::hausdorff(p.coarse, p.fine);
        benchmark::DoNotOptimize(r.H);
    }
    state.SetLabel(fmt::format("H={:.9f} m", relief::curves::hausdorff(p.coarse, p.fine).H));
}
BENCHMARK(BM_HausdorffTerrainRow)->Unit(benchmark::kMillisecond);

void BM_HausdorffTerrainRowVertexOnly(benchmark::State& state) {
    const auto& p = terrainRows();
    for (auto _ : state) {
        const double h = relief::curves::vertexHausdorff({&p.coarse, 1}, {&p.fine, 1});
        benchmark::DoNotOptimize(h);
    }
    state.SetLabel(fmt::format("H={:.9f} m (a lower bound)",
                               relief::curves::vertexHausdorff({&p.coarse, 1}, {&p.fine, 1})));
}
BENCHMARK(BM_HausdorffTerrainRowVertexOnly)->Unit(benchmark::kMillisecond);

// The nearest-sample fill: relief's k-d tree (geo::gridSamples, nearest
// gridding: every node filled) against GDAL's nearest neighbour with radius 0
// (what relief used before: every sample searched for every node), on the
// same scattered points and net, in the same run. Arg: samples (and about as
// many nodes).
struct ScatteredSet {
    std::vector<geo::FramePoint> points;
    std::vector<double> xs, ys, zs;
    int side = 0;  ///< net nodes per side
};
const ScatteredSet& scattered(int n) {
    static std::map<int, ScatteredSet> sets;
    auto& s = sets[n];
    if (s.points.empty()) {
        std::uint64_t state = 12345;
        auto next = [&] {  // a fixed LCG: the same points in every run
            state = state * 6364136223846793005ULL + 1442695040888963407ULL;
            return static_cast<double>(state >> 11) / 9007199254740992.0;
        };
        for (int i = 0; i < n; ++i) {
            const double x = 1000 * next(), y = 1000 * next();
            const double z = 100 * std::sin(x / 70) * std::cos(y / 90);
            s.points.push_back({{x, y, z}, {}});
            s.xs.push_back(x), s.ys.push_back(y), s.zs.push_back(z);
        }
        s.side = static_cast<int>(std::sqrt(static_cast<double>(n)));
    }
    return s;
}

void BM_NearestFill(benchmark::State& state) {
    const auto& s = scattered(static_cast<int>(state.range(0)));
    scene::NetSpec spec;
    spec.rows = spec.cols = s.side;
    spec.extentM = FrameBox{0, 0, 1000, 1000};
    spec.gridding = scene::Gridding::Nearest;
    for (auto _ : state) {
        Diagnostics diags;
        auto net = geo::gridSamples(spec, "bench", geo::Frame{}, s.points, diags);
        benchmark::DoNotOptimize(net->grid.points.data());
    }
    state.counters["nodes"] = s.side * s.side;
}
BENCHMARK(BM_NearestFill)->Arg(5000)->Arg(20000)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_NearestFillGdalRadius0(benchmark::State& state) {
    const auto& s = scattered(static_cast<int>(state.range(0)));
    GDALGridAlgorithm algorithm;
    void* options = nullptr;
    ParseAlgorithmAndOptions("nearest:radius1=0:radius2=0", &algorithm, &options);
    const double d = 1000.0 / (s.side - 1);
    std::vector<double> out(static_cast<size_t>(s.side) * s.side);
    for (auto _ : state) {
        GDALGridCreate(algorithm, options, static_cast<GUInt32>(s.xs.size()), s.xs.data(), s.ys.data(),
                       s.zs.data(), -0.5 * d, 1000 + 0.5 * d, -0.5 * d, 1000 + 0.5 * d,
                       static_cast<GUInt32>(s.side), static_cast<GUInt32>(s.side), GDT_Float64, out.data(),
                       nullptr, nullptr);
        benchmark::DoNotOptimize(out.data());
    }
    CPLFree(options);
    state.counters["nodes"] = s.side * s.side;
}
BENCHMARK(BM_NearestFillGdalRadius0)->Arg(5000)->Arg(20000)->Unit(benchmark::kMillisecond)->UseRealTime();

// Reading scattered samples: a lon,lat,elev CSV of 770,000 lines (the size of
// a 1197 x 643 DEM written out), parsed and checked; items = lines.
const std::string& samplesCsv770k() {
    static const std::string path = [] {
        const std::string p = (std::filesystem::temp_directory_path() / "relief-bench-samples.csv").string();
        std::FILE* f = std::fopen(p.c_str(), "w");
        std::fputs("lon,lat,elev\n", f);
        for (int r = 0; r < 643; ++r)
            for (int c = 0; c < 1197; ++c)
                std::fprintf(f, "%.8f,%.8f,%.3f\n", -117.5 + c * 0.000337, 36.1 + r * 0.00027,
                             1200 + 300 * std::sin(r * 0.01) * std::cos(c * 0.013));
        std::fclose(f);
        return p;
    }();
    return path;
}

void BM_ReadSamples(benchmark::State& state) {
    const std::string& path = samplesCsv770k();
    size_t count = 0;
    for (auto _ : state) {
        Diagnostics diags;
        const auto samples = geo::readSamples(path, "bench.csv", diags);
        count = samples.size();
        benchmark::DoNotOptimize(samples.data());
    }
    state.SetItemsProcessed(static_cast<int64_t>(state.iterations() * count));
}
BENCHMARK(BM_ReadSamples)->Unit(benchmark::kMillisecond)->UseRealTime();

// The baseline: the same file's bytes read into memory, no parsing.
void BM_ReadSamplesFileBytes(benchmark::State& state) {
    const std::string& path = samplesCsv770k();
    size_t bytes = 0;
    for (auto _ : state) {
        const std::string text = readFile(path);
        bytes = text.size();
        benchmark::DoNotOptimize(text.data());
    }
    state.SetBytesProcessed(static_cast<int64_t>(state.iterations() * bytes));
}
BENCHMARK(BM_ReadSamplesFileBytes)->Unit(benchmark::kMillisecond)->UseRealTime();

// render.quality = "high": the sky-view factor of a 2001 x 2001 refined grid
// (16 directions, the default radius), against the stage before it, refining a
// 1001 x 1001 net once to that grid (the default scene's four-point scheme).
const geo::GeoGrid& skyGrid() {
    static const geo::GeoGrid g = [] {
        geo::GeoGrid grid;
        grid.grid = subdiv::refineGrid(subdiv::dlgFourPoint(1.0 / 16), terrainNet(1001), 1);
        grid.dx = grid.dy = 15;
        return grid;
    }();
    return g;
}

void BM_SkyView(benchmark::State& state) {
    const geo::GeoGrid& grid = skyGrid();
    for (auto _ : state) {
        auto svf = geo::skyViewFactor(grid, {});
        benchmark::DoNotOptimize(svf.data());
    }
    state.counters["nodes"] = double(grid.grid.points.size());
}
BENCHMARK(BM_SkyView)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(3);

void BM_SkyViewBaselineRefine(benchmark::State& state) {
    const Grid net = terrainNet(1001);
    for (auto _ : state) {
        Grid out = subdiv::refineGrid(subdiv::dlgFourPoint(1.0 / 16), net, 1);
        benchmark::DoNotOptimize(out.points.data());
    }
}
BENCHMARK(BM_SkyViewBaselineRefine)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(3);

}  // namespace
