// The fit of a net to samples through the scheme's own surface: the basis is
// what the refiner renders; samples of a surface the scheme makes give its
// net back; the GCV score and trace are those of the textbook formula on a
// small case computed densely here; the prefilter makes an approximating
// scheme's surface pass through the net's values; the peak loss on a cone is
// the B-spline's (4 + sqrt 2) / 9 k h, and none for an interpolating scheme.
#include <gtest/gtest.h>

#include <Eigen/Dense>

#include <cmath>
#include <map>
#include <random>
#include <thread>

#include "fit/basis.h"
#include "fit/fit_net.h"
#include "fit/prefilter.h"
#include "fit/sparse_cholesky.h"
#include "measure/peak_loss.h"
#include "subdiv/refine.h"
#include "subdiv/resolve.h"

namespace relief::fit {
namespace {

subdiv::Scheme schemeNamed(const std::string& family, const std::string& preset = "",
                           std::map<std::string, double> params = {}) {
    scene::SchemeSpec spec;
    spec.name = preset.empty() ? family : "";
    spec.preset = preset;
    spec.params = std::move(params);
    Diagnostics d;
    auto s = subdiv::resolveScheme(spec, d);
    EXPECT_TRUE(s) << family << preset;
    return s->scheme;
}

// A net rows x cols of 10 m in UTM 60S, heights from f(r, c).
geo::ControlNet netOf(int rows, int cols, const std::function<double(int, int)>& f) {
    geo::ControlNet net;
    net.frame.kind = scene::FrameKind::Utm;
    net.frame.utmZone = 60;
    net.frame.northp = false;
    net.grid.rows = rows, net.grid.cols = cols;
    net.x0 = 300000, net.y0 = 5916000, net.dx = net.dy = 10;
    for (int r = 0; r < rows; ++r)
        for (int c = 0; c < cols; ++c) net.grid.points.push_back({net.x0 + 10.0 * c, net.y0 + 10.0 * r, f(r, c)});
    return net;
}

TEST(AxisBasis, TheNetsHeightsTimesTheBasisAreWhatTheRefinerRenders) {
    for (const auto& scheme : {schemeNamed("dlg4"), schemeNamed("ternary-bspline"), schemeNamed("", "quintic-bspline"),
                               schemeNamed("", "gentle-mountains")}) {
        const geo::ControlNet net = netOf(9, 11, [](int r, int c) { return std::sin(r * 1.3) * 40 + c * c * 0.7; });
        const int depth = 2;
        const Grid refined = subdiv::refineGrid(scheme, net.grid, depth);
        const AxisBasis bx = axisBasis(scheme, net.cols(), depth), by = axisBasis(scheme, net.rows(), depth);
        ASSERT_EQ(int(bx.weights.size()), refined.cols);
        ASSERT_EQ(int(by.weights.size()), refined.rows);
        double worst = 0;
        for (int R = 0; R < refined.rows; ++R)
            for (int C = 0; C < refined.cols; ++C) {
                double z = 0;
                for (const auto& [r, wy] : by.weights[R])
                    for (const auto& [c, wx] : bx.weights[C]) z += wy * wx * net.grid.at(r, c).z;
                worst = std::max(worst, std::abs(z - refined.at(R, C).z));
            }
        EXPECT_LT(worst, 1e-11) << scheme.name;
    }
}

// Samples of the surface a net makes (at random points, more than the nodes):
// the fit without smoothing gives that net back.
TEST(FitNet, SamplesOfTheSchemesOwnSurfaceGiveItsNetBack) {
    for (const auto& scheme : {schemeNamed("dlg4"), schemeNamed("ternary-bspline")}) {
        const geo::ControlNet truth = netOf(10, 12, [](int r, int c) { return 100 + 20 * std::sin(r * 0.9 + c * 0.4) + r * c * 0.3; });
        const int depth = 2;
        const AxisBasis bx = axisBasis(scheme, truth.cols(), depth), by = axisBasis(scheme, truth.rows(), depth);
        std::mt19937 rng(7);
        std::uniform_real_distribution<double> ux(truth.x0, truth.xMax()), uy(truth.y0, truth.yMax());
        std::vector<Vec3> samples;
        SurfaceRow row;
        for (int i = 0; i < 600; ++i) {
            const double x = ux(rng), y = uy(rng);
            ASSERT_TRUE(surfaceRow(bx, by, truth, x, y, row));
            double z = 0;
            for (const auto& [r, wy] : row.y)
                for (const auto& [c, wx] : row.x) z += wy * wx * truth.grid.at(r, c).z;
            samples.push_back({x, y, z});
        }
        geo::ControlNet net = netOf(10, 12, [](int, int) { return 0.0; });
        scene::NetSpec spec;
        spec.smoothing = 0;
        Diagnostics diags;
        const auto report = fitNet(scheme, depth, samples, spec, net, diags);
        ASSERT_TRUE(report) << (diags.all().empty() ? "" : diags.all().front().message);
        double worst = 0;
        for (size_t i = 0; i < net.grid.points.size(); ++i)
            worst = std::max(worst, std::abs(net.grid.points[i].z - truth.grid.points[i].z));
        EXPECT_LT(worst, 1e-9) << scheme.name;
        EXPECT_LT(report->rmseM, 1e-9);
        EXPECT_EQ(report->nodesConstrained, report->nodes);
    }
}

// A plane is what the smoothness never pays for: any smoothing gives it back.
TEST(FitNet, APlaneIsFittedExactlyWhateverTheSmoothing) {
    const subdiv::Scheme scheme = schemeNamed("four-point-4p");
    const auto plane = [](double x, double y) { return 50 + 0.02 * (x - 300000) - 0.05 * (y - 5916000); };
    std::vector<Vec3> samples;
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> ux(300000, 300110), uy(5916000, 5916090);
    for (int i = 0; i < 40; ++i) {  // fewer samples than nodes: the rest held by the smoothness
        const double x = ux(rng), y = uy(rng);
        samples.push_back({x, y, plane(x, y)});
    }
    for (double smoothing : {1e-6, 1.0, 1e3}) {
        geo::ControlNet net = netOf(10, 12, [](int, int) { return 0.0; });
        scene::NetSpec spec;
        spec.smoothing = smoothing;
        Diagnostics diags;
        ASSERT_TRUE(fitNet(scheme, 2, samples, spec, net, diags));
        EXPECT_EQ(diags.warningCount(), 0);  // 40 samples for 120 nodes: a third, no warning
        for (const Vec3& p : net.grid.points) EXPECT_NEAR(p.z, plane(p.x, p.y), 1e-6) << smoothing;  // 2e-8 relative
    }
}

// `count` samples at random over `size` metres square from the nets' corner,
// heights f(x, y) of the offsets from it plus noise within +-`noise`.
std::vector<Vec3> scattered(int count, unsigned seed, double size, double noise,
                            const std::function<double(double, double)>& f) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> ux(300000, 300000 + size), uy(5916000, 5916000 + size), un(-noise, noise);
    std::vector<Vec3> out;
    for (int i = 0; i < count; ++i) {
        const double x = ux(rng), y = uy(rng);
        out.push_back({x, y, f(x - 300000, y - 5916000) + un(rng)});
    }
    return out;
}

// The fit's equations written out densely: A from the surface's rows, the
// thin plate's and the membrane's energies from their differences.
struct DenseFit {
    Eigen::MatrixXd a, thinPlate, membrane;
    Eigen::VectorXd s;
    double spacing = 0;  ///< the samples' mean spacing, the tension's unit

