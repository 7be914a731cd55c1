#include "subdiv/scheme.h"

#include <gtest/gtest.h>

#include <numeric>

namespace relief::subdiv {
namespace {

void expectWeights(const Rule& rule, int offset, std::vector<double> weights) {
    EXPECT_EQ(rule.offset, offset);
    ASSERT_EQ(rule.weights.size(), weights.size());
    for (size_t j = 0; j < weights.size(); ++j) EXPECT_DOUBLE_EQ(rule.weights[j], weights[j]) << j;
}

TEST(Scheme, ClassicFourPointMask) {
    const Scheme s = dlgFourPoint(1.0 / 16);
    EXPECT_EQ(s.arity, 2);
    expectWeights(s.rules[0], 0, {1.0});
    expectWeights(s.rules[1], -1, {-1.0 / 16, 9.0 / 16, 9.0 / 16, -1.0 / 16});
}

// Paper 001's scheme with lambda = mu = 0, nu = 1/2 is the classic 4-point with w = +omega.
TEST(Scheme, FourParameterSpecialCaseIsClassic) {
    for (double w : {1.0 / 16, 0.03, -0.02}) {
        const Scheme a = fourPoint4p(0, 0, 0.5, w), b = dlgFourPoint(w);
        expectWeights(a.rules[0], -1, {0.0, 1.0, 0.0});
        expectWeights(a.rules[1], b.rules[1].offset, b.rules[1].weights);
    }
}

// Paper 000's scheme with lambda = mu = 0 is the classic 4-point with w = -omega.
TEST(Scheme, ThreeParameterSpecialCaseIsClassicWithOppositeSign) {
    const Scheme a = binary3p(0, 0, -1.0 / 16), b = dlgFourPoint(1.0 / 16);
    expectWeights(a.rules[0], -2, {0, 0, 1, 0, 0});
    expectWeights(a.rules[1], b.rules[1].offset, b.rules[1].weights);
}

// Theorem 4 of paper 000 with lambda = 0 is the quintic B-spline, mask (1+z)^6 / 32.
TEST(Scheme, ThreeParameterC4FamilyAtZeroIsQuinticBSpline) {
    const Scheme s = binary3p(0, 3.0 / 16, 1.0 / 32);
    expectWeights(s.rules[0], -2, {0, 6.0 / 32, 20.0 / 32, 6.0 / 32, 0});
    expectWeights(s.rules[1], -1, {1.0 / 32, 15.0 / 32, 15.0 / 32, 1.0 / 32});
}

TEST(Scheme, EveryRuleSumsToOneForAnyParameters) {
    for (double a : {-0.3, 0.0, 1.0 / 30, 7.0 / 32, 0.5})
        for (double b : {-0.1, 0.0, 0.25, 1.0 / 3})
            for (const Scheme& s : {fourPoint4p(a, b, 0.3, b), binary3p(a, b, a - b),
                                    dlgFourPoint(b)})
                for (const Rule& r : s.rules)
                    EXPECT_NEAR(std::accumulate(r.weights.begin(), r.weights.end(), 0.0), 1.0,
                                1e-15)
                        << s.name;
}

TEST(Scheme, GhostPointsPerSide) {
    EXPECT_EQ(dlgFourPoint(0.0625).ghostsBefore(), 1);
    EXPECT_EQ(dlgFourPoint(0.0625).ghostsAfter(), 1);
    EXPECT_EQ(fourPoint4p(0.1, 0.1, 0.5, 0.05).ghostsBefore(), 1);
    EXPECT_EQ(fourPoint4p(0.1, 0.1, 0.5, 0.05).ghostsAfter(), 1);
    EXPECT_EQ(binary3p(0.01, 0.2, 0.05).ghostsBefore(), 2);
    EXPECT_EQ(binary3p(0.01, 0.2, 0.05).ghostsAfter(), 2);
}

TEST(MakeScheme, FillsDefaultsAndReportsUnknownParameterWithSuggestion) {
    Diagnostics diags;
    std::map<std::string, double> resolved;
    auto s = makeScheme("four-point-4p", {"s.toml", 3, 10}, {{"omega", 0.05}}, {}, diags,
                        &resolved);
    ASSERT_TRUE(s);
    EXPECT_EQ(resolved.at("nu"), 0.5);
    EXPECT_EQ(resolved.at("omega"), 0.05);

    Diagnostics bad;
    EXPECT_FALSE(makeScheme("four-point-4p", {"s.toml", 3, 10}, {{"omgea", 0.05}},
                            {{"omgea", {"s.toml", 7, 1}}}, bad));
    ASSERT_EQ(bad.all().size(), 1u);
    EXPECT_EQ(formatDiagnostic(bad.all()[0]),
              "s.toml:7:1: error: unknown parameter \"omgea\" for scheme \"four-point-4p\" (did "
              "you mean \"omega\"?); it takes: lambda, mu, nu, omega");
}

TEST(MakeScheme, WarnsOnAsymmetricFourParameterScheme) {
    Diagnostics diags;
    ASSERT_TRUE(makeScheme("four-point-4p", {"s.toml", 3, 10},
                           {{"lambda", 0.0125}, {"mu", 0.0625}}, {}, diags));
    EXPECT_FALSE(diags.hasErrors());
    EXPECT_EQ(diags.warningCount(), 1);
}

}  // namespace
}  // namespace relief::subdiv
