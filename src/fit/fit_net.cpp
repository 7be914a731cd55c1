#include "fit/fit_net.h"

#include <Eigen/SparseCholesky>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>

#include <fmt/format.h>
#include <nanoflann.hpp>

#include "fit/basis.h"
#include "fit/normal_equations.h"

namespace relief::fit {

namespace {

using Sparse = Eigen::SparseMatrix<double>;
using Cholesky = Eigen::SimplicialLLT<Sparse, Eigen::Lower, Eigen::AMDOrdering<int>>;

constexpr int kProbes = 64;            // Hutchinson's probes of the influence matrix's trace
constexpr int kExactTraceNodes = 400;  // up to this many nodes the trace is exact
constexpr int kRefinementSteps = 3;

// A symmetric matrix stored as its lower triangle, times a vector.
Eigen::VectorXd timesSymmetric(const Sparse& lower, const Eigen::VectorXd& v) {
    Eigen::VectorXd out = lower.selfadjointView<Eigen::Lower>() * v;
    return out;
}

// The fixed probes: +-1 from splitmix64 with a fixed seed (the same on every
// standard library), one set for every smoothing tried, so that the score is
// a smooth function of it and the same on every run.
Eigen::MatrixXd probes(Eigen::Index n) {
    std::uint64_t state = 0x5EED5EEDu;
    auto next = [&] {
        std::uint64_t z = (state += 0x9E3779B97F4A7C15ull);
        z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
        z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
        return z ^ (z >> 31);
    };
    Eigen::MatrixXd out(n, kProbes);
    for (Eigen::Index k = 0; k < kProbes; ++k)
        for (Eigen::Index i = 0; i < n; ++i) out(i, k) = (next() >> 63) ? 1.0 : -1.0;
    return out;
}

// The system (A'A + lambda P) z = A's for one smoothing: solved, its GCV score.
struct Solved {
    Eigen::VectorXd z;
    bool ok = false;
    int steps = 0;
    double relativeResidual = 0, traceH = 0, score = 0;
};

class FitSystem {
public:
    FitSystem(const NormalEquations& eq) : eq_(eq) {
        eq.toSparse(m_, p_);
        double tm = 0, tp = 0;
        for (Eigen::Index i = 0; i < m_.cols(); ++i) tm += m_.coeff(i, i), tp += p_.coeff(i, i);
        scale_ = tp > 0 ? tm / tp : 1;
        cholesky_.analyzePattern(m_ + p_);
        if (m_.cols() > kExactTraceNodes) {
            probes_ = probes(m_.cols());
            mProbes_ = m_.selfadjointView<Eigen::Lower>() * probes_;  // A'A v, the same for every smoothing
        }
    }

    Solved solve(double smoothing, bool withTrace) {
        Solved s;
        const Sparse c = m_ + (smoothing * scale_) * p_;
        cholesky_.factorize(c);
        if (cholesky_.info() != Eigen::Success) return s;
        const Eigen::VectorXd& b = eq_.rhs();
        s.z = cholesky_.solve(b);
        // Iterative refinement: the residual of the equations, solved again, until it is at rounding's level.
        for (; s.steps < kRefinementSteps; ++s.steps) {
            const Eigen::VectorXd r = b - timesSymmetric(c, s.z);
            s.relativeResidual = r.norm() / std::max(b.norm(), 1e-300);
            if (s.relativeResidual <= kFitTolerance * 1e-3) break;
            s.z += cholesky_.solve(r);
        }
        const Eigen::VectorXd r = b - timesSymmetric(c, s.z);
        s.relativeResidual = r.norm() / std::max(b.norm(), 1e-300);
        s.ok = s.relativeResidual <= kFitTolerance;
        if (withTrace) score(s);
        return s;
    }

