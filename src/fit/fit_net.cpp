#include "fit/fit_net.h"

#include <array>
#include <limits>
#include <mutex>
#include <new>
#include <stdexcept>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <exception>
#include <functional>

#include <fmt/format.h>
#include <nanoflann.hpp>

#include "core/stopwatch.h"
#include "fit/basis.h"
#include "fit/normal_equations.h"
#include "fit/penalty_search.h"
#include "fit/sparse_cholesky.h"

namespace relief::fit {

namespace {

using Sparse = Eigen::SparseMatrix<double>;

constexpr int kExactTraceNodes = 400;  // up to this many nodes the trace is exact
constexpr int kRefinementSteps = 3;
constexpr int kWorkers = 2;            // penalties tried at once, each with its own factorization

// A symmetric matrix stored as its lower triangle, times a vector.
Eigen::VectorXd timesSymmetric(const Sparse& lower, const Eigen::VectorXd& v) {
    Eigen::VectorXd out = lower.selfadjointView<Eigen::Lower>() * v;
    return out;
}

// The system (A'A + lambda P) z = A's for one penalty: solved, its GCV score.
struct Solved {
    Penalty penalty;
    int cholmodStatus = 0;  ///< CHOLMOD's, when it failed otherwise than on a matrix not positive definite
    Eigen::VectorXd z;
    bool ok = false;
    int steps = 0;
    double relativeResidual = 0, traceH = 0, score = std::numeric_limits<double>::infinity();
};

// ||s - Az||^2, for the net's heights z, from the samples themselves: from A'A
// and A's it would be a difference of sums as large as s's, and lose the
// residuals of a close fit to cancellation.
using SquaredResiduals = std::function<double(const Eigen::VectorXd& z)>;

class FitSystem {
public:
    /// `spacing`: the samples' mean spacing, metres, the tension's unit.
    FitSystem(const NormalEquations& eq, double spacing, SquaredResiduals squaredResiduals)
        : eq_(eq), squaredResiduals_(std::move(squaredResiduals)), membranePerTension_(1 / (spacing * spacing)) {
        eq.toSparse(m_, thinPlate_, membrane_);
        traceM_ = m_.diagonal().sum(), traceThinPlate_ = thinPlate_.diagonal().sum();
        traceMembrane_ = membrane_.diagonal().sum();
        if (m_.cols() > kExactTraceNodes && eq.probes() > 0) probeSums_ = eq.probeSums();
        analyse();
    }

    /// Solved by the factorization of `worker` (0 .. kWorkers - 1), which one
    /// thread at a time may use: the same bits whichever.
    Solved solve(Penalty penalty, bool withTrace, int worker) {
        SparseCholesky& cholesky = choleskies_[static_cast<size_t>(worker)];
        Solved s;
        s.penalty = penalty;
        // Out of memory, or too large for CHOLMOD's indices: failures of their own, not of the equations.
        const auto failed = [&](int status) {
            s.cholmodStatus = std::min(status, -1);
            s.z.resize(0);
            return s;
        };
        if (analysisStatus_ != 0) return failed(analysisStatus_);
        // P = thin plate + (tension / spacing)^2 membrane; lambda = smoothing tr(A'A) / tr(P). One
        // expression, no P held beside the system.
        const double membraneWeight = penalty.tension * penalty.tension * membranePerTension_;
        const double tracePenalty = traceThinPlate_ + membraneWeight * traceMembrane_;
        const double lambda = penalty.smoothing * (tracePenalty > 0 ? traceM_ / tracePenalty : 1);
        const Sparse c = membraneWeight == 0 ? Sparse(m_ + lambda * thinPlate_)
                                             : Sparse(m_ + lambda * thinPlate_ + (lambda * membraneWeight) * membrane_);
        const SparseCholesky::Factorized factorized = cholesky.factorize(c);
        if (factorized == SparseCholesky::Factorized::notPositiveDefinite) return s;
        if (factorized == SparseCholesky::Factorized::failed) return failed(cholesky.status());
        const Eigen::VectorXd& b = eq_.rhs();
        s.z = cholesky.solve(b);
        if (s.z.size() == 0) return failed(cholesky.status());
        // Iterative refinement: the residual of the equations, solved again, until it is at rounding's level.
        for (; s.steps < kRefinementSteps; ++s.steps) {
            const Eigen::VectorXd r = b - timesSymmetric(c, s.z);
            s.relativeResidual = r.norm() / std::max(b.norm(), 1e-300);
            if (s.relativeResidual <= kFitTolerance * 1e-3) break;
            const Eigen::VectorXd dz = cholesky.solve(r);
            if (dz.size() == 0) return failed(cholesky.status());
            s.z += dz;
        }
        const Eigen::VectorXd r = b - timesSymmetric(c, s.z);
        s.relativeResidual = r.norm() / std::max(b.norm(), 1e-300);
        s.ok = s.relativeResidual <= kFitTolerance;
        if (withTrace && s.ok) score(cholesky, s);
        return s;
    }

