#include "subdiv/resolve.h"
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

scene::SchemeSpec specOf(std::string name, SchemeParams params) {
    scene::SchemeSpec spec;
    spec.name = std::move(name);
    spec.params = std::move(params);
    spec.locs.file = "s.toml";
    spec.locs.keys["subdivision.scheme"] = {"s.toml", 3, 10};
    return spec;
}

TEST(ResolveScheme, FillsDefaultsAndReportsUnknownParameterWithSuggestion) {
    Diagnostics diags;
    auto s = resolveScheme(specOf("four-point-4p", {{"omega", 0.05}}), diags);
    ASSERT_TRUE(s);
    EXPECT_EQ(s->params.at("nu"), 0.5);
    EXPECT_EQ(s->params.at("omega"), 0.05);
    EXPECT_EQ(s->report.smoothness, 1);

    Diagnostics bad;
    auto spec = specOf("four-point-4p", {{"omgea", 0.05}});
    spec.locs.keys["subdivision.omgea"] = {"s.toml", 7, 1};
    EXPECT_FALSE(resolveScheme(spec, bad));
    ASSERT_EQ(bad.all().size(), 1u);
    EXPECT_EQ(formatDiagnostic(bad.all()[0]),
              "s.toml:7:1: error: unknown parameter \"omgea\" for scheme \"four-point-4p\" (did "
              "you mean \"omega\"?); it takes: lambda, mu, nu, omega");
}

TEST(ResolveScheme, WarnsOnAsymmetricFourParameterScheme) {
    Diagnostics diags;
    ASSERT_TRUE(resolveScheme(specOf("four-point-4p", {{"lambda", 0.0125}, {"mu", 0.0625}}), diags));
    EXPECT_FALSE(diags.hasErrors());
    EXPECT_EQ(diags.warningCount(), 1);
}

// A preset is its family with fixed parameters; naming another family is an
// error at the preset, and a parameter the preset fixes is an error at that key.
TEST(ResolveScheme, PresetsResolveToTheirFamily) {
    Diagnostics diags;
    auto spec = specOf("", {});
    spec.preset = "hassan";
    const auto hassan = resolveScheme(spec, diags);
    ASSERT_TRUE(hassan);
    EXPECT_EQ(hassan->family, "ternary-blend");
    EXPECT_DOUBLE_EQ(hassan->params.at("beta"), 1.0 / 18 + 1.0 / 66);

    spec.name = "dlg4";
    spec.locs.keys["subdivision.preset"] = {"s.toml", 4, 10};
    Diagnostics wrongFamily;
    EXPECT_FALSE(resolveScheme(spec, wrongFamily));
    ASSERT_EQ(wrongFamily.all().size(), 1u);
    EXPECT_EQ(wrongFamily.all()[0].loc.line, 4);

    auto fixed = specOf("", {{"alpha", 0.1}});
    fixed.preset = "deslauriers-dubuc";
    fixed.locs.keys["subdivision.alpha"] = {"s.toml", 6, 1};
    Diagnostics fixedParam;
    EXPECT_FALSE(resolveScheme(fixed, fixedParam));
    ASSERT_EQ(fixedParam.all().size(), 1u);
    EXPECT_EQ(fixedParam.all()[0].loc.line, 6);
}

// A mask becomes its scheme; a scheme not proven to converge is a warning at
// the scheme's key unless allowed.
TEST(ResolveScheme, MaskAndNonconvergenceWarning) {
    auto spec = specOf("mask", {});
    spec.maskArity = 2;
    spec.mask = {-1.0 / 16, 0, 9.0 / 16, 1, 9.0 / 16, 0, -1.0 / 16};
    Diagnostics diags;
    const auto mask = resolveScheme(spec, diags);
    ASSERT_TRUE(mask);
    EXPECT_EQ(mask->scheme.arity, 2);
    EXPECT_EQ(mask->report.smoothness, 1);  // the classic 4-point
    EXPECT_EQ(diags.warningCount(), 0);

    Diagnostics rough;
    ASSERT_TRUE(resolveScheme(specOf("dlg4", {{"w", -0.5}}), rough));
    ASSERT_EQ(rough.warningCount(), 1);
    EXPECT_EQ(rough.all()[0].loc.line, 3);
    auto allowed = specOf("dlg4", {{"w", -0.5}});
    allowed.allowNonconvergent = true;
    Diagnostics quiet;
    ASSERT_TRUE(resolveScheme(allowed, quiet));
    EXPECT_EQ(quiet.warningCount(), 0);
}

// The help text and docs/schemes.md's table come from the scheme table.
TEST(SchemeTable, MarkdownListsEveryFamilyAndPreset) {
    const std::string table = schemeTableMarkdown();
    for (const auto& f : schemeFamilies()) EXPECT_NE(table.find("| `" + f.name + "` |"), std::string::npos) << f.name;
    for (const auto& p : presets()) EXPECT_NE(table.find("| `" + p.name + "` |"), std::string::npos) << p.name;
}

}  // namespace
}  // namespace relief::subdiv
