#pragma once
// Which penalties (smoothing, tension) generalized cross-validation tries, in
// rounds of two, and when it stops: the search alone, the scoring the
// caller's (fit_net.cpp factorizes the equations for each). Apart from the
// fit's numbers, so that the search can be held to synthetic scores. Internal
// to fit/.
#include <cstddef>
#include <functional>
#include <optional>
#include <vector>

namespace relief::fit {

/// log10 of the least and the largest smoothing searched.
inline constexpr double kLeastSmoothingLog = -6, kLargestSmoothingLog = 2;
/// The finest step of the search, in log10 of the smoothing.
inline constexpr double kFinestSmoothingStep = 1.0 / 3;
/// The greatest tension the search tries.
inline constexpr double kGreatestTension = 8;

struct Penalty {
    double smoothing = 0, tension = 0;
};

/// Scores one round's penalties (at most two, one for each worker), in
/// order: infinity where a penalty has no score (its equations failed).
using ScoreRound = std::function<std::vector<double>(const std::vector<Penalty>& round)>;

struct PenaltySearch {
    std::vector<Penalty> tried;  ///< in the order tried
    std::vector<double> scores;  ///< of each tried
    std::optional<size_t> best;  ///< into tried: the least score (the first of equals); none if none scored
};

/// The smoothing over log10 [-6, 2] (below, the equations' condition makes
/// the score itself uncertain) at the tension given (else none): the points a
/// third and two thirds of the way across, then three rounds of the
/// points half a step either side of the best so far, the step halved each
/// round, down to a third of a decade (a GCV minimum is that flat): these
/// rounds reach the ends' neighbours, not the ends. Then, unless
/// the tension is given, tensions 1 and 1/2 at the best smoothing; if neither
/// lowers the score by a thousandth (a third of a decade of smoothing moves it
/// by about a hundredth near its minimum), the search ends there, the least
/// score kept. Else twice the tension while it wins, from 1 up to 8 if 1 won,
/// or half, from 1/2 down to 1/4 if 1/2 won, each at the best smoothing and a
/// third of a decade below (a membrane's pull lowers the best smoothing, if
/// anything; this may reach 10^-6). 8 penalties with the tension given, 10 to
/// 16 without (fewer when the first round scores nothing).
PenaltySearch searchPenalty(const ScoreRound& scoreRound, std::optional<double> givenTension);

}  // namespace relief::fit