    std::string traceMethod() const {
        return m_.cols() <= kExactTraceNodes ? "exact" : fmt::format("Hutchinson's estimate, {} fixed probes", kProbes);
    }

private:
    // The ordering, once (A'A and both energies share one pattern), copied to the other workers. METIS,
    // which orders the net, keeps its random state in globals: two orderings at once in a process
    // would draw from one sequence and differ from run to run.
    void analyse() {
        static std::mutex ordering;
        const std::lock_guard<std::mutex> lock(ordering);
        for (SparseCholesky& cholesky : choleskies_) {
            const bool first = &cholesky == &choleskies_[0];
            if (first ? cholesky.analyse(m_) : cholesky.analyseAs(choleskies_[0])) continue;
            analysisStatus_ = std::min(cholesky.status(), -1);
            return;
        }
    }

    // GCV: N ||s - Az||^2 / (N - tr H)^2, H = A (A'A + lambda P)^-1 A' the influence matrix. Its
    // trace is estimated from probes u over the samples (u'Hu = (A'u)' (A'A + lambda P)^-1 A'u), not
    // over the nodes: with u'u = N, N - u'Hu = u'(I - H)u, whose error vanishes with I - H as the
    // fit closes on the samples, where an estimate over the nodes keeps its error and N - tr H, the
    // score's denominator, is lost in it (a close fit then scored near zero and won).
    void score(SparseCholesky& cholesky, Solved& s) const {
        const double n = static_cast<double>(eq_.samples());
        const double rss = squaredResiduals_(s.z);
        double trace = 0;
        if (m_.cols() <= kExactTraceNodes) {
            Eigen::VectorXd e = Eigen::VectorXd::Zero(m_.cols());
            for (Eigen::Index i = 0; i < m_.cols(); ++i) {
                e[i] = 1;
                const Eigen::VectorXd column = cholesky.solve(timesSymmetric(m_, e));
                if (column.size() == 0) return;  // no score: this penalty is not chosen
                trace += column[i];
                e[i] = 0;
            }
        } else {
            if (probeSums_.cols() != kProbes) throw std::logic_error("fit: the trace is estimated, but no probes were summed");
            trace = cholesky.sumOfInverseForms(probeSums_) / static_cast<double>(probeSums_.cols());
            if (std::isnan(trace)) return;
        }
        s.traceH = trace;
        s.score = n * rss / std::pow(std::max(n - trace, 1e-9), 2);
    }

