// GCV's search for the fit's penalty, held to synthetic scores: which
// penalties it tries, in rounds of at most two, and which it keeps.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <set>

#include "fit/penalty_search.h"

namespace relief::fit {
namespace {

// A score over (log10 smoothing, tension); the rounds it was asked for.
struct Landscape {
    explicit Landscape(std::function<double(double log, double tension)> s) : score(std::move(s)) {}

    std::function<double(double log, double tension)> score;
    std::vector<std::vector<Penalty>> rounds;

    PenaltySearch search(std::optional<double> givenTension) {
        return searchPenalty(
            [&](const std::vector<Penalty>& round) {
                rounds.push_back(round);
                std::vector<double> out;
                for (const Penalty& p : round) out.push_back(score(std::log10(p.smoothing), p.tension));
                return out;
            },
            givenTension);
    }
    double chosenLog(const PenaltySearch& s) const { return std::log10(s.tried.at(*s.best).smoothing); }
};

// A bowl in log10 smoothing about `least`, 1 at its bottom, and each tension's share of it.
std::function<double(double, double)> bowl(double least, std::map<double, double> tensionShare = {}) {
    return [=](double log, double tension) {
        const auto share = tensionShare.find(tension);
        return (1 + (log - least) * (log - least)) * (1 + (share == tensionShare.end() ? 0 : share->second));
    };
}

// The smoothing: the points a third and two thirds across log10 [-6, 2], then
// three rounds of half a step either side of the best, at the tension given:
// on a bowl, the third of a decade nearest its bottom, the range's ends not
// tried. Every round at most two penalties, none tried twice.
TEST(PenaltySearch, TheSmoothingToAThirdOfADecade) {
    for (int i = 0; i <= 180; ++i) {
        const double least = -6.49 + 0.05 * i;  // never half way between two thirds of a decade: no tie
        Landscape l(bowl(least));
        const PenaltySearch s = l.search(2.0);
        ASSERT_TRUE(s.best);
        ASSERT_EQ(s.tried.size(), 8u) << least;
        EXPECT_NEAR(std::log10(s.tried[0].smoothing), -6 + 8.0 / 3, 1e-12);
        EXPECT_NEAR(std::log10(s.tried[1].smoothing), -6 + 16.0 / 3, 1e-12);
        std::set<std::pair<double, double>> seen;
        for (const Penalty& p : s.tried) {
            EXPECT_EQ(p.tension, 2);
            EXPECT_TRUE(seen.insert({p.smoothing, p.tension}).second) << "tried twice: " << p.smoothing;
        }
        for (const auto& round : l.rounds) EXPECT_LE(round.size(), 2u);
        const double nearest = std::clamp(-6 + std::round((least + 6) * 3) / 3, -6 + 1.0 / 3, 2 - 1.0 / 3);
        EXPECT_NEAR(l.chosenLog(s), nearest, 1e-9) << least;
        EXPECT_EQ(s.scores[*s.best], *std::min_element(s.scores.begin(), s.scores.end()));
    }
}

// The whole sequence on one bowl, in order: the rounds' points, lower first.
TEST(PenaltySearch, TheSequenceOnABowl) {
    Landscape l(bowl(0.4));
    const PenaltySearch s = l.search(std::nullopt);
    std::vector<double> logs, tensions;
    for (const Penalty& p : s.tried) logs.push_back(std::round(3 * std::log10(p.smoothing))), tensions.push_back(p.tension);
    // In thirds of a decade, the bowl's bottom at 1.2: -10, -2; -2 +- 4; 2 +- 2; 2 +- 1; then 1 at
    // tensions 1 and 1/2.
    EXPECT_EQ(logs, (std::vector<double>{-10, -2, -6, 2, 0, 4, 1, 3, 1, 1}));
    EXPECT_EQ(tensions, (std::vector<double>{0, 0, 0, 0, 0, 0, 0, 0, 1, 0.5}));
    EXPECT_EQ(l.rounds.size(), 5u);
    EXPECT_NEAR(l.chosenLog(s), 1.0 / 3, 1e-9);
}

// Without a tension given: tensions 1 and 1/2 at the best smoothing, one trial
// each; if neither gains a thousandth of the score, nothing more, and the
// least score is kept even so.
TEST(PenaltySearch, ATensionThatGainsLessThanAThousandthIsNotPursued) {
    Landscape l(bowl(-1.1, {{1, -0.0008}, {0.5, -0.0005}}));
    const PenaltySearch s = l.search(std::nullopt);
    ASSERT_EQ(s.tried.size(), 10u);
    size_t bestUntensioned = 0;
    for (size_t i = 0; i < 8; ++i)
        if (s.scores[i] < s.scores[bestUntensioned]) bestUntensioned = i;
    EXPECT_NEAR(std::log10(s.tried[bestUntensioned].smoothing), -1, 1e-9);  // the bowl's bottom, to a third of a decade
    EXPECT_EQ(s.tried[8].tension, 1);
    EXPECT_EQ(s.tried[9].tension, 0.5);
    EXPECT_EQ(s.tried[8].smoothing, s.tried[bestUntensioned].smoothing);
    EXPECT_EQ(s.tried[9].smoothing, s.tried[bestUntensioned].smoothing);
    EXPECT_EQ(s.tried[*s.best].tension, 1);  // 0.08 %: kept, not pursued
    EXPECT_NEAR(l.chosenLog(s), -1, 1e-9);
}

// 1/2 gains more than a thousandth: half of it next, at the best smoothing and
// a third of a decade below, then no further than 1/4.
TEST(PenaltySearch, HalfWinsAndQuarterIsTried) {
    Landscape l(bowl(-1.1, {{1, -0.001}, {0.5, -0.01}, {0.25, -0.02}}));
    const PenaltySearch s = l.search(std::nullopt);
    ASSERT_EQ(s.tried.size(), 12u);
    EXPECT_EQ(s.tried[10].tension, 0.25);
    EXPECT_EQ(s.tried[11].tension, 0.25);
    EXPECT_NEAR(std::log10(s.tried[10].smoothing), -1, 1e-9);
    EXPECT_NEAR(std::log10(s.tried[11].smoothing), -1 - 1.0 / 3, 1e-9);
    EXPECT_EQ(s.tried[*s.best].tension, 0.25);
    EXPECT_EQ(l.rounds.size(), 6u);  // four of the smoothing, two of the tension
}

// 1 wins: twice it while the last won, each round at the best smoothing and a
// third of a decade below, which a membrane's pull may make the best; up to 8.
TEST(PenaltySearch, OneWinsAndTheTensionDoublesWhileItWins) {
    // Each tension above 1 lowers the bowl's bottom by a third of a decade.
    const auto score = [](double log, double tension) {
        const double shift = tension > 1 ? std::log2(tension) / 3 : 0;
        const double share = tension == 0 ? 0 : tension == 0.5 ? -0.001 : -0.01 * (1 + std::log2(tension));
        return (1 + (log - (-1 - shift)) * (log - (-1 - shift))) * (1 + share);
    };
    Landscape l(score);
    const PenaltySearch s = l.search(std::nullopt);
    std::vector<double> tensions;
    for (const Penalty& p : s.tried)
        if (p.tension > 1) tensions.push_back(p.tension);
    EXPECT_EQ(tensions, (std::vector<double>{2, 2, 4, 4, 8, 8}));
    EXPECT_EQ(s.tried[*s.best].tension, 8);
    EXPECT_NEAR(l.chosenLog(s), -2, 1e-9);  // three tensions, each a third of a decade below the last
    ASSERT_EQ(s.tried.size(), 16u);

    // A tension that loses ends it: 4 worse than 2.
    Landscape stops([&](double log, double tension) { return tension >= 4 ? 10.0 : score(log, tension); });
    const PenaltySearch t = stops.search(std::nullopt);
    EXPECT_EQ(t.tried.size(), 14u);
    EXPECT_EQ(t.tried[*t.best].tension, 2);
}

// No trial scored: no choice; the rounds climb from the top of the range, the
// best conditioned, and no tension is tried.
TEST(PenaltySearch, NoScoreNoChoice) {
    Landscape l([](double, double) { return std::numeric_limits<double>::infinity(); });
    const PenaltySearch s = l.search(std::nullopt);
    EXPECT_FALSE(s.best);
    ASSERT_EQ(s.tried.size(), 5u);
    for (const Penalty& p : s.tried) EXPECT_EQ(p.tension, 0);
    EXPECT_NEAR(std::log10(s.tried.back().smoothing), 2 - 1.0 / 3, 1e-9);
}

}  // namespace
}  // namespace relief::fit
