#include "subdiv/refine.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>
#include <tuple>

#include "reference/naive_four_point.h"
#include "reference/naive_schemes.h"
#include "core/memory_budget.h"
#include "subdiv/budget.h"
#include "subdiv/row_kernels.h"

namespace relief::subdiv {
namespace {

Grid randomNet(int rows, int cols, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> jitter(-0.3, 0.3), height(0, 100);
    Grid g;
    g.rows = rows;
    g.cols = cols;
    for (int r = 0; r < rows; ++r)
        for (int c = 0; c < cols; ++c)
            g.points.push_back({10.0 * c + jitter(rng), 10.0 * r + jitter(rng), height(rng)});
    return g;
}

Grid lattice(int rows, int cols, double dx, double dy, unsigned seed) {
    Grid g = randomNet(rows, cols, seed);
    for (int r = 0; r < rows; ++r)
        for (int c = 0; c < cols; ++c) {
            g.at(r, c).x = 1000 + dx * c;
            g.at(r, c).y = -500 + dy * r;
        }
    return g;
}

const std::vector<Scheme>& allSchemes() {
    static const std::vector<Scheme> s{dlgFourPoint(1.0 / 16),
                                       fourPoint4p(7.0 / 32, 7.0 / 32, 0.5, 3.0 / 64),
                                       fourPoint4p(1.0 / 30, 1.0 / 30, 0.5, 1.0 / 3),
                                       binary3p(0.01, 0.23, 0.07),
                                       binary3p(0, 3.0 / 16, 1.0 / 32)};
    return s;
}

TEST(Refine, InterpolatingSchemesKeepNetPoints) {
    const Grid net = randomNet(6, 7, 1);
    for (const Scheme& s : {dlgFourPoint(1.0 / 16), fourPoint4p(0, 0, 0.5, 0.05),
                            binary3p(0, 0, -0.04)}) {
        const Grid g = refineGrid(s, net, 3);
        ASSERT_EQ(g.rows, 8 * 5 + 1);
        ASSERT_EQ(g.cols, 8 * 6 + 1);
        for (int r = 0; r < net.rows; ++r)
            for (int c = 0; c < net.cols; ++c) EXPECT_EQ(g.at(8 * r, 8 * c), net.at(r, c)) << s.name;
    }
}

// The classic 4-point (w = 1/16) reproduces cubic polynomials: new points
// away from the boundary (whose ghost points are only linear) lie on the cubic.
TEST(Refine, FourPointReproducesCubics) {
    auto f = [](double t) { return 0.5 * t * t * t - 2 * t * t + 3 * t - 7; };
    std::vector<Vec3> pts;
    for (int i = 0; i < 10; ++i) pts.push_back({double(i), f(i), -f(i)});
    const auto out = refineCurve(dlgFourPoint(1.0 / 16), pts);
    ASSERT_EQ(out.size(), 19u);
    for (size_t k = 2; k + 2 < out.size(); ++k) {
        const double t = 0.5 * static_cast<double>(k);
        EXPECT_NEAR(out[k].x, t, 1e-12);
        EXPECT_NEAR(out[k].y, f(t), 1e-10) << k;
        EXPECT_NEAR(out[k].z, -f(t), 1e-10) << k;
    }
}

TEST(Refine, RowThenColumnEqualsColumnThenRow) {
    const Grid net = randomNet(7, 9, 2);
    for (const Scheme& s : allSchemes()) {
        const Grid a = refinePass(s, refinePass(s, net, Axis::AlongRows), Axis::AlongColumns);
        const Grid b = refinePass(s, refinePass(s, net, Axis::AlongColumns), Axis::AlongRows);
        ASSERT_EQ(a.points.size(), b.points.size());
        for (size_t i = 0; i < a.points.size(); ++i)
            ASSERT_LT(length(a.points[i] - b.points[i]), 1e-10) << s.name << " at " << i;
    }
}

// Point reflection at the boundary: a regular lattice stays a regular lattice
// in x and y, the net's extent and its corners stay where they were.
TEST(Refine, RegularLatticeStaysRegularAndKeepsExtent) {
    const Grid net = lattice(6, 8, 20.0, 15.0, 3);
    for (const Scheme& s : allSchemes()) {
        const Grid g = refineGrid(s, net, 3);
        for (int r = 0; r < g.rows; ++r)
            for (int c = 0; c < g.cols; ++c) {
                ASSERT_NEAR(g.at(r, c).x, 1000 + 20.0 * c / 8, 1e-9) << s.name;
                ASSERT_NEAR(g.at(r, c).y, -500 + 15.0 * r / 8, 1e-9) << s.name;
            }
    }
}

// The fused level (rows and columns in one sweep) equals the two passes.
TEST(Refine, FusedLevelEqualsTwoPasses) {
    const Grid net = randomNet(11, 8, 9);
    for (const Scheme& s : allSchemes())
        for (int threads : {1, 2}) {
            Grid fused;
            refineLevel(s, net, fused, threads);
            const Grid twoPass = refinePass(s, refinePass(s, net, Axis::AlongRows), Axis::AlongColumns);
            ASSERT_EQ(fused.rows, twoPass.rows);
            ASSERT_EQ(fused.cols, twoPass.cols);
            for (size_t i = 0; i < fused.points.size(); ++i)
                ASSERT_LT(length(fused.points[i] - twoPass.points[i]), 1e-11) << s.name << " " << i;
        }
}

// Every scheme family, and a user mask with rules longer than the unrolled
// sums of row_kernels (11 and 10 taps).
const std::vector<Scheme>& kernelSchemes() {
    static const std::vector<Scheme> s = [] {
        std::vector<Scheme> all = allSchemes();
        all.push_back(ternaryFourPoint(19.0 / 30));
        all.push_back(ternaryBlend(-2.0 / 27, 1.0 / 81, 2.0 / 81));
        all.push_back(ternaryBSpline(1.0 / 27));
        Scheme wide{"wide", 2, {}, Boundary::PointReflection};
        const std::vector<double> even{0.01, -0.02, 0.03, -0.05, 0.2, 0.66,
                                       0.2,  -0.05, 0.03, -0.02, 0.01};
        const std::vector<double> odd{0.005, -0.015, 0.03, -0.07, 0.55,
                                      0.55,  -0.07,  0.03, -0.015, 0.005};
        wide.rules = {{-5, even}, {-4, odd}};
        all.push_back(wide);
        return all;
    }();
    return s;
}

// Nets wide or tall enough for every path of the row kernels: whole
// interleave periods, several 128-point pieces (inside ones read the row in
// place, end ones a copy with ghosts), odd tails, streaming heads and tails.
TEST(Refine, FusedLevelEqualsTwoPassesOnWideAndTallNets) {
    for (const Scheme& s : kernelSchemes())
        for (auto [rows, cols] : {std::pair{7, 301}, std::pair{263, 6}}) {
            const Grid net = randomNet(rows, cols, 12);
            Grid fused;
            refineLevel(s, net, fused, 2);
            const Grid twoPass =
                refinePass(s, refinePass(s, net, Axis::AlongRows), Axis::AlongColumns);
            ASSERT_EQ(fused.points.size(), twoPass.points.size());
            for (size_t i = 0; i < fused.points.size(); ++i)
                ASSERT_LT(length(fused.points[i] - twoPass.points[i]), 1e-9) << s.name << " " << i;
        }
}

// The AVX-512, AVX2 and plain kernels compute the same sums in the same order
// (the one-sweep row pass adds exact zeros, and every row pass writes a zero
// as +0): a refined grid has the same bits on any x86-64 (so has a .pov).
// Restores the best kernels when it goes out of scope, however the test leaves
// (an ASSERT returns early), so no later test runs on the wrong kernels.
struct KernelIsaGuard {
    ~KernelIsaGuard() { useKernelIsa(bestKernelIsa()); }
};

TEST(Refine, VectorKernelsGiveTheSameBitsAsPlainOnes) {
    if (bestKernelIsa() == KernelIsa::Baseline) GTEST_SKIP() << "this CPU has no AVX2";
    const KernelIsaGuard restore;
    for (const Scheme& s : kernelSchemes())
        for (auto [rows, cols, zeros] : {std::tuple{7, 301, false}, std::tuple{150, 9, false},
                                         std::tuple{7, 301, true}}) {
            Grid net = randomNet(rows, cols, 13);
            if (zeros)  // sums of -0 and +0: every kernel must write the same zero
                for (size_t i = 0; i < net.points.size(); ++i) net.points[i].z = i % 7 ? -0.0 : 0.0;
            useKernelIsa(KernelIsa::Baseline);
            const Grid plain = refineGrid(s, net, 2, 2);
            for (KernelIsa isa : {KernelIsa::Avx2, KernelIsa::Avx512}) {
                if (static_cast<int>(isa) > static_cast<int>(bestKernelIsa())) continue;
                useKernelIsa(isa);
                const Grid vector = refineGrid(s, net, 2, 2);
                ASSERT_EQ(plain.points.size(), vector.points.size());
                EXPECT_EQ(0, std::memcmp(plain.points.data(), vector.points.data(),
                                         plain.points.size() * sizeof(Vec3)))
                    << s.name << " " << rows << " x " << cols << (zeros ? " zeros" : "")
                    << " kernels " << static_cast<int>(isa);
            }
        }
}

// Which schemes the AVX-512 one-sweep row pass takes (the test above checks
// its bits): the papers' binary and ternary ones, not rules too long for it.
TEST(Refine, OneSweepRowPassTakesThePapersSchemes) {
    if (bestKernelIsa() != KernelIsa::Avx512) GTEST_SKIP() << "this CPU has no AVX-512";
    EXPECT_TRUE(rowPassInOneSweep(fourPoint4p(7.0 / 32, 7.0 / 32, 0.5, 3.0 / 64)));
    EXPECT_TRUE(rowPassInOneSweep(binary3p(0, 3.0 / 16, 1.0 / 32)));
    EXPECT_TRUE(rowPassInOneSweep(binary3p(0.01, 0.23, 0.07)));
    EXPECT_TRUE(rowPassInOneSweep(dlgFourPoint(1.0 / 16)));
    EXPECT_TRUE(rowPassInOneSweep(ternaryBlend(-2.0 / 27, 1.0 / 81, 2.0 / 81)));
    EXPECT_TRUE(rowPassInOneSweep(ternaryFourPoint(19.0 / 30)));
    EXPECT_TRUE(rowPassInOneSweep(ternaryBSpline(1.0 / 27)));
    EXPECT_FALSE(rowPassInOneSweep(kernelSchemes().back()));  // the 11/10-point mask
}

TEST(Refine, RefinerReusesStorageAndGivesTheSameResult) {
    const Grid net = randomNet(9, 10, 10);
    Refiner refiner;
    const Scheme s = ternaryFourPoint(19.0 / 30);
    const Grid first = refiner.refine(s, net, 2);
    const Vec3* storage = refiner.refine(s, net, 2).points.data();
    EXPECT_EQ(refiner.refine(s, net, 2).points.data(), storage);
    EXPECT_EQ(refiner.refine(s, net, 2).points, first.points);
    EXPECT_EQ(refineGrid(s, net, 2).points, first.points);
}

TEST(Refine, TableRefinerMatchesNaiveFourPointLoop) {
    const Grid net = randomNet(9, 12, 4);
    const Grid fast = refineGrid(dlgFourPoint(1.0 / 16), net, 3, 2);
    const Grid slow = reference::naiveFourPointGrid(net, 1.0 / 16, 3);
    ASSERT_EQ(fast.rows, slow.rows);
    ASSERT_EQ(fast.cols, slow.cols);
    for (size_t i = 0; i < fast.points.size(); ++i)
        ASSERT_LT(length(fast.points[i] - slow.points[i]), 1e-9) << i;
}

// Every family, interpolating and approximating, binary and ternary, against
// its own point-by-point reference written from the paper's formulas, with
// parameters away from the special cases (so a wrong weight shows).
TEST(Refine, TableRefinerMatchesNaiveLoopForEveryFamily) {
    struct Case {
        const char* name;
        Scheme scheme;
        reference::NaiveCurve naive;
    };
    const std::vector<Case> cases{
        {"dlg4", dlgFourPoint(0.07), [](const std::vector<Vec3>& p) { return reference::naiveFourPointCurve(p, 0.07); }},
        {"four-point-4p", fourPoint4p(0.11, 0.05, 0.4, 0.045), reference::naiveFourPoint4p(0.11, 0.05, 0.4, 0.045)},
        {"binary-3p", binary3p(0.01, 0.23, 0.07), reference::naiveBinary3p(0.01, 0.23, 0.07)},
        {"ternary-blend", ternaryBlend(-2.0 / 27, 1.0 / 81, 2.0 / 81), reference::naiveTernaryBlend(-2.0 / 27, 1.0 / 81, 2.0 / 81)},
        {"ternary-4point", ternaryFourPoint(19.0 / 30), reference::naiveTernaryFourPoint(19.0 / 30)},
        {"ternary-bspline", ternaryBSpline(0.05), reference::naiveTernaryBSpline(0.05)},
    };
    ASSERT_EQ(cases.size(), schemeFamilies().size());  // a new family needs its reference here
    const Grid net = randomNet(9, 12, 4);
    for (const Case& c : cases) {
        const Grid fast = refineGrid(c.scheme, net, 2, 2);
        const Grid slow = reference::naiveGrid(net, c.naive, 2);
        ASSERT_EQ(fast.rows, slow.rows) << c.name;
        ASSERT_EQ(fast.cols, slow.cols) << c.name;
        for (size_t i = 0; i < fast.points.size(); ++i)
            ASSERT_LT(length(fast.points[i] - slow.points[i]), 1e-9) << c.name << " at " << i;
    }
}

TEST(Refine, ThreadCountDoesNotChangeTheResult) {
    const Grid net = randomNet(20, 17, 5);
    const Scheme s = binary3p(0.01, 0.23, 0.07);
    const Grid one = refineGrid(s, net, 2, 1), two = refineGrid(s, net, 2, 2);
    EXPECT_EQ(one.points, two.points);
}

TEST(Budget, EstimateMatchesRefinedSize) {
    const Grid net = randomNet(5, 6, 6);
    const Scheme s = dlgFourPoint(1.0 / 16);
    const auto est = estimateOutput(s, net.rows, net.cols, 3);
    const Grid g = refineGrid(s, net, 3);
    EXPECT_EQ(est.rows, g.rows);
    EXPECT_EQ(est.cols, g.cols);
    EXPECT_EQ(est.triangles, 2.0 * (g.rows - 1) * (g.cols - 1));
    EXPECT_DOUBLE_EQ(est.parseSeconds, est.triangles * 4e-6);
}

TEST(Budget, RefusesOversizedOutputNamingTheLimit) {
    Diagnostics diags;
    const auto est = estimateOutput(dlgFourPoint(1.0 / 16), 257, 257, 5);
    EXPECT_FALSE(checkBudget(est, {20e6, 2048, 120, 1e9}, {"s.toml", 9, 1}, 5, diags));
    ASSERT_EQ(diags.errorCount(), 1);
    EXPECT_EQ(formatDiagnostic(diags.all()[0]),
              "s.toml:9:1: error: depth 5 refines the net to 8193 x 8193 vertices: 1.34e+08 "
              "triangles > limits.max_triangles = 2e+07; 8054 MB of SDL > limits.max_sdl_mb = "
              "2048; ~536.9 s of POV-Ray parsing > limits.max_parse_s = 120; lower "
              "subdivision.depth, use a coarser net, or raise [limits]");
}

// The memory budget, known before anything is allocated: a 3601 x 3601
// one-arc-second tile refined once (7201 x 7201) needs about 1.8 GB (the
// grid; the mesh2 is a view of it), which a 24 GiB machine has; refused, with
// the numbers, under a smaller budget.
TEST(Budget, MemoryIsEstimatedAndRefused) {
    const auto est = estimateOutput(dlgFourPoint(1.0 / 16), 3601, 3601, 1);
    EXPECT_NEAR(est.memoryBytes / 1e9, 7201.0 * 7201 * 29 / 1e9 + 3601.0 * 3601 * 24 / 1e9, 0.01);
    EXPECT_LT(est.memoryBytes, 0.75 * 24 * 1024.0 * 1024 * 1024);
    Diagnostics diags;
    EXPECT_FALSE(checkBudget(est, {1e9, 1e9, 1e9, 1000}, {"s.toml", 4, 1}, 1, diags));
    ASSERT_EQ(diags.errorCount(), 1);
    EXPECT_EQ(formatDiagnostic(diags.all()[0]),
              "s.toml:4:1: error: depth 1 refines the net to 7201 x 7201 vertices: 1815 MB of memory > "
              "limits.max_memory_mb = 1000; lower subdivision.depth, use a coarser net, or raise [limits]");
    EXPECT_GT(relief::defaultMemoryBudgetMB(), 100);
}

}  // namespace
}  // namespace relief::subdiv

