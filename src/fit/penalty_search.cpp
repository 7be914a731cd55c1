#include "fit/penalty_search.h"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <utility>

namespace relief::fit {

namespace {

constexpr double kLowestLog = kLeastSmoothingLog, kHighestLog = kLargestSmoothingLog;
constexpr double kStep = (kHighestLog - kLowestLog) / 3, kFinest = kFinestSmoothingStep;
// The tensions tried beside none when none is given: powers of two, from 1 and 1/2 outwards.
constexpr double kFirstTension = 1, kLeastTension = 0.25;
constexpr double kTensionGain = 1e-3;  // the least share of the score a first tension must gain to be pursued

// A point of the search: log10 of the smoothing, and the tension.
struct Point {
    double log, tension;
};

class Search {
public:
    explicit Search(const ScoreRound& scoreRound) : scoreRound_(scoreRound) {}

    /// Scores the points not tried before and inside the range.
    void round(std::vector<Point> points) {
        std::erase_if(points, [&](const Point& p) { return outside(p.log) || tried(p); });
        if (points.empty()) return;
        std::vector<Penalty> penalties;
        for (const Point& p : points) penalties.push_back({std::pow(10.0, p.log), p.tension});
        const std::vector<double> scores = scoreRound_(penalties);
        if (scores.size() != penalties.size()) throw std::logic_error("fit: a round scored other than its penalties");
        for (size_t i = 0; i < points.size(); ++i) {
            out_.tried.push_back(penalties[i]);
            out_.scores.push_back(scores[i]);
            logs_.push_back(points[i].log);
            if (scores[i] < bestScore()) out_.best = out_.tried.size() - 1;
        }
    }

    bool scored() const { return out_.best.has_value(); }
    double bestScore() const { return out_.best ? out_.scores[*out_.best] : std::numeric_limits<double>::infinity(); }
    /// Of the best so far; before any, the top of the range: the rounds then climb to the best
    /// conditioned equations.
    double bestLog() const { return out_.best ? logs_[*out_.best] : kHighestLog; }
    double bestTension() const { return out_.best ? out_.tried[*out_.best].tension : 0; }
    PenaltySearch result() && { return std::move(out_); }

private:
    static bool outside(double log) { return log < kLowestLog - 1e-9 || log > kHighestLog + 1e-9; }
    bool tried(const Point& p) const {
        for (size_t i = 0; i < logs_.size(); ++i)
            if (out_.tried[i].tension == p.tension && std::abs(logs_[i] - p.log) < 1e-9) return true;
        return false;
    }

    const ScoreRound& scoreRound_;
    PenaltySearch out_;
    std::vector<double> logs_;  // of each tried
};

}  // namespace

PenaltySearch searchPenalty(const ScoreRound& scoreRound, std::optional<double> givenTension) {
    Search search(scoreRound);
    const double tension = givenTension.value_or(0);
    search.round({{kLowestLog + kStep, tension}, {kLowestLog + 2 * kStep, tension}});
    for (double half = kStep / 2; half > kFinest - 1e-9; half /= 2)
        search.round({{search.bestLog() - half, tension}, {search.bestLog() + half, tension}});
    if (givenTension || !search.scored()) return std::move(search).result();
    const double untensioned = search.bestScore();
    search.round({{search.bestLog(), kFirstTension}, {search.bestLog(), kFirstTension / 2}});
    if (!(search.bestScore() < (1 - kTensionGain) * untensioned)) return std::move(search).result();
    const double factor = search.bestTension() == kFirstTension ? 2 : 0.5;
    for (double t = search.bestTension() * factor; t >= kLeastTension && t <= kGreatestTension; t *= factor) {
        const double before = search.bestScore();
        search.round({{search.bestLog(), t}, {search.bestLog() - kFinest, t}});
        if (!(search.bestScore() < before)) break;
    }
    return std::move(search).result();
}

}  // namespace relief::fit
