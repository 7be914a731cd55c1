// Benchmarks (never timed unit tests). Each figure has a baseline measured in
// the same run: the refiner against a naive per-point loop, the mesh2 writer
// against fprintf("%.9g").
#include <benchmark/benchmark.h>

#include <cmath>
#include <algorithm>
#include <cstdio>

#include "emit/mesh.h"
#include "emit/write_scene.h"
#include "reference/naive_four_point.h"
#include "subdiv/refine.h"

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

// STREAM-style copy of a buffer the size of the refined grid: the machine's
// memory bandwidth, measured in the same binary and run.
void BM_StreamCopy(benchmark::State& state) {
    const size_t n = static_cast<size_t>(2049) * 2049 * 3;
    std::vector<double, BigBufferAllocator<double>> a(n, 1.0), b(n, 0.0);
    for (auto _ : state) {
        std::copy(a.begin(), a.end(), b.begin());
        benchmark::DoNotOptimize(b.data());
        benchmark::ClobberMemory();
    }
    state.SetBytesProcessed(static_cast<int64_t>(state.iterations()) * static_cast<int64_t>(2 * n * sizeof(double)));
}
BENCHMARK(BM_StreamCopy)->Unit(benchmark::kMillisecond)->UseRealTime();

// Binary: 257 x 257 -> 2049 x 2049 (three levels); ternary: -> 2305 x 2305
// (two levels, 5.3 M vertices; a third would be 48 M). Rows then columns.
void BM_RefineTable(benchmark::State& state, subdiv::Scheme scheme) {
    const int threads = static_cast<int>(state.range(0));
    const int levels = scheme.arity == 2 ? 3 : 2;
    subdiv::Refiner refiner;  // storage reused across iterations, as STREAM's arrays are
    const Grid* out = nullptr;
    for (auto _ : state) {
        out = &refiner.refine(scheme, net257(), levels, threads);
        benchmark::DoNotOptimize(out->points.data());
    }
    setVertexCounters(state, *out, bytesMoved(scheme, 257, 257, levels));
}
BENCHMARK_CAPTURE(BM_RefineTable, dlg4, subdiv::dlgFourPoint(1.0 / 16))
    ->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(BM_RefineTable, four_point_4p, subdiv::fourPoint4p(7.0 / 32, 7.0 / 32, 0.5, 3.0 / 64))
    ->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(BM_RefineTable, binary_3p, subdiv::binary3p(0, 3.0 / 16, 1.0 / 32))
    ->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();

// Ternary schemes (paper 004): 257 x 257 -> 2305 x 2305, two levels.
BENCHMARK_CAPTURE(BM_RefineTable, ternary_4point, subdiv::ternaryFourPoint(19.0 / 30))
    ->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(BM_RefineTable, ternary_blend, subdiv::ternaryBlend(-2.0 / 27, 1.0 / 81, 2.0 / 81))
    ->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();

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
    static const emit::Mesh m = [] {
        scene::SceneDesc desc;
        return emit::buildMesh(subdiv::refineGrid(subdiv::dlgFourPoint(1.0 / 16), terrainNet(129), 2),
                               desc);
    }();
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

// Baseline: the same vertex, normal and face data through fprintf("%.9g").
void BM_Mesh2Fprintf(benchmark::State& state) {
    std::FILE* devnull = std::fopen("/dev/null", "wb");
    const emit::Mesh& m = benchMesh();
    int64_t bytes = 0;
    for (auto _ : state) {
        bytes = 0;
        for (const Vec3& p : m.positions) bytes += std::fprintf(devnull, ",\n<%.9g,%.9g,%.9g>", p.x, p.y, p.z);
        for (const Vec3& n : m.normals) bytes += std::fprintf(devnull, ",\n<%.9g,%.9g,%.9g>", n.x, n.y, n.z);
        const size_t cols = static_cast<size_t>(m.cols);
        for (size_t r = 0; r + 1 < static_cast<size_t>(m.rows); ++r)
            for (size_t c = 0; c + 1 < cols; ++c) {
                const size_t sw = r * cols + c, se = sw + 1, nw = sw + cols, ne = nw + 1;
                bytes += std::fprintf(devnull, ",\n<%zu,%zu,%zu>,%d,%d,%d", sw, se, ne, m.palette[sw],
                                      m.palette[se], m.palette[ne]);
                bytes += std::fprintf(devnull, ",\n<%zu,%zu,%zu>,%d,%d,%d", sw, ne, nw, m.palette[sw],
                                      m.palette[ne], m.palette[nw]);
            }
    }
    std::fclose(devnull);
    state.SetBytesProcessed(state.iterations() * bytes);
}
BENCHMARK(BM_Mesh2Fprintf)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