namespace relief::subdiv {
namespace {

// A closed curve wraps around: interpolating schemes keep every vertex, and
// the ternary linear B-spline puts the new points at thirds of each edge.
TEST(Refine, ClosedCurves) {
    std::vector<Vec3> hexagon;
    for (int k = 0; k < 6; ++k)
        hexagon.push_back({std::cos(k * M_PI / 3), std::sin(k * M_PI / 3), 0});
    const auto dd = refineCurveLevels(ternaryFourPoint(5.0 / 9), hexagon, true, 3);
    ASSERT_EQ(dd.size(), 6u * 27);
    for (int k = 0; k < 6; ++k) EXPECT_LT(length(dd[27 * k] - hexagon[k]), 1e-14);
    const auto linear = refineClosedCurve(ternaryBlend(0, 0, 0), hexagon);
    for (int k = 0; k < 6; ++k) {
        const Vec3 a = hexagon[k], b = hexagon[(k + 1) % 6];
        EXPECT_LT(length(linear[3 * k + 1] - ((2.0 / 3) * a + (1.0 / 3) * b)), 1e-14);
        EXPECT_LT(length(linear[3 * k + 2] - ((1.0 / 3) * a + (2.0 / 3) * b)), 1e-14);
    }
    // Approximating schemes shrink a convex closed polygon: every point stays inside.
    for (const Vec3& p : refineCurveLevels(ternaryBSpline(1.0 / 27), hexagon, true, 4))
        EXPECT_LE(length(p), 1.0 + 1e-12);
}

}  // namespace
}  // namespace relief::subdiv