    std::string traceMethod() const {
        return probes_.size() == 0 ? "exact" : fmt::format("Hutchinson's estimate, {} fixed probes", kProbes);
    }

private:
    // GCV: N ||s - Az||^2 / (N - tr H)^2, with ||s - Az||^2 = s's - 2 z'A's + z'A'Az
    // and tr H = tr((A'A + lambda P)^-1 A'A).
    void score(Solved& s) {
        const double n = static_cast<double>(eq_.samples());
        const double rss = std::max(0.0, eq_.samplesSquared() - 2 * s.z.dot(eq_.rhs()) + s.z.dot(timesSymmetric(m_, s.z)));
        double trace = 0;
        if (probes_.size() == 0) {
            Eigen::VectorXd e = Eigen::VectorXd::Zero(m_.cols());
            for (Eigen::Index i = 0; i < m_.cols(); ++i) {
                e[i] = 1;
                trace += cholesky_.solve(timesSymmetric(m_, e))[i];
                e[i] = 0;
            }
        } else {
            // The probes in blocks, one solve of many right-hand sides each, the blocks on all
            // cores: each column's solution is the same whichever thread made it.
            constexpr int kBlock = 8;
            static_assert(kProbes % kBlock == 0);
            Eigen::MatrixXd solved(mProbes_.rows(), kProbes);
#pragma omp parallel for schedule(static)
            for (int block = 0; block < kProbes / kBlock; ++block)
                solved.middleCols(block * kBlock, kBlock) = cholesky_.solve(mProbes_.middleCols(block * kBlock, kBlock));
            trace = probes_.cwiseProduct(solved).sum() / kProbes;
        }
        s.traceH = trace;
        s.score = n * rss / std::pow(std::max(n - trace, 1e-9), 2);
    }

