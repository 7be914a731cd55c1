#include "subdiv/analysis.h"
#include "subdiv/resolve.h"

#include <gtest/gtest.h>

#include <cmath>

namespace relief::subdiv {
namespace {

Scheme preset(const std::string& name, std::map<std::string, double> own = {}) {
    Diagnostics d;
    scene::SchemeSpec spec;
    spec.name = "";
    spec.preset = name;
    spec.params = std::move(own);
    spec.allowNonconvergent = true;
    auto s = resolveScheme(spec, d);
    EXPECT_TRUE(s) << name;
    return s->scheme;
}

void expectSameSymbol(const Scheme& a, const Scheme& b) {
    const Symbol sa = symbolOf(a), sb = symbolOf(b);
    ASSERT_EQ(sa.arity, sb.arity);
    ASSERT_EQ(sa.first, sb.first) << a.name << " vs " << b.name;
    ASSERT_EQ(sa.coeffs.size(), sb.coeffs.size()) << a.name << " vs " << b.name;
    for (size_t i = 0; i < sa.coeffs.size(); ++i)
        EXPECT_NEAR(sa.coeffs[i], sb.coeffs[i], 1e-15) << a.name << " vs " << b.name << " at " << i;
}

// Every row of the table in docs/schemes.md.
struct Row {
    const char* what;
    Scheme scheme;
    bool interpolating;
    int smoothness;
    double holder;     // the table's value; < 0: not stated there
    double tolerance;
};

TEST(Certificate, SchemesTable) {
    const std::vector<Row> rows{
        {"classic 4-point", dlgFourPoint(1.0 / 16), true, 1, 2.0, 0.01},
        {"paper 000 Theorem 4, lambda = 0", binary3p(0, 3.0 / 16, 1.0 / 32), false, 4, 5.0, 0.01},
        {"paper 001 lambda = mu = 1/16", fourPoint4p(1.0 / 16, 1.0 / 16, 0.5, 1.0 / 32), false, 2, -1, 0},
        {"paper 001 example 1", fourPoint4p(7.0 / 32, 7.0 / 32, 0.5, 3.0 / 64), false, 1, 1.68, 0.01},
        {"paper 001 example 2", fourPoint4p(1.0 / 30, 1.0 / 30, 0.5, 1.0 / 3), false, 0, 0.5, 0.03},
        {"paper 004 theta = 19/30", ternaryFourPoint(19.0 / 30), true, 2, -1, 0},
        {"paper 004 eta = 1/27", ternaryBSpline(1.0 / 27), false, 2, 3.0, 0.01},
        {"quartic ternary B-spline", ternaryBlend(-5.0 / 27, -5.0 / 81, -1.0 / 81), false, 3, 4.0, 0.01},
    };
    for (const Row& row : rows) {
        const SchemeReport r = analyzeScheme(row.scheme);
        EXPECT_EQ(r.interpolating, row.interpolating) << row.what;
        EXPECT_EQ(r.smoothness, row.smoothness) << row.what;
        if (row.holder > 0) {
            EXPECT_NEAR(r.holder, row.holder, row.tolerance) << row.what;
        }
        EXPECT_LE(r.holderLower, r.holder + 1e-9) << row.what;
        EXPECT_TRUE(r.sumRules) << row.what;
    }
}

// The classic 4-point needs two steps; the papers' one-step test proves only C0.
TEST(Certificate, ClassicFourPointNeedsTwoSteps) {
    const SchemeReport r = analyzeScheme(dlgFourPoint(1.0 / 16));
    ASSERT_GE(r.tests.size(), 2u);
    EXPECT_EQ(r.tests[1].provedAtL, 2);
    EXPECT_DOUBLE_EQ(r.tests[1].normAtL1, 1.0);
    EXPECT_EQ(r.smoothnessByPaperTest, 0);
    const auto notes = explainReport(r, "dlg4", {{"w", 1.0 / 16}});
    ASSERT_FALSE(notes.empty());
    EXPECT_EQ(notes.back(), "the papers' one-step test (L = 1) proves C0; the certificate needs L = 2 to prove C1");
}

// Paper 001 Fig. 2(b): the caption claims C2, the printed parameters give C0.
TEST(Certificate, Paper001Figure2bCaption) {
    const std::map<std::string, double> p{{"lambda", 1.0 / 80}, {"mu", 1.0 / 16}, {"nu", 0.5}, {"omega", 1.0 / 32}};
    const SchemeReport r = analyzeScheme(fourPoint4p(1.0 / 80, 1.0 / 16, 0.5, 1.0 / 32));
    EXPECT_EQ(r.smoothness, 0);
    bool mentioned = false;
    for (const auto& n : explainReport(r, "four-point-4p", p))
        if (n.find("Fig. 2(b)") != std::string::npos) mentioned = true;
    EXPECT_TRUE(mentioned);
}

// Sweeps across the C^k boundaries the papers give.
TEST(Certificate, TernaryFourPointC2ExactlyBetweenThreeFifthsAndTwoThirds) {
    for (double theta : {0.605, 0.62, 0.633, 0.65, 0.66})
        EXPECT_EQ(analyzeScheme(ternaryFourPoint(theta)).smoothness, 2) << theta;
    for (double theta : {0.55, 0.59, 0.675, 0.7})
        EXPECT_LT(analyzeScheme(ternaryFourPoint(theta)).smoothness, 2) << theta;
}

TEST(Certificate, ParametricCubicBSplineC2ExactlyBetweenZeroAndOneNinth) {
    for (double eta : {0.005, 1.0 / 27, 0.06, 0.1, 0.108})
        EXPECT_EQ(analyzeScheme(ternaryBSpline(eta)).smoothness, 2) << eta;
    for (double eta : {-0.01, 0.115, 0.13})
        EXPECT_LT(analyzeScheme(ternaryBSpline(eta)).smoothness, 2) << eta;
}

TEST(Certificate, Paper000TheoremFourFamilyIsAtLeastC4) {
    for (double lambda : {-0.015, -0.005, 0.0, 0.01, 0.02, 0.04})
        EXPECT_GE(analyzeScheme(binary3p(lambda, 4 * lambda + 3.0 / 16, 4 * lambda + 1.0 / 32)).smoothness, 4)
            << lambda;
}

// Each special case equals its named scheme's mask exactly.
TEST(Presets, SpecialCasesEqualTheirSchemes) {
    expectSameSymbol(preset("deslauriers-dubuc"), ternaryFourPoint(5.0 / 9));
    for (double mu : {0.0, 1.0 / 11, 0.2})
        expectSameSymbol(preset("hassan", {{"mu", mu}}), ternaryFourPoint(0.5 + 1.5 * mu));
    for (double eta : {0.0, 1.0 / 27, 0.08})
        expectSameSymbol(ternaryBSpline(eta), ternaryBlend(-1.0 / 9 - eta, -eta, 0));
    for (double theta : {0.6, 19.0 / 30})
        expectSameSymbol(ternaryFourPoint(theta), ternaryBlend(0, theta / 9, (1 - theta) / 9));
    expectSameSymbol(preset("ternary-bspline-3"), ternaryBSpline(1.0 / 27));
    expectSameSymbol(preset("classic-4point"), fourPoint4p(0, 0, 0.5, 1.0 / 16));
    expectSameSymbol(preset("classic-4point"), binary3p(0, 0, -1.0 / 16));
    // Ternary B-spline of degree d: symbol (1 + z + z^2)^(d+1) / 3^d.
    for (int d = 1; d <= 4; ++d) {
        Symbol b{3, 0, {1.0}};
        for (int i = 0; i <= d; ++i) {
            std::vector<double> next(b.coeffs.size() + 2, 0.0);
            for (size_t j = 0; j < b.coeffs.size(); ++j)
                for (int t = 0; t < 3; ++t) next[j + t] += b.coeffs[j] / (i < d ? 3.0 : 1.0);
            b.coeffs = next;
        }
        const Symbol s = symbolOf(preset("ternary-bspline-" + std::to_string(d)));
        ASSERT_EQ(s.coeffs.size(), b.coeffs.size()) << d;
        for (size_t j = 0; j < b.coeffs.size(); ++j) EXPECT_NEAR(s.coeffs[j], b.coeffs[j], 1e-15) << d;
        EXPECT_EQ(analyzeScheme(preset("ternary-bspline-" + std::to_string(d))).smoothness, d - 1) << d;
    }
}

// Polynomial reproduction (primal parameterisation) up to each scheme's degree,
// checked on refined data away from the boundary.
TEST(Reproduction, Degrees) {
    EXPECT_EQ(analyzeScheme(dlgFourPoint(1.0 / 16)).reproductionDegree, 3);
    EXPECT_EQ(analyzeScheme(dlgFourPoint(0.04)).reproductionDegree, 1);
    EXPECT_EQ(analyzeScheme(ternaryFourPoint(5.0 / 9)).reproductionDegree, 3);
    EXPECT_EQ(analyzeScheme(ternaryFourPoint(19.0 / 30)).reproductionDegree, 2);
    EXPECT_EQ(analyzeScheme(ternaryBSpline(1.0 / 27)).reproductionDegree, 1);
    EXPECT_EQ(analyzeScheme(binary3p(0, 3.0 / 16, 1.0 / 32)).reproductionDegree, 1);
    EXPECT_EQ(analyzeScheme(fourPoint4p(7.0 / 32, 7.0 / 32, 0.5, 3.0 / 64)).reproductionDegree, 1);
}

TEST(Mask, RawMaskEqualsTheNamedScheme) {
    Diagnostics d;
    auto s = schemeFromMask(2, -3, {-1.0 / 16, 0, 9.0 / 16, 1, 9.0 / 16, 0, -1.0 / 16}, {}, d);
    ASSERT_TRUE(s);
    expectSameSymbol(*s, dlgFourPoint(1.0 / 16));
    EXPECT_EQ(s->ghostsBefore(), 1);
    Diagnostics bad;
    EXPECT_FALSE(schemeFromMask(2, -1, {0.5, 1, 0.6}, {"s.toml", 4, 8}, bad));
    EXPECT_EQ(formatDiagnostic(bad.all()[0]),
              "s.toml:4:8: error: mask: the weights of child position 1 sum to 1.1, not 1; every "
              "position must (the sum rule), or the scheme cannot converge");
}

}  // namespace
}  // namespace relief::subdiv
