#include "fit/fit_net.h"

#include <Eigen/CholmodSupport>

#include <array>
#include <limits>
#include <mutex>
#include <new>

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
// CHOLMOD's simplicial LL' (its own loops, no BLAS: the same bits whatever BLAS a machine has) in
// nested-dissection order, which fills a net's 2-D stencil by a third less than minimum degree.
using Cholesky = Eigen::CholmodSimplicialLLT<Sparse, Eigen::Lower>;

constexpr int kProbes = 64;            // Hutchinson's probes of the influence matrix's trace
constexpr int kExactTraceNodes = 400;  // up to this many nodes the trace is exact
constexpr int kRefinementSteps = 3;
constexpr int kWorkers = 2;            // smoothings tried at once, each with its own factorization

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
    double smoothing = 0;
    int cholmodStatus = 0;  ///< CHOLMOD's, when it failed otherwise than on a matrix not positive definite
    Eigen::VectorXd z;
    bool ok = false;
    int steps = 0;
    double relativeResidual = 0, traceH = 0, score = std::numeric_limits<double>::infinity();
};

class FitSystem {
public:
    explicit FitSystem(const NormalEquations& eq) : eq_(eq) {
        eq.toSparse(m_, p_);
        double tm = 0, tp = 0;
        for (Eigen::Index i = 0; i < m_.cols(); ++i) tm += m_.coeff(i, i), tp += p_.coeff(i, i);
        scale_ = tp > 0 ? tm / tp : 1;
        for (Cholesky& cholesky : choleskies_) cholesky.cholmod().print = 0;  // its warnings went to stdout
    }

    /// Before solving with the trace: the probes, shared by every smoothing.
    void prepareTrace() {
        if (m_.cols() <= kExactTraceNodes || probes_.size() != 0) return;
        probes_ = probes(m_.cols());
        mProbes_ = m_.selfadjointView<Eigen::Lower>() * probes_;  // A'A v, the same for every smoothing
    }

    /// Solved by the factorization of `worker` (0 .. kWorkers - 1), which one
    /// thread at a time may use: the same bits whichever.
    Solved solve(double smoothing, bool withTrace, int worker) {
        Cholesky& cholesky = choleskies_[static_cast<size_t>(worker)];
        Solved s;
        s.smoothing = smoothing;
        // Out of memory, or too large for CHOLMOD's indices: failures of their own, not of the equations.
        const auto failed = [&] {
            if (cholesky.cholmod().status >= CHOLMOD_OK && cholesky.info() == Eigen::Success) return false;
            s.cholmodStatus = std::min(cholesky.cholmod().status, -1);
            s.z.resize(0);
            return true;
        };
        if (!analysed(worker)) {
            failed();
            return s;
        }
        const Sparse c = m_ + (smoothing * scale_) * p_;
        cholesky.factorize(c);
        if (cholesky.info() != Eigen::Success && cholesky.cholmod().status >= CHOLMOD_OK) return s;  // not positive definite
        if (failed()) return s;
        const Eigen::VectorXd& b = eq_.rhs();
        s.z = cholesky.solve(b);
        if (failed()) return s;
        // Iterative refinement: the residual of the equations, solved again, until it is at rounding's level.
        for (; s.steps < kRefinementSteps; ++s.steps) {
            const Eigen::VectorXd r = b - timesSymmetric(c, s.z);
            s.relativeResidual = r.norm() / std::max(b.norm(), 1e-300);
            if (s.relativeResidual <= kFitTolerance * 1e-3) break;
            const Eigen::VectorXd dz = cholesky.solve(r);
            if (failed()) return s;
            s.z += dz;
        }
        const Eigen::VectorXd r = b - timesSymmetric(c, s.z);
        s.relativeResidual = r.norm() / std::max(b.norm(), 1e-300);
        s.ok = s.relativeResidual <= kFitTolerance;
        if (withTrace && s.ok) score(cholesky, s);  // prepareTrace() first
        return s;
    }

    std::string traceMethod() const {
        return m_.cols() <= kExactTraceNodes ? "exact" : fmt::format("Hutchinson's estimate, {} fixed probes", kProbes);
    }

private:
    // The ordering, once a worker (m_ and p_ share their pattern). METIS, which orders the net,
    // keeps its random state in globals: two orderings at once in a process would draw from one
    // sequence and differ from run to run.
    bool analysed(int worker) {
        const auto w = static_cast<size_t>(worker);
        if (analysed_[w]) return true;
        static std::mutex ordering;
        const std::lock_guard<std::mutex> lock(ordering);
        cholmod_common& common = choleskies_[w].cholmod();
        common.nmethods = 1;
        common.method[0].ordering = CHOLMOD_NESDIS;
        common.postorder = 1;
        choleskies_[w].analyzePattern(m_);
        analysed_[w] = common.status >= CHOLMOD_OK;
        return analysed_[w];
    }