    DenseFit(const subdiv::Scheme& scheme, int depth, const geo::ControlNet& net, const std::vector<Vec3>& samples) {
        const int rows = net.rows(), cols = net.cols(), n = rows * cols, count = static_cast<int>(samples.size());
        const AxisBasis bx = axisBasis(scheme, cols, depth), by = axisBasis(scheme, rows, depth);
        a = Eigen::MatrixXd::Zero(count, n);
        s.resize(count);
        SurfaceRow row;
        for (int i = 0; i < count; ++i) {
            EXPECT_TRUE(surfaceRow(bx, by, net, samples[i].x, samples[i].y, row));
            for (const auto& [r, wy] : row.y)
                for (const auto& [c, wx] : row.x) a(i, r * cols + c) += wy * wx;
            s[i] = samples[i].z;
        }
        thinPlate = membrane = Eigen::MatrixXd::Zero(n, n);
        const double h = net.dx, area = h * h;
        auto term = [&](Eigen::MatrixXd& energy, std::initializer_list<std::pair<int, double>> t, double weight) {
            Eigen::VectorXd v = Eigen::VectorXd::Zero(n);
            for (const auto& [k, c] : t) v[k] = c;
            energy += weight * v * v.transpose();
        };
        for (int r = 0; r < rows; ++r)
            for (int c = 0; c < cols; ++c) {
                const int k = r * cols + c;
                if (c >= 1 && c + 1 < cols) term(thinPlate, {{k - 1, 1}, {k, -2}, {k + 1, 1}}, area / std::pow(h, 4));
                if (r >= 1 && r + 1 < rows) term(thinPlate, {{k - cols, 1}, {k, -2}, {k + cols, 1}}, area / std::pow(h, 4));
                if (r + 1 < rows && c + 1 < cols)
                    term(thinPlate, {{k, 1}, {k + 1, -1}, {k + cols, -1}, {k + cols + 1, 1}}, 2 * area / std::pow(h, 4));
                if (c + 1 < cols) term(membrane, {{k, -1}, {k + 1, 1}}, area / (h * h));
                if (r + 1 < rows) term(membrane, {{k, -1}, {k + cols, 1}}, area / (h * h));
            }
        spacing = std::sqrt(h * (cols - 1) * h * (rows - 1) / count);
    }

