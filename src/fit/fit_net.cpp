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
constexpr int kFolds = 5;              // of cross-validation by blocks
// GCV assumes samples that are independent and spread evenly. Where the nodes' mean distance from their
// nearest sample is more than this many times what evenly spread samples leave (half their spacing),
// the samples come in lines, clusters or around holes: GCV, which scores each sample left out against
// its neighbours along a line, chose near-interpolation there (a sample's tiny offsets across its line
// then set the slope across it, which the thin plate carries on across the gap: +-5 km between two
// lines of samples 70-155 m high). Blocks left out whole score what is predicted across the gaps.
constexpr double kClumped = 2;
constexpr double kBlockReaches = 2;    // a block's side, in the nodes' mean distance from their nearest sample
constexpr size_t kSlopeQueries = 20000;  // samples whose neighbours give the data's steepest slope
// The least slope any data justify, 1 mm a metre: samples all of one height would otherwise make a
// surface's rounding (1e-12 m) stray without bound.
constexpr double kLeastJustifiedSlope = 1e-3;

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

// ||s - Az||^2, for the net's heights z, from the samples themselves (those of
// one fold, or all with kAllFolds): from A'A and A's it would be a difference
// of sums as large as s's, and lose the residuals of a close fit to
// cancellation.
constexpr int kAllFolds = -1;
using SquaredResiduals = std::function<double(const Eigen::VectorXd& z, int fold)>;

class FitSystem {
public:
    /// `spacing`: the samples' mean spacing, metres, the tension's unit.
    FitSystem(const NormalEquations& eq, double spacing, SquaredResiduals squaredResiduals)
        : eq_(eq), squaredResiduals_(std::move(squaredResiduals)), membranePerTension_(1 / (spacing * spacing)) {
        eq.toSparse(m_, thinPlate_, membrane_);
        traceM_ = m_.diagonal().sum(), traceThinPlate_ = thinPlate_.diagonal().sum();
        traceMembrane_ = membrane_.diagonal().sum();
        if (m_.cols() > kExactTraceNodes && eq.probes() > 0) probeSums_ = eq.probeSums();
        // Each fold's equations without it, once: every penalty tried solves them all.
        withoutFold_.resize(static_cast<size_t>(eq.folds()));
        for (int fold = 0; fold < eq.folds(); ++fold)
            eq.withoutFold(fold, withoutFold_[static_cast<size_t>(fold)].m, withoutFold_[static_cast<size_t>(fold)].rhs);
        analyse();
    }

    /// Solved by the factorization of `worker` (0 .. kWorkers - 1), which one
    /// thread at a time may use: the same bits whichever. `withTrace`: scored
    /// by GCV.
    Solved solve(Penalty penalty, bool withTrace, int worker) {
        Solved s = solveSystem(m_, eq_.rhs(), penalty, worker);
        if (withTrace && s.ok) score(choleskies_[static_cast<size_t>(worker)], s);
        return s;
    }

    /// Scored by cross-validation by folds: each fold's samples' squared
    /// residuals from the fit of all the others, summed over the folds, over
    /// the samples. No solution kept (the fit of all the samples is another).
    Solved crossValidate(Penalty penalty, int worker) {
        Solved scored;
        scored.penalty = penalty;
        double squares = 0;
        for (int fold = 0; fold < static_cast<int>(withoutFold_.size()); ++fold) {
            const Equations& kept = withoutFold_[static_cast<size_t>(fold)];
            const Solved s = solveSystem(kept.m, kept.rhs, penalty, worker);
            if (s.cholmodStatus != 0) scored.cholmodStatus = s.cholmodStatus;
            if (!s.ok) return scored;  // no score: a fold's equations failed at this penalty
            squares += squaredResiduals_(s.z, fold);
        }
        scored.ok = true;
        scored.score = squares / static_cast<double>(eq_.samples());
        return scored;
    }