    // GCV: N ||s - Az||^2 / (N - tr H)^2, with ||s - Az||^2 = s's - 2 z'A's + z'A'Az
    // and tr H = tr((A'A + lambda P)^-1 A'A).
    void score(Cholesky& cholesky, Solved& s) const {
        const double n = static_cast<double>(eq_.samples());
        const double rss = std::max(0.0, eq_.samplesSquared() - 2 * s.z.dot(eq_.rhs()) + s.z.dot(timesSymmetric(m_, s.z)));
        double trace = 0;
        if (m_.cols() <= kExactTraceNodes) {
            Eigen::VectorXd e = Eigen::VectorXd::Zero(m_.cols());
            for (Eigen::Index i = 0; i < m_.cols(); ++i) {
                e[i] = 1;
                trace += cholesky.solve(timesSymmetric(m_, e))[i];
                e[i] = 0;
            }
        } else {
            const Eigen::MatrixXd solved = cholesky.solve(mProbes_);
            trace = probes_.cwiseProduct(solved).sum() / kProbes;
        }
        if (cholesky.info() != Eigen::Success) return;  // no score: this smoothing is not chosen
        s.traceH = trace;
        s.score = n * rss / std::pow(std::max(n - trace, 1e-9), 2);
    }

    const NormalEquations& eq_;
    Sparse m_, p_;
    double scale_ = 1;
    std::array<Cholesky, kWorkers> choleskies_;
    std::array<bool, kWorkers> analysed_{};
    Eigen::MatrixXd probes_, mProbes_;  ///< Hutchinson's probes v, and A'A v; empty: the exact trace
};

// The smoothing of the least GCV score over log10 smoothing in [-6, 2] (below,
// the equations' condition makes the score itself uncertain): four points a
// third of the range apart, then rounds that try the points half a step
// either side of the best so far, the step halved each round, down to a third
// of a decade (a GCV minimum is that flat). A round's two trials run at once,
// one on each worker; the points tried do not depend on how many cores there
// are, so neither does the choice. Every trial is recorded; the best one's
// solution is kept.
Solved chooseSmoothing(FitSystem& system, std::vector<GcvTrial>& trials) {
    system.prepareTrace();
    Solved best;
    double bestLog = 0;  // of the best trial's smoothing
    auto round = [&](const std::vector<double>& logs) {
        std::vector<Solved> solved(logs.size());
#pragma omp parallel for num_threads(kWorkers) schedule(static, 1)
        for (int i = 0; i < static_cast<int>(logs.size()); ++i) {
            Solved& trial = solved[static_cast<size_t>(i)];
            try {  // an exception may not leave a parallel region
                trial = system.solve(std::pow(10.0, logs[static_cast<size_t>(i)]), true, i % kWorkers);
            } catch (const std::bad_alloc&) {
                trial = Solved{};
                trial.cholmodStatus = CHOLMOD_OUT_OF_MEMORY;
            }
        }
        for (size_t i = 0; i < logs.size(); ++i) {
            trials.push_back({std::pow(10.0, logs[i]), solved[i].score, solved[i].traceH});
            if (solved[i].score < best.score) best = std::move(solved[i]), bestLog = logs[i];
        }
    };
    constexpr double kLow = -6, kHigh = 2, kStep = (kHigh - kLow) / 3;
    round({kLow, kLow + kStep});
    round({kLow + 2 * kStep, kHigh});
    for (double half = kStep / 2; half > 0.3; half /= 2) {
        std::vector<double> logs;
        for (double l : {bestLog - half, bestLog + half})
            if (l >= kLow - 1e-9 && l <= kHigh + 1e-9) logs.push_back(l);
        round(logs);
    }
    return best;
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
    Solved solved;
    if (spec.smoothing) {
        report.smoothing = *spec.smoothing;
        report.chosenBy = "net.smoothing";
        if (progress) progress(fmt::format("fitting {} samples (smoothing {:.3g})", report.samples, report.smoothing));
        solved = system.solve(report.smoothing, false, 0);
    } else {
        if (progress) progress(fmt::format("fitting {} samples: choosing the smoothing by cross-validation", report.samples));
        solved = chooseSmoothing(system, report.gcv);
        // No smoothing gave a solution: the largest tried, the best conditioned, fails below saying why.
        if (solved.z.size() == 0) solved = system.solve(1e2, false, 0);
        report.smoothing = solved.smoothing;
        report.chosenBy = "generalized cross-validation";
    }
    const SourceLoc key = spec.smoothing ? spec.locs.at("net.smoothing") : at;
    if (solved.cholmodStatus != 0) {
        diags.error(key, fmt::format("net.gridding = \"fit\": the sparse Cholesky (CHOLMOD) failed: {}; a coarser "
                                     "net (net.spacing_m) needs less",
                                     solved.cholmodStatus == CHOLMOD_OUT_OF_MEMORY ? std::string("out of memory")
                                     : solved.cholmodStatus == CHOLMOD_TOO_LARGE
                                         ? std::string("the net is too large for its indices")
                                         : fmt::format("status {}", solved.cholmodStatus)));
        return std::nullopt;
    }
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