    const NormalEquations& eq_;
    SquaredResiduals squaredResiduals_;
    double membranePerTension_;
    Sparse m_, thinPlate_, membrane_;
    double traceM_ = 0, traceThinPlate_ = 0, traceMembrane_ = 0;
    std::array<SparseCholesky, kWorkers> choleskies_;
    int analysisStatus_ = 0;  ///< CHOLMOD's, when the analysis failed
    Eigen::MatrixXd probeSums_;  ///< A'U, U Hutchinson's probes over the samples; empty: the exact trace
};

// The penalty of the least GCV score, as searchPenalty tries them (on rough
// terrain a tension wins, where between samples the thin plate alone
// overshoots: held-out topobathy, mostly 1/2 to 8; the smooth volcano, none to
// 1). A round's two trials run at once, one on each worker; the points tried
// do not depend on how many cores there are, so neither does the choice.
// Every trial is recorded in `trials`; the chosen one's solution is returned
// (none when no trial gave one). `told` (may be empty) hears each round's end:
// a large net's trials take seconds each.
Solved choosePenalty(FitSystem& system, std::optional<double> givenTension, std::vector<GcvTrial>& trials,
                     const std::function<void(const std::string&)>& told) {
    std::vector<Solved> solved;  // every trial's, in the order tried: a few net-sized vectors
    const ScoreRound scoreRound = [&](const std::vector<Penalty>& round) {
        const size_t first = solved.size();
        solved.resize(first + round.size());
        std::vector<std::exception_ptr> thrown(round.size());  // an exception may not leave a parallel region
#pragma omp parallel for num_threads(kWorkers) schedule(static, 1)
        for (int i = 0; i < static_cast<int>(round.size()); ++i) {
            Solved& trial = solved[first + static_cast<size_t>(i)];
            try {
                trial = system.solve(round[static_cast<size_t>(i)], true, i % kWorkers);
            } catch (const std::bad_alloc&) {
                trial = Solved{};
                trial.cholmodStatus = SparseCholesky::kOutOfMemory;
            } catch (...) {
                thrown[static_cast<size_t>(i)] = std::current_exception();
            }
        }
        for (const std::exception_ptr& e : thrown)
            if (e) std::rethrow_exception(e);
        std::vector<double> scores;
        for (size_t i = first; i < solved.size(); ++i) {
            trials.push_back({round[i - first].smoothing, round[i - first].tension, solved[i].score, solved[i].traceH});
            scores.push_back(solved[i].score);
        }
        const auto best = std::min_element(solved.begin(), solved.end(),
                                           [](const Solved& a, const Solved& b) { return a.score < b.score; });
        if (told && best->z.size() != 0)
            told(fmt::format("cross-validation: {} penalties tried, the best so far smoothing {:.3g}, tension {:.3g}",
                             trials.size(), best->penalty.smoothing, best->penalty.tension));
        return scores;
    };
    const PenaltySearch search = searchPenalty(scoreRound, givenTension);
    return search.best ? std::move(solved[*search.best]) : Solved{};
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

// The samples' residuals from the surface of the net heights z (row-major).
struct Residuals {
    double squares = 0, largest = 0;
    Vec3 worst;
};

Residuals residualsOf(const AxisBasis& bx, const AxisBasis& by, const geo::GeoGrid& net,
                      const std::vector<Vec3>& samples, const Eigen::VectorXd& z) {
    Residuals out;
    SurfaceRow row;
    for (const Vec3& s : samples) {
        if (!surfaceRow(bx, by, net, s.x, s.y, row)) continue;
        double at = 0;
        for (const auto& [r, wy] : row.y) {
            double along = 0;
            for (const auto& [c, wx] : row.x) along += wx * z[static_cast<Eigen::Index>(r) * net.cols() + c];
            at += wy * along;
        }
        const double e = std::abs(at - s.z);
        out.squares += e * e;
        if (e > out.largest) out.largest = e, out.worst = s;
    }
    return out;
}

}  // namespace

std::optional<FitReport> fitNet(const subdiv::Scheme& scheme, int depth, const std::vector<Vec3>& samples,
                                const scene::NetSpec& spec, geo::ControlNet& net, Diagnostics& diags,
                                const std::function<void(const std::string&)>& progress) {
    const auto t0 = Clock::now();
    FitReport report;
    report.depth = depth;
    report.nodes = net.grid.points.size();
    const SourceLoc at = spec.locs.at("net.gridding");
    const AxisBasis bx = axisBasis(scheme, net.cols(), depth), by = axisBasis(scheme, net.rows(), depth);
    const bool probed = !spec.smoothing && report.nodes > static_cast<size_t>(kExactTraceNodes);
    NormalEquations eq(net.rows(), net.cols(), std::max(bx.span, by.span) - 1, probed ? kProbes : 0);
    SurfaceRow row;
    for (const Vec3& s : samples) {
        if (surfaceRow(bx, by, net, s.x, s.y, row)) eq.addSample(row, s);
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
    eq.addMembrane(net.dx, net.dy);
    // The tension's unit: the samples' mean spacing, sqrt(the net's area / samples).
    const double spacing = std::sqrt(net.dx * (net.cols() - 1) * net.dy * (net.rows() - 1) /
                                     static_cast<double>(report.samples));
    FitSystem system(eq, spacing, [&](const Eigen::VectorXd& z) { return residualsOf(bx, by, net, samples, z).squares; });
    report.traceMethod = system.traceMethod();
    Solved solved;
    if (spec.smoothing) {
        if (progress) progress(fmt::format("fitting {} samples (smoothing {:.3g})", report.samples, *spec.smoothing));
        solved = system.solve({*spec.smoothing, spec.tension.value_or(0)}, false, 0);
        report.chosenBy = "net.smoothing";
    } else {
        if (progress) progress(fmt::format("fitting {} samples: choosing the penalty by cross-validation", report.samples));
        solved = choosePenalty(system, spec.tension, report.gcv, progress);
        // No smoothing gave a solution: the largest tried (the search's first round always tries two),
        // the best conditioned, fails again below saying why.
        if (solved.z.size() == 0) {
            const auto largest = std::max_element(report.gcv.begin(), report.gcv.end(),
                                                  [](const GcvTrial& a, const GcvTrial& b) { return a.smoothing < b.smoothing; });
            solved = system.solve({largest->smoothing, largest->tension}, false, 0);
        }
        report.chosenBy = "generalized cross-validation";
    }
    report.smoothing = solved.penalty.smoothing;
    report.tension = solved.penalty.tension;
    report.tensionChosenBy = spec.tension ? "net.tension" : spec.smoothing ? "none: net.smoothing given" : report.chosenBy;
    const SourceLoc key = spec.smoothing ? spec.locs.at("net.smoothing") : at;
    if (solved.cholmodStatus != 0) {
        diags.error(key, fmt::format("net.gridding = \"fit\": the sparse Cholesky (CHOLMOD) failed: {}; a coarser "
                                     "net (net.spacing_m) needs less",
                                     SparseCholesky::describe(solved.cholmodStatus)));
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
    const Residuals residuals = residualsOf(bx, by, net, samples, solved.z);
    report.rmseM = std::sqrt(residuals.squares / static_cast<double>(report.samples));
    report.maxResidualM = residuals.largest;
    report.worstSample = residuals.worst;
    report.dataReachM = dataReach(samples, net);
    report.seconds = secondsSince(t0);
    return report;
}

}  // namespace relief::fit