    std::string traceMethod() const {
        return m_.cols() <= kExactTraceNodes ? "exact" : fmt::format("Hutchinson's estimate, {} fixed probes", kProbes);
    }

private:
    // (m + lambda P) z = b, m of A'A's pattern: solved, refined, not scored.
    Solved solveSystem(const Sparse& m, const Eigen::VectorXd& b, Penalty penalty, int worker) {
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
        // P = thin plate + (tension / spacing)^2 membrane; lambda = smoothing tr(A'A) / tr(P), A'A of all
        // the samples (a fold's fit is penalized as the whole's). One expression, no P held beside the system.
        const double membraneWeight = penalty.tension * penalty.tension * membranePerTension_;
        const double tracePenalty = traceThinPlate_ + membraneWeight * traceMembrane_;
        const double lambda = penalty.smoothing * (tracePenalty > 0 ? traceM_ / tracePenalty : 1);
        const Sparse c = membraneWeight == 0 ? Sparse(m + lambda * thinPlate_)
                                             : Sparse(m + lambda * thinPlate_ + (lambda * membraneWeight) * membrane_);
        const SparseCholesky::Factorized factorized = cholesky.factorize(c);
        if (factorized == SparseCholesky::Factorized::notPositiveDefinite) return s;
        if (factorized == SparseCholesky::Factorized::failed) return failed(cholesky.status());
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
        return s;
    }

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
        const double rss = squaredResiduals_(s.z, kAllFolds);
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
    struct Equations {
        Sparse m;  ///< lower triangle, m_'s pattern
        Eigen::VectorXd rhs;
    };
    std::vector<Equations> withoutFold_;  ///< A'A and A's of all the samples but each fold's
    double traceM_ = 0, traceThinPlate_ = 0, traceMembrane_ = 0;
    std::array<SparseCholesky, kWorkers> choleskies_;
    int analysisStatus_ = 0;  ///< CHOLMOD's, when the analysis failed
    Eigen::MatrixXd probeSums_;  ///< A'U, U Hutchinson's probes over the samples; empty: the exact trace
};

// How a penalty is scored: by GCV, or by cross-validation by folds of blocks.
enum class Criterion { gcv, folds };

// The penalty of the least score, as searchPenalty tries them (on rough
// terrain a tension wins, where between samples the thin plate alone
// overshoots: held-out topobathy, mostly 1/2 to 8; the smooth volcano, none to
// 1). A round's two trials run at once, one on each worker; the points tried
// do not depend on how many cores there are, so neither does the choice.
// Every trial is recorded in `trials`; the chosen one's solution is returned
// (none when no trial gave one). `told` (may be empty) hears each round's end:
// a large net's trials take seconds each.
// With GCV every trial has its surface, and one that strays from its data
// (strayOf above kStrayLimit, fit_net.h) is not chosen whatever its score:
// the search moves on past it at no extra solve (769,650 samples of Holyrood
// Park: GCV's least score, smoothing 2.2e-6, put the net's corners beyond the
// data 29 times as steep from them as any two samples). Folds' trials keep no
// surface; their choice is checked after (pullInWhileStraying).
Solved choosePenalty(FitSystem& system, Criterion criterion, std::optional<double> givenTension,
                     const std::function<double(const Eigen::VectorXd&)>& strayOf, std::vector<GcvTrial>& trials,
                     const std::function<void(const std::string&)>& told) {
    std::vector<Solved> solved;  // every trial's, in the order tried: a few net-sized vectors
    const auto trial = [&](Penalty p, int worker) {
        return criterion == Criterion::gcv ? system.solve(p, true, worker) : system.crossValidate(p, worker);
    };
    const ScoreRound scoreRound = [&](const std::vector<Penalty>& round) {
        const size_t first = solved.size();
        solved.resize(first + round.size());
        std::vector<std::exception_ptr> thrown(round.size());  // an exception may not leave a parallel region
#pragma omp parallel for num_threads(kWorkers) schedule(static, 1)
        for (int i = 0; i < static_cast<int>(round.size()); ++i) {
            Solved& tried = solved[first + static_cast<size_t>(i)];
            try {
                tried = trial(round[static_cast<size_t>(i)], i % kWorkers);
            } catch (const std::bad_alloc&) {
                tried = Solved{};
                tried.cholmodStatus = SparseCholesky::kOutOfMemory;
            } catch (...) {
                thrown[static_cast<size_t>(i)] = std::current_exception();
            }
        }
        for (const std::exception_ptr& e : thrown)
            if (e) std::rethrow_exception(e);
        std::vector<double> scores;
        for (size_t i = first; i < solved.size(); ++i) {
            const bool strays = solved[i].z.size() != 0 && strayOf(solved[i].z) > kStrayLimit;
            trials.push_back({round[i - first].smoothing, round[i - first].tension, solved[i].score, solved[i].traceH, strays});
            scores.push_back(strays ? std::numeric_limits<double>::infinity() : solved[i].score);
        }
        const size_t best = static_cast<size_t>(std::min_element(scores.begin(), scores.end()) - scores.begin());
        if (told && std::isfinite(scores[best]))
            told(fmt::format("cross-validation: {} penalties tried, the best so far smoothing {:.3g}, tension {:.3g}",
                             trials.size(), round[best].smoothing, round[best].tension));
        return scores;
    };
    const PenaltySearch search = searchPenalty(scoreRound, givenTension);
    if (!search.best) return Solved{};
    Solved& best = solved[*search.best];
    // Folds' scores keep no solution: the fit of all the samples at the penalty chosen.
    return criterion == Criterion::gcv ? std::move(best) : system.solve(best.penalty, false, 0);
}

