#pragma once
// net.gridding = "fit": the net whose surface, as the scheme refines it to the
// depth rendered, passes nearest the samples, smooth where they are sparse.
// The net z minimises ||A z - s||^2 + lambda z'Pz: a row of A a sample, the
// refined surface there as weights on the net (fit/basis.h); P the net's
// discrete thin-plate energy (second differences, which no plane pays) plus,
// with a tension t, (t / d)^2 times its membrane energy (first differences),
// d the samples' mean spacing: between samples further apart than about 2 pi
// d / t the surface is pulled flat rather than carried on by its slope;
// lambda from `smoothing` (dimensionless: lambda = smoothing tr(A'A) / tr(P)).
// The smoothing given (the tension then 0 unless given too) or chosen by
// cross-validation, with the tension (given, or chosen among 0 and the powers
// of two from 1/4 to 8): generalized cross-validation for samples spread
// evenly, cross-validation over folds of blocks for samples in lines,
// clusters or around holes (the nodes' mean distance from their nearest
// sample over twice what evenly spread samples leave); a surface that strays
// from its nearest samples more steeply than any two samples do is not
// chosen (GCV passes it by; a choice by blocks is pulled in: tension, then
// smoothing). The normal equations are
// solved by CHOLMOD's supernodal Cholesky in nested-dissection order, on
// relief's own dense kernels (dense_kernels.h: the same bits on every machine
// with the same SuiteSparse, METIS and Eigen, whatever its BLAS).
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/diagnostics.h"
#include "core/types.h"
#include "geo/normalize.h"
#include "scene/scene_spec.h"
#include "subdiv/scheme.h"

namespace relief::fit {

/// One penalty tried by cross-validation: its GCV score, and the trace of
/// the influence matrix (the fit's degrees of freedom).
struct GcvTrial {
    double smoothing = 0, tension = 0, score = 0, traceH = 0;
    bool strays = false;  ///< its surface strays from the data (above kStrayLimit): not chosen
};

struct FitReport {
    int depth = 0;                     ///< the refinement the surface was fitted at
    size_t samples = 0;                ///< fitted (inside the net)
    size_t samplesOutside = 0;         ///< outside the net: not fitted
    size_t nodes = 0;
    size_t nodesConstrained = 0;       ///< nodes some sample's surface weighs on; the rest are the penalty's
    double smoothing = 0, tension = 0;
    std::string chosenBy;              ///< "generalized cross-validation", "cross-validation by blocks ...", or "net.smoothing"
    std::string tensionChosenBy;       ///< that, "net.tension", or "none: net.smoothing given"
    std::vector<GcvTrial> gcv;         ///< in the order tried
    std::string traceMethod;           ///< "exact", or Hutchinson's estimate with its probes
    double rmseM = 0, maxResidualM = 0;
    Vec3 worstSample;                  ///< where the largest residual is
    double dataReachM = 0;             ///< the farthest a node is from its nearest sample
    double meanReachM = 0;             ///< the nodes' mean distance from their nearest sample
    double unsupportedShare = 0;       ///< of the nodes, farther than unsupportedBeyondM from every sample
    double unsupportedBeyondM = 0;     ///< kUnsupportedSpacings times the samples' mean spacing
    std::vector<float> reachM;         ///< each node's (row-major) distance from its nearest sample
    /// What became of those nodes (net.unsupported, the pipeline's doing).
    scene::Unsupported unsupportedAs = scene::Unsupported::Show;
    /// Node `node` (row-major) is farther than unsupportedBeyondM from every sample.
    bool unsupported(size_t node) const { return reachM[node] > unsupportedBeyondM; }
    /// Over the nodes farther than half a net spacing from their nearest sample, the
    /// largest |node - sample| / (the samples' steepest slope x distance):
    /// above kStrayLimit the surface strays from its data (not chosen).
    double strayFromData = 0;
    int refinementSteps = 0;           ///< of the solution, after the Cholesky solve
    double relativeResidual = 0;       ///< of the normal equations, at the end
    double seconds = 0;
};

/// The memory a fit takes for each node of the net: the normal equations, two
/// factorizations (smoothings are tried two at a time) and the trace's probes.
/// Measured 6.5-13 kB a node on 65 x 65 to 257 x 257 nets, dlg4 to the gentle
/// preset's wide stencil; with the tension's membrane term, the whole process
/// 8.7 kB a node (gentle, 257 x 257) to 13.5 (dlg4, 129 x 129, its fixed
/// 100 MB included). Nested dissection's fill grows slowly with the net. The
/// supernodal factorization takes 2 % more than the simplicial one did: with
/// 770,000 samples (their own memory included), the whole process 14.2 kB a
/// node (gentle, 257 x 257), against 13.9.
/// Cross-validation by blocks adds each fold's A'A beside the whole's while
/// they are summed (5 stencils of 8 bytes an entry, up to 81 entries a node)
/// and the 5 systems without a fold (sparse lower triangles, about 41
/// entries of 12 bytes): up to 5.7 kB a node more, so 20 kB a node is
/// reserved.
inline constexpr double kFitBytesPerNode = 20e3;

/// A node farther than this many of the samples' mean spacings (sqrt(area /
/// samples)) from every sample is one the data say nothing of: samples spread
/// evenly at random leave e^(-4 pi), 3.5e-6, of the area that far.
inline constexpr double kUnsupportedSpacings = 2;

/// How far a fit may stray from its data (FitReport::strayFromData) and be
/// chosen: fits of samples spread at random reach 1.02 (a node between
/// samples on a steep slope may rise as steeply as they do); a small
/// smoothing along a single line of samples 2.4 to 5.2, an interpolation of
/// 769,650 samples at the net's corners beyond them 29.
inline constexpr double kStrayLimit = 1.5;

/// The nodes whose straying is measured: those farther than this many net
/// spacings from their nearest sample (nearer, a node is held by the samples
/// its basis reaches; at the edge of a cluster it is held by their tails only,
/// and at a smoothing of 0.005 cyl_elev's clustered samples set such nodes 4.7
/// km away 2,000 m below them).
inline constexpr double kStrayFromNetSpacings = 0.5;

/// The largest relative residual of the normal equations a fit accepts.
inline constexpr double kFitTolerance = 1e-10;

/// Replaces `net`'s heights by the fit of `samples` (frame metres) at `depth`
/// levels of `scheme`. Nullopt, after an error at net.gridding or
/// net.smoothing, when no sample lies on the net, when the equations are
/// singular (smoothing 0 and nodes no sample reaches) or do not converge
/// (naming the steps and the residual); a warning when there are fewer
/// samples than a quarter of the nodes. `progress` (may be empty) hears what
/// it does.
std::optional<FitReport> fitNet(const subdiv::Scheme& scheme, int depth, const std::vector<Vec3>& samples,
                                const scene::NetSpec& spec, geo::ControlNet& net, Diagnostics& diags,
                                const std::function<void(const std::string&)>& progress = {});

}  // namespace relief::fit