    const NormalEquations& eq_;
    Sparse m_, p_;
    double scale_ = 1;
    Cholesky cholesky_;
    Eigen::MatrixXd probes_, mProbes_;  ///< Hutchinson's probes v, and A'A v; empty: the exact trace
};

// The smoothing of the least GCV score, log-spaced over [1e-6, 1e2] (below,
// the equations' condition makes the score itself uncertain): a coarse sweep,
// then golden sections around its best. Every trial is recorded.
double chooseSmoothing(FitSystem& system, std::vector<GcvTrial>& trials) {
    auto trial = [&](double log10s) {
        const double s = std::pow(10.0, log10s);
        const Solved solved = system.solve(s, true);
        const double score = solved.ok ? solved.score : std::numeric_limits<double>::infinity();
        trials.push_back({s, score, solved.traceH});
        return score;
    };
    double best = -6, bestScore = std::numeric_limits<double>::infinity();
    for (double l : {-6.0, -4.0, -2.0, 0.0, 2.0}) {
        const double v = trial(l);
        if (v < bestScore) best = l, bestScore = v;
    }
    double lo = std::max(-6.0, best - 2), hi = std::min(2.0, best + 2);
    const double g = (std::sqrt(5.0) - 1) / 2;
    double a = hi - g * (hi - lo), b = lo + g * (hi - lo);
    double fa = trial(a), fb = trial(b);
    for (int i = 0; i < 3; ++i) {
        if (fa < fb) hi = b, b = a, fb = fa, a = hi - g * (hi - lo), fa = trial(a);
        else lo = a, a = b, fa = fb, b = lo + g * (hi - lo), fb = trial(b);
    }
    for (const auto& t : trials)
        if (t.score < bestScore) bestScore = t.score, best = std::log10(t.smoothing);
    return std::pow(10.0, best);
}

// The farthest any node is from its nearest sample, metres (a k-d tree of the samples).
struct SampleCloud {
    const std::vector<Vec3>& pts;
    size_t kdtree_get_point_count() const { return pts.size(); }
    double kdtree_get_pt(size_t i, size_t d) const { return d == 0 ? pts[i].x : pts[i].y; }
    template <class Box>
    bool kdtree_get_bbox(Box&) const { return false; }
};

double dataReach(const std::vector<Vec3>& samples, const geo::GeoGrid& net) {
    SampleCloud cloud{samples};
    using Tree = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<double, SampleCloud>, SampleCloud, 2, size_t>;
    Tree tree(2, cloud, nanoflann::KDTreeSingleIndexAdaptorParams(10));
    tree.buildIndex();
    double reach = 0;
    for (const Vec3& p : net.grid.points) {
        size_t index = 0;
        double d2 = 0;
        const double q[2] = {p.x, p.y};
        tree.knnSearch(q, 1, &index, &d2);
        reach = std::max(reach, std::sqrt(d2));
    }
    return reach;
}

}  // namespace

std::optional<FitReport> fitNet(const subdiv::Scheme& scheme, int depth, const std::vector<Vec3>& samples,
                                const scene::NetSpec& spec, geo::ControlNet& net, Diagnostics& diags,
                                const std::function<void(const std::string&)>& progress) {
    const auto t0 = std::chrono::steady_clock::now();
    FitReport report;
    report.depth = depth;
    report.nodes = net.grid.points.size();
    const SourceLoc at = spec.locs.at("net.gridding");
    const AxisBasis bx = axisBasis(scheme, net.cols(), depth), by = axisBasis(scheme, net.rows(), depth);
    NormalEquations eq(net.rows(), net.cols(), std::max(bx.span, by.span) - 1);
    SurfaceRow row;
    for (const Vec3& s : samples) {
        if (surfaceRow(bx, by, net, s.x, s.y, row)) eq.addSample(row, s.z);
        else ++report.samplesOutside;
    }
    report.samples = eq.samples();
    if (report.samples == 0) {
        diags.error(at, "net.gridding = \"fit\": no sample lies on the net");
        return std::nullopt;
    }
    if (report.samples * 4 < report.nodes)
        diags.warning(at, fmt::format("net.gridding = \"fit\": {} samples for a net of {} nodes (fewer than a "
                                      "quarter): most nodes are set by the smoothness alone; a coarser net "
                                      "(net.spacing_m) follows the data more closely",
                                      report.samples, report.nodes));
    eq.addThinPlate(net.dx, net.dy);
    FitSystem system(eq);
    report.traceMethod = system.traceMethod();
    if (spec.smoothing) {
        report.smoothing = *spec.smoothing;
        report.chosenBy = "net.smoothing";
    } else {
        if (progress) progress(fmt::format("fitting {} samples: choosing the smoothing by cross-validation", report.samples));
        report.smoothing = chooseSmoothing(system, report.gcv);
        report.chosenBy = "generalized cross-validation";
    }
    if (progress) progress(fmt::format("fitting {} samples (smoothing {:.3g})", report.samples, report.smoothing));
    const Solved solved = system.solve(report.smoothing, false);
    const SourceLoc key = spec.smoothing ? spec.locs.at("net.smoothing") : at;
    if (solved.z.size() == 0) {
        diags.error(key, fmt::format("net.gridding = \"fit\": the equations are singular at smoothing {:.3g}: "
                                     "nodes no sample reaches are free without smoothing; give net.smoothing > 0, "
                                     "or a coarser net",
                                     report.smoothing));
        return std::nullopt;
    }
    if (!solved.ok) {
        diags.error(key, fmt::format("net.gridding = \"fit\": the solution did not converge: after {} steps of "
                                     "refinement the equations' relative residual is {:.3g} (at most {:.0e} is "
                                     "accepted); raise net.smoothing",
                                     solved.steps, solved.relativeResidual, kFitTolerance));
        return std::nullopt;
    }
    report.refinementSteps = solved.steps;
    report.relativeResidual = solved.relativeResidual;
    for (size_t i = 0; i < net.grid.points.size(); ++i) net.grid.points[i].z = solved.z[static_cast<Eigen::Index>(i)];
    const double maxDiagonal = [&] {
        double m = 0;
        for (int i = 0; i < static_cast<int>(report.nodes); ++i) m = std::max(m, eq.diagonal(i));
        return m;
    }();
    for (int i = 0; i < static_cast<int>(report.nodes); ++i) report.nodesConstrained += eq.diagonal(i) > 1e-12 * maxDiagonal;
    double squares = 0;
    for (const Vec3& s : samples) {
        if (!surfaceRow(bx, by, net, s.x, s.y, row)) continue;
        double z = 0;
        for (const auto& [r, wy] : row.y)
            for (const auto& [c, wx] : row.x) z += wy * wx * net.grid.at(r, c).z;
        const double e = std::abs(z - s.z);
        squares += e * e;
        if (e > report.maxResidualM) report.maxResidualM = e, report.worstSample = s;
    }
    report.rmseM = std::sqrt(squares / static_cast<double>(report.samples));
    report.dataReachM = dataReach(samples, net);
    report.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return report;
}

}  // namespace relief::fit