// The samples as nanoflann's k-d tree reads them (x, y).
struct SampleCloud {
    const std::vector<Vec3>& pts;
    size_t kdtree_get_point_count() const { return pts.size(); }
    double kdtree_get_pt(size_t i, size_t d) const { return d == 0 ? pts[i].x : pts[i].y; }
    template <class Box>
    bool kdtree_get_bbox(Box&) const { return false; }
};

// How far the net's nodes are from their nearest samples, and which those are.
struct Reach {
    double meanM = 0, largestM = 0;
    double shareBeyond = 0;           ///< of the nodes, farther than the distance asked
    std::vector<size_t> nearest;      ///< each node's nearest sample
    std::vector<double> distanceM;    ///< from it
};

using SampleTree = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<double, SampleCloud>, SampleCloud, 2, size_t>;

Reach dataReach(const SampleTree& tree, const geo::GeoGrid& net, double beyondM) {
    Reach reach;
    size_t beyond = 0;
    for (const Vec3& p : net.grid.points) {
        size_t index = 0;
        double d2 = 0;
        const double q[2] = {p.x, p.y};
        tree.knnSearch(q, 1, &index, &d2);
        const double d = std::sqrt(d2);
        reach.meanM += d, reach.largestM = std::max(reach.largestM, d), beyond += d > beyondM;
        reach.nearest.push_back(index), reach.distanceM.push_back(d);
    }
    const double nodes = static_cast<double>(std::max<size_t>(net.grid.points.size(), 1));
    reach.meanM /= nodes, reach.shareBeyond = static_cast<double>(beyond) / nodes;
    return reach;
}

// The steepest slope the samples show between two of them `h` to 2 `reach`
// apart (h the net's spacing: a surface on the net holds nothing steeper over
// a shorter run; `reach` at least h, and the samples' mean spacing where they
// are sparser than the net, so that pairs are found), from at most
// kSlopeQueries samples evenly through the list.
double steepestSlope(const SampleTree& tree, const std::vector<Vec3>& samples, double h, double reach) {
    double steepest = 0;
    const size_t stride = (samples.size() + kSlopeQueries - 1) / kSlopeQueries;
    std::vector<std::pair<size_t, double>> near;
    for (size_t i = 0; i < samples.size(); i += stride) {
        const double q[2] = {samples[i].x, samples[i].y};
        near.clear();
        tree.radiusSearch(q, 4 * reach * reach, near, nanoflann::SearchParams(32, 0, false));
        for (const auto& [j, d2] : near)
            if (d2 >= h * h) steepest = std::max(steepest, std::abs(samples[j].z - samples[i].z) / std::sqrt(d2));
    }
    return steepest;
}

// Which fold of cross-validation each sample is in: the fold of its block, a
// square `block` metres across from the net's first node; block (i, j) in
// fold (i + 2 j) mod kFolds, so that no two blocks that touch, sides or
// corners, share a fold: a fold's samples are predicted from around them, not
// from beside them.
std::vector<int> foldsOfBlocks(const std::vector<Vec3>& samples, const geo::GeoGrid& net, double block) {
    const Vec3 origin = net.grid.points.front();
    std::vector<int> folds;
    folds.reserve(samples.size());
    for (const Vec3& s : samples) {
        const auto i = static_cast<long long>(std::floor((s.x - origin.x) / block));
        const auto j = static_cast<long long>(std::floor((s.y - origin.y) / block));
        folds.push_back(static_cast<int>((((i + 2 * j) % kFolds) + kFolds) % kFolds));
    }
    return folds;
}

// The samples' residuals from the surface of the net heights z (row-major).
struct Residuals {
    double squares = 0, largest = 0;
    Vec3 worst;
};