    /// V = N |(I - H) s|^2 / (N - tr H)^2 and tr H, H = A (A'A + lambda P)^-1 A'.
    std::pair<double, double> gcv(double smoothing, double tension) const {
        const Eigen::MatrixXd m = a.transpose() * a;
        const Eigen::MatrixXd p = thinPlate + std::pow(tension / spacing, 2) * membrane;
        const Eigen::MatrixXd c = m + smoothing * m.trace() / p.trace() * p;
        const Eigen::MatrixXd hat = a * c.ldlt().solve(a.transpose());
        const double n = static_cast<double>(s.size()), trace = hat.trace();
        return {n * (s - hat * s).squaredNorm() / std::pow(n - trace, 2), trace};
    }
};

// The sparse Cholesky against Eigen's dense one, on a 20 x 20 grid's
// Laplacian plus a diagonal (lower triangle; over CHOLMOD's 200 nodes, so that
// METIS orders it): its solve; b' C^-1 b summed over columns from L^-1 alone;
// a second factorization analysed as the first gives the same bits; solves of
// one and of five columns in turn; an indefinite matrix is reported so, and
// the next matrix factorizes again.
TEST(SparseCholesky, SolvesAndQuadraticFormsAreTheDenseOnes) {
    const int side = 20, n = side * side;
    std::vector<Eigen::Triplet<double>> t;
    for (int i = 0; i < n; ++i) {
        t.emplace_back(i, i, 4.5 + 0.01 * i);
        if (i % side + 1 < side) t.emplace_back(i + 1, i, -1.0);
        if (i + side < n) t.emplace_back(i + side, i, -1.0);
    }
    Eigen::SparseMatrix<double> lower(n, n);
    lower.setFromTriplets(t.begin(), t.end());
    const Eigen::SparseMatrix<double> symmetric = lower.selfadjointView<Eigen::Lower>();
    const Eigen::MatrixXd dense(symmetric);
    const Eigen::LLT<Eigen::MatrixXd> reference(dense);
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> u(-1, 1);
    const Eigen::MatrixXd b = Eigen::MatrixXd::NullaryExpr(n, 5, [&] { return u(rng); });

    SparseCholesky first, second;
    ASSERT_TRUE(first.analyse(lower));
    ASSERT_TRUE(second.analyseAs(first));
    ASSERT_EQ(first.factorize(lower), SparseCholesky::Factorized::ok);
    ASSERT_EQ(second.factorize(lower), SparseCholesky::Factorized::ok);
    const Eigen::VectorXd x = first.solve(b.col(0));
    ASSERT_EQ(x.size(), n);
    EXPECT_LT((x - reference.solve(Eigen::VectorXd(b.col(0)))).norm(), 1e-12 * x.norm());
    EXPECT_EQ(second.solve(b.col(0)), x);
    const double forms = (b.transpose() * reference.solve(b)).trace();
    EXPECT_NEAR(first.sumOfInverseForms(b), forms, 1e-12 * std::abs(forms));
    EXPECT_EQ(second.sumOfInverseForms(b), first.sumOfInverseForms(b));
    EXPECT_EQ(first.solve(b.col(0)), x);  // after a solve of five columns

    Eigen::SparseMatrix<double> indefinite = lower;
    indefinite.coeffRef(n / 2, n / 2) = -1;
    EXPECT_EQ(first.factorize(indefinite), SparseCholesky::Factorized::notPositiveDefinite);
    ASSERT_EQ(first.factorize(lower), SparseCholesky::Factorized::ok);
    EXPECT_EQ(first.solve(b.col(0)), x);
}

// GCV on 12 samples and a 5 x 5 net, against the formula computed densely.
TEST(FitNet, CrossValidationScoresAreTheFormulas) {
    const subdiv::Scheme scheme = schemeNamed("dlg4");
    const std::vector<Vec3> samples = scattered(12, 11, 40, 1, [](double x, double y) { return 0.001 * x * y; });
    geo::ControlNet net = netOf(5, 5, [](int, int) { return 0.0; });
    const DenseFit dense(scheme, 1, net, samples);
    Diagnostics diags;
    const auto report = fitNet(scheme, 1, samples, scene::NetSpec{}, net, diags);
    ASSERT_TRUE(report);
    ASSERT_EQ(report->traceMethod, "exact");
    ASSERT_GE(report->gcv.size(), 6u);
    int tensioned = 0;
    for (const GcvTrial& t : report->gcv) {
        tensioned += t.tension > 0;
        if (t.smoothing < 1e-4) continue;  // below, the equations' condition makes either side's score uncertain
        const auto [score, trace] = dense.gcv(t.smoothing, t.tension);
        EXPECT_NEAR(t.traceH, trace, 1e-7 * std::max(1.0, trace)) << t.smoothing << " " << t.tension;
        EXPECT_NEAR(t.score, score, 1e-6 * score) << t.smoothing << " " << t.tension;
    }
    EXPECT_GE(tensioned, 1);  // the tension was tried
    // The penalty chosen is the least score tried.
    double least = 1e300;
    for (const GcvTrial& t : report->gcv) least = std::min(least, t.score);
    for (const GcvTrial& t : report->gcv)
        if (t.score == least) {
            EXPECT_DOUBLE_EQ(report->smoothing, t.smoothing);
            EXPECT_DOUBLE_EQ(report->tension, t.tension);
        }
}

// Over 400 nodes the trace is estimated from probes over the samples, whose
// N - tr H is accurate however closely the fit follows them. An estimate over
// the nodes was off by more than N - tr H itself there, so the score of a
// near-interpolation came out near zero and won: on 150 samples of a 21 x 21
// net, every trial's N - tr H within 25 % of the formula's, the search down
// to fits that close, and the penalty chosen within 20 % of the least score by
// the formula, not the least smoothing tried.
TEST(FitNet, CrossValidationTracesHoldForCloseFits) {
    const subdiv::Scheme scheme = schemeNamed("dlg4");
    const std::vector<Vec3> samples =
        scattered(150, 3, 200, 0.5, [](double x, double y) { return 20 * std::sin(x / 40) * std::cos(y / 55); });
    geo::ControlNet net = netOf(21, 21, [](int, int) { return 0.0; });
    const DenseFit dense(scheme, 1, net, samples);
    Diagnostics diags;
    const auto report = fitNet(scheme, 1, samples, scene::NetSpec{}, net, diags);
    ASSERT_TRUE(report);
    ASSERT_NE(report->traceMethod, "exact");
    const double n = static_cast<double>(samples.size());
    double leastByFormula = 1e300, chosenByFormula = 0, closest = n, smallest = 1e300;
    for (const GcvTrial& t : report->gcv) {
        const auto [score, trace] = dense.gcv(t.smoothing, t.tension);
        EXPECT_NEAR(n - t.traceH, n - trace, 0.25 * (n - trace)) << t.smoothing << " " << t.tension;
        leastByFormula = std::min(leastByFormula, score);
        closest = std::min(closest, n - trace);
        smallest = std::min(smallest, t.smoothing);
        if (t.smoothing == report->smoothing && t.tension == report->tension) chosenByFormula = score;
    }
    EXPECT_LT(closest, 0.05 * n);  // the search reached fits close to interpolation, where the old estimate failed
    EXPECT_LE(chosenByFormula, 1.2 * leastByFormula);
    EXPECT_GT(report->smoothing, smallest);
}

// Without net.tension, after the smoothing's search at none: tensions 1 and
// 1/2 at its best smoothing, one trial each; they are pursued only if one
// gains a thousandth of the score, then twice the winner (or, if 1/2 won,
// half) only while the last tension tried won, within 1/4 .. 8, two trials
// each; the penalty kept is the least score of all. On a smooth surface no
// tension is pursued (none chosen), on one with sharp ridges between the
// samples it is, upwards (4 chosen: the interpolations that score less stray
// from the data and are passed by).
TEST(FitNet, TensionsAreTriedOutwardsWhileTheyWin) {
    const subdiv::Scheme scheme = schemeNamed("dlg4");
    for (const double roughness : {0.0, 40.0}) {
        std::mt19937 rng(11);
        std::normal_distribution<double> noise(0, 1);
        const std::vector<Vec3> samples = scattered(150, 3, 200, 0.5, [&](double x, double y) {
            return 20 * std::sin(x / 40) * std::cos(y / 55) + roughness * std::abs(std::sin(x / 7 + y / 5)) + 0.01 * noise(rng);
        });
        geo::ControlNet net = netOf(21, 21, [](int, int) { return 0.0; });
        Diagnostics diags;
        const auto report = fitNet(scheme, 1, samples, scene::NetSpec{}, net, diags);
        ASSERT_TRUE(report);
        std::vector<double> tensions;  // in the order first tried, none left out
        std::map<double, std::pair<double, int>> atTension;  // least score, trials
        double least = 1e300;
        // The score the search goes by: none for a trial whose surface strays from its data.
        const auto searched = [](const GcvTrial& t) { return t.strays ? 1e300 : t.score; };
        for (const GcvTrial& t : report->gcv) {
            if (!atTension.count(t.tension)) tensions.push_back(t.tension), atTension[t.tension] = {1e300, 0};
            auto& [score, trials] = atTension[t.tension];
            score = std::min(score, searched(t)), ++trials, least = std::min(least, searched(t));
        }
        const auto chosen = std::min_element(report->gcv.begin(), report->gcv.end(),
                                             [&](const GcvTrial& a, const GcvTrial& b) { return searched(a) < searched(b); });
        const bool anyStrays = std::any_of(report->gcv.begin(), report->gcv.end(), [](const GcvTrial& t) { return t.strays; });
        ASSERT_GE(tensions.size(), 3u) << roughness;  // none, 1 and 1/2
        EXPECT_EQ(tensions[0], 0);
        EXPECT_EQ(tensions[1], 1);
        EXPECT_EQ(tensions[2], 0.5);
        EXPECT_EQ(atTension[1].second, 1);
        EXPECT_EQ(atTension[0.5].second, 1);
        const double firstBest = std::min(atTension[1].first, atTension[0.5].first);
        const bool pursued = firstBest < (1 - 1e-3) * atTension[0].first;
        EXPECT_EQ(pursued, roughness > 0);  // the ridged surface wants a tension, the smooth one none
        if (!pursued) {
            EXPECT_EQ(tensions.size(), 3u) << "went on after tensions 1 and 1/2 gained too little";
        }
        const double factor = atTension[1].first < atTension[0.5].first ? 2 : 0.5;
        double bestBefore = std::min(atTension[0].first, firstBest);
        for (size_t i = 3; i < tensions.size(); ++i) {
            const double t = tensions[i];
            EXPECT_DOUBLE_EQ(t, (i == 3 ? (factor == 2 ? 1 : 0.5) : tensions[i - 1]) * factor);
            EXPECT_TRUE(atTension[t].second == 2 || (atTension[t].second == 1 && chosen->smoothing < 2e-6))
                << t;  // at the least smoothing tried, a third of a decade below is out of the range
            EXPECT_TRUE(t >= 0.25 && t <= 8) << t;
            const bool won = atTension[t].first < bestBefore;
            if (i + 1 < tensions.size()) EXPECT_TRUE(won) << "went on after tension " << t << " lost";
            else EXPECT_TRUE(!won || t * factor < 0.25 || t * factor > 8) << "stopped while tension " << t << " won";
            bestBefore = std::min(bestBefore, atTension[t].first);
        }
        // The search's choice: the least score of the trials whose surfaces do not stray from their
        // data (some stray on both surfaces: the smallest smoothings). On the ridges GCV's least score
        // of all is an interpolation (smoothing 1e-6, tension 2),
        // which between samples 16 m apart rises from them 6.3 times as steeply as any two of them do;
        // the search passes it by and keeps smoothing 46, tension 4. None is pulled in after.
        EXPECT_TRUE(anyStrays);
        EXPECT_EQ(chosen->tension, roughness > 0 ? 4 : 0);
        EXPECT_EQ(report->chosenBy, "generalized cross-validation");
        EXPECT_EQ(report->tension, chosen->tension);
        EXPECT_EQ(report->smoothing, chosen->smoothing);
        EXPECT_LE(report->strayFromData, kStrayLimit);
    }
}

// The smoothing chosen by GCV with Hutchinson's probes (over 400 nodes), two
// trials at a time: the same bits in every run, and when two fits run at once
// in one process (METIS, which orders the equations, keeps its random state in
// globals; two orderings at once drew from one sequence).
TEST(FitNet, TheSameBitsWhenFitsRunAtOnce) {
    const subdiv::Scheme scheme = schemeNamed("dlg4");
    std::vector<Vec3> samples;
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> ux(300000, 300390), uy(5916000, 5916390);
    for (int i = 0; i < 900; ++i) {
        const double x = ux(rng), y = uy(rng);
        samples.push_back({x, y, 30 * std::sin((x - 300000) / 60) * std::cos((y - 5916000) / 80)});
    }
    const auto fitted = [&] {
        geo::ControlNet net = netOf(40, 40, [](int, int) { return 0.0; });
        Diagnostics diags;
        const auto report = fitNet(scheme, 1, samples, scene::NetSpec{}, net, diags);
        EXPECT_TRUE(report && report->traceMethod != "exact");
        std::vector<double> z;
        for (const Vec3& p : net.grid.points) z.push_back(p.z);
        return z;
    };
    const std::vector<double> alone = fitted();
    for (int run = 0; run < 3; ++run) {
        std::vector<double> first, second;
        std::thread a([&] { first = fitted(); }), b([&] { second = fitted(); });
        a.join(), b.join();
        ASSERT_EQ(first.size(), alone.size());
        for (size_t i = 0; i < alone.size(); ++i) {
            ASSERT_EQ(first[i], alone[i]) << "node " << i << ", run " << run;
            ASSERT_EQ(second[i], alone[i]) << "node " << i << ", run " << run;
        }
    }
}

TEST(FitNet, NoSampleOnTheNetAndSingularEquationsAreErrors) {
    const subdiv::Scheme scheme = schemeNamed("dlg4");
    geo::ControlNet net = netOf(6, 6, [](int, int) { return 0.0; });
    scene::NetSpec spec;
    Diagnostics off;
    EXPECT_FALSE(fitNet(scheme, 1, {{0, 0, 5}}, spec, net, off));
    EXPECT_NE(off.all().front().message.find("no sample lies on the net"), std::string::npos);
    spec.smoothing = 0;  // one sample, no smoothing: 35 free nodes
    Diagnostics singular;
    EXPECT_FALSE(fitNet(scheme, 1, {{300021, 5916021, 5}}, spec, net, singular));
    ASSERT_EQ(singular.errorCount(), 1);
    EXPECT_NE(singular.all().back().message.find("singular"), std::string::npos) << singular.all().back().message;
    EXPECT_EQ(singular.warningCount(), 1);  // 1 sample for 36 nodes
    EXPECT_NE(singular.all().front().message.find("1 samples for a net of 36 nodes"), std::string::npos);
}

// net.fit = true: after the prefilter, the refined surface at the net's nodes
// is the net's values, for the approximating schemes.
TEST(Prefilter, TheSurfacePassesThroughTheNetsValues) {
    for (const auto& scheme : {schemeNamed("ternary-bspline"), schemeNamed("", "quintic-bspline"),
                               schemeNamed("", "gentle-mountains"), schemeNamed("", "ternary-bspline-3")}) {
        const auto f = [](int r, int c) { return 120 + 30 * std::exp(-((r - 6) * (r - 6) + (c - 7) * (c - 7)) / 6.0); };
        geo::ControlNet net = netOf(13, 15, f);
        const int depth = 3;
        scene::NetSpec spec;
        spec.fit = true;
        Diagnostics diags;
        const auto report = prefilterNet(scheme, depth, spec, net, diags);
        ASSERT_TRUE(report) << scheme.name << ": " << (diags.all().empty() ? "" : diags.all().front().message);
        EXPECT_GT(report->largestChangeM, 0.1) << scheme.name;  // the peak raised
        const Grid refined = subdiv::refineGrid(scheme, net.grid, depth);
        const long long stride = std::llround(std::pow(scheme.arity, depth));
        double worst = 0;
        for (int r = 0; r < 13; ++r)
            for (int c = 0; c < 15; ++c)
                worst = std::max(worst, std::abs(refined.at(int(r * stride), int(c * stride)).z - f(r, c)));
        EXPECT_LT(worst, 1e-6) << scheme.name;
    }
}

TEST(Prefilter, AnInterpolatingSchemeIsLeftAsItIsAndATooFlatFilterRefused) {
    geo::ControlNet net = netOf(8, 8, [](int r, int c) { return r * 3.0 + c; });
    scene::NetSpec spec;
    spec.fit = true;
    Diagnostics interpolating;
    ASSERT_TRUE(prefilterNet(schemeNamed("dlg4"), 2, spec, net, interpolating));
    EXPECT_EQ(interpolating.warningCount(), 1);
    EXPECT_EQ(net.grid.at(3, 4).z, 13.0);
    // eta = 1/9: the end of its C2 range, whose limit filter is zero at the net's own frequency; at
    // depth 6 the surface is close enough to its limit for undoing it to be refused.
    Diagnostics flat;
    EXPECT_FALSE(prefilterNet(schemeNamed("ternary-bspline", "", {{"eta", 1.0 / 9}}), 6, spec, net, flat));
    EXPECT_NE(flat.all().front().message.find("cannot be made to pass through the net"), std::string::npos)
        << flat.all().front().message;
}

// A cone of slope k on spacing h, its apex at a node: the cubic B-spline's
// surface keeps sum phi(i) phi(j) of its neighbours, (4 + sqrt 2) / 9 k h
// below the apex (phi = 1/6, 2/3, 1/6); an interpolating scheme keeps the apex.
TEST(PeakLoss, OnAConeTheCubicBsplineLosesWhatItsWeightsSay) {
    const double k = 2, h = 10, top = 300;
    const auto cone = [&](int r, int c) { return top - k * h * std::hypot(r - 8.0, c - 8.0); };
    for (const auto& [scheme, depth, expected] :
         {std::tuple{schemeNamed("ternary-bspline"), 4, (4 + std::sqrt(2.0)) / 9 * k * h},
          std::tuple{schemeNamed("dlg4"), 4, 0.0}}) {
        const geo::ControlNet net = netOf(17, 17, cone);
        const Vec3 peak = measure::highestNode(net);
        EXPECT_DOUBLE_EQ(peak.z, top);
        geo::GeoGrid refined = net.refined(subdiv::refineGrid(scheme, net.grid, depth), std::pow(scheme.arity, depth));
        const measure::PeakLoss loss = measure::peakLoss(peak, refined, h);
        EXPECT_NEAR(loss.lossM, expected, 1e-3 * k * h) << scheme.name;
    }
}

}  // namespace
}  // namespace relief::fit