// Of one fold's samples only, when `fold` is one (`folds`: each sample's).
Residuals residualsOf(const AxisBasis& bx, const AxisBasis& by, const geo::GeoGrid& net,
                      const std::vector<Vec3>& samples, const Eigen::VectorXd& z,
                      const std::vector<int>& folds = {}, int fold = kAllFolds) {
    Residuals out;
    SurfaceRow row;
    for (size_t i = 0; i < samples.size(); ++i) {
        const Vec3& s = samples[i];
        if (fold != kAllFolds && folds[i] != fold) continue;
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

// What the samples' layout says about how to fit them: their mean spacing
// on the net, how far its nodes are from them, and so which criterion
// chooses the penalty.
struct Sampling {
    size_t onNet = 0;
    double spacing = 0;  ///< sqrt(the net's area / the samples on it): the tension's unit
    Reach reach;         ///< shareBeyond: farther than kUnsupportedSpacings spacings
    Criterion criterion = Criterion::gcv;
    double blockM = 0;       ///< of the folds' blocks
    std::vector<int> folds;  ///< each sample's, with Criterion::folds
    double netSpacingM = 0;  ///< the larger of the net's dx and dy
    double steepest = 0;     ///< the samples' steepest slope, steepestSlope's
};

// How far the surface strays from what its data justify: over the nodes
// farther than half a net spacing (kStrayFromNetSpacings) from their nearest sample, the largest of
// |the node's height - that sample's| / (the data's steepest slope x the
// distance between them). Above 1, a node rises or falls from its nearest
// sample more steeply than any two samples do.
double strayFromData(const Sampling& sampling, const std::vector<Vec3>& samples, const Eigen::VectorXd& z) {
    double stray = 0;
    for (size_t node = 0; node < sampling.reach.nearest.size(); ++node) {
        const double d = sampling.reach.distanceM[node];
        if (d <= kStrayFromNetSpacings * sampling.netSpacingM) continue;
        const double rise = std::abs(z[static_cast<Eigen::Index>(node)] - samples[sampling.reach.nearest[node]].z);
        stray = std::max(stray, rise / (std::max(sampling.steepest, kLeastJustifiedSlope) * d));
    }
    return stray;
}

Sampling samplingOf(const AxisBasis& bx, const AxisBasis& by, const geo::ControlNet& net,
                    const std::vector<Vec3>& samples) {
    Sampling out;
    SurfaceRow row;
    std::vector<bool> onNet(samples.size());
    for (size_t i = 0; i < samples.size(); ++i) {
        onNet[i] = surfaceRow(bx, by, net, samples[i].x, samples[i].y, row);
        out.onNet += onNet[i];
    }
    if (out.onNet == 0) return out;
    out.spacing = std::sqrt(net.dx * (net.cols() - 1) * net.dy * (net.rows() - 1) / static_cast<double>(out.onNet));
    SampleCloud cloud{samples};
    SampleTree tree(2, cloud, nanoflann::KDTreeSingleIndexAdaptorParams(10));
    tree.buildIndex();
    out.reach = dataReach(tree, net, kUnsupportedSpacings * out.spacing);
    out.netSpacingM = std::max(net.dx, net.dy);
    out.steepest = steepestSlope(tree, samples, out.netSpacingM, std::max(out.netSpacingM, out.spacing));
    // Samples spread evenly at random leave a node half their spacing from the nearest on average.
    if (out.reach.meanM <= kClumped * 0.5 * out.spacing) return out;
    out.blockM = kBlockReaches * out.reach.meanM;
    out.folds = foldsOfBlocks(samples, net, out.blockM);
    std::array<size_t, kFolds> perFold{};
    for (size_t i = 0; i < samples.size(); ++i)
        if (onNet[i]) ++perFold[static_cast<size_t>(out.folds[i])];
    // Every fold left out must leave samples, and more than one fold be scored.
    if (std::count_if(perFold.begin(), perFold.end(), [](size_t n) { return n > 0; }) < 2) return out;
    out.criterion = Criterion::folds;
    return out;
}

// Cross-validation scores how the surface predicts samples from samples; along
// a single line, or wherever nodes are far from every sample, nothing scores
// what the surface does there, and a small smoothing lets samples' offsets
// across a line set the slope across it, which the thin plate carries on
// (one line of samples 72-192 m high: nodes 30 m off it at 25 m and 237 m,
// 5.2 times the samples' steepest slope). While the chosen surface strays more
// than kStrayLimit, it is pulled flat away from the samples: the tension
// doubled (from 1) up to the search's greatest, unless net.tension is given,
// then the smoothing raised a third of a decade at a time up to the search's
// top.
void pullInWhileStraying(FitSystem& system, const Sampling& sampling, const std::vector<Vec3>& samples,
                         bool tensionGiven, Solved& solved, FitReport& report) {
    if (!solved.ok) return;
    const Penalty from = solved.penalty;
    const double stray = strayFromData(sampling, samples, solved.z);
    if (stray <= kStrayLimit) return;
    const double step = std::pow(10.0, kFinestSmoothingStep), top = std::pow(10.0, kLargestSmoothingLog);
    double now = stray;
    while (now > kStrayLimit) {
        Penalty next = solved.penalty;
        if (!tensionGiven && next.tension < kGreatestTension) next.tension = std::max(2 * next.tension, 1.0);
        else if (next.smoothing * step <= top * (1 + 1e-9)) next.smoothing *= step;
        else break;
        Solved pulled = system.solve(next, false, 0);
        if (!pulled.ok) break;
        solved = std::move(pulled);
        now = strayFromData(sampling, samples, solved.z);
    }
    report.chosenBy += fmt::format(" (smoothing {:.3g}, tension {:.3g}), then pulled in: its surface rose or fell "
                                   "from the nearest sample {:.2f} times as steeply as any two samples do{}",
                                   from.smoothing, from.tension, stray,
                                   now > kStrayLimit ? fmt::format(" (still {:.2f} at the search's greatest tension and smoothing)", now) : "");
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
    const Sampling sampling = samplingOf(bx, by, net, samples);
    const bool chosen = !spec.smoothing;
    const bool byFolds = chosen && sampling.criterion == Criterion::folds;
    const bool probed = chosen && !byFolds && report.nodes > static_cast<size_t>(kExactTraceNodes);
    NormalEquations eq(net.rows(), net.cols(), std::max(bx.span, by.span) - 1, probed ? kProbes : 0, byFolds ? kFolds : 0);
    SurfaceRow row;
    for (size_t i = 0; i < samples.size(); ++i) {
        if (surfaceRow(bx, by, net, samples[i].x, samples[i].y, row)) eq.addSample(row, samples[i], byFolds ? sampling.folds[i] : -1);
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
    FitSystem system(eq, sampling.spacing, [&](const Eigen::VectorXd& z, int fold) {
        return residualsOf(bx, by, net, samples, z, sampling.folds, fold).squares;
    });
    report.traceMethod = system.traceMethod();
    Solved solved;
    if (spec.smoothing) {
        if (progress) progress(fmt::format("fitting {} samples (smoothing {:.3g})", report.samples, *spec.smoothing));
        solved = system.solve({*spec.smoothing, spec.tension.value_or(0)}, false, 0);
        report.chosenBy = "net.smoothing";
    } else {
        report.chosenBy = byFolds ? fmt::format("cross-validation by blocks {:.0f} m across in {} folds", sampling.blockM, kFolds)
                                  : "generalized cross-validation";
        if (progress) progress(fmt::format("fitting {} samples: choosing the penalty by {}", report.samples, report.chosenBy));
        const auto strayOf = [&](const Eigen::VectorXd& z) { return strayFromData(sampling, samples, z); };
        solved = choosePenalty(system, byFolds ? Criterion::folds : Criterion::gcv, spec.tension, strayOf, report.gcv,
                               progress);
        // No trial was chosen (none gave a solution, or every surface strayed): the largest smoothing
        // tried (the search's first round always tries two), the best conditioned, which fails again
        // below saying why, or is pulled in.
        if (solved.z.size() == 0) {
            const auto largest = std::max_element(report.gcv.begin(), report.gcv.end(),
                                                  [](const GcvTrial& a, const GcvTrial& b) { return a.smoothing < b.smoothing; });
            solved = system.solve({largest->smoothing, largest->tension}, false, 0);
        }
        pullInWhileStraying(system, sampling, samples, spec.tension.has_value(), solved, report);
    }
    report.strayFromData = solved.ok ? strayFromData(sampling, samples, solved.z) : 0;
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
    report.dataReachM = sampling.reach.largestM;
    report.meanReachM = sampling.reach.meanM;
    report.unsupportedShare = sampling.reach.shareBeyond;
    report.unsupportedBeyondM = kUnsupportedSpacings * sampling.spacing;
    report.reachM.assign(sampling.reach.distanceM.begin(), sampling.reach.distanceM.end());
    report.seconds = secondsSince(t0);
    return report;
}

}  // namespace relief::fit
