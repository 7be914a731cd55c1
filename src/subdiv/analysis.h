#pragma once
// What a scheme and its parameters give: mask, sum rules, interpolation,
// support, polynomial reproduction, and a certified smoothness class from the
// difference-scheme test, with a Hölder exponent estimate.
//
// Notation: the symbol a(z) = sum_k a_k z^k with P'_k = sum_l a_{k - m l} P_l
// (m = arity), and sigma(z) = 1 + z + ... + z^{m-1}. The scheme is C^k when
// the scheme (1/m) S_{k+1}, with symbol b_k(z) = m^k a(z) / sigma(z)^{k+1}, is
// contractive: ||((1/m) S_{k+1})^L||_inf < 1 for some L (Dyn 1992; Hassan &
// Dodgson for ternary schemes). The papers' own sufficient conditions are this
// test with L = 1.
#include <map>
#include <string>
#include <vector>

#include "subdiv/scheme.h"

namespace relief::subdiv {

/// a(z) = sum_i coeffs[i] z^(first + i)
struct Symbol {
    int arity = 2;
    int first = 0;
    std::vector<double> coeffs;
};

Symbol symbolOf(const Scheme& scheme);

struct DifferenceTest {
    int k;                      ///< the order of smoothness tested (C^k)
    bool factorizable;          ///< sigma^(k+1) divides a(z)
    int provedAtL = 0;          ///< smallest L with norm < 1; 0 when none up to maxL
    double normAtL1 = 0;        ///< the papers' one-step test
    double bestNormRoot = 0;    ///< min over L of ||.||^(1/L)
};

struct SchemeReport {
    Symbol symbol;
    bool sumRules = false;          ///< every child position's weights sum to 1
    bool interpolating = false;
    double supportWidth = 0;        ///< of the basic limit function, in coarse intervals
    int reproductionDegree = -1;    ///< polynomials reproduced exactly (primal parameterisation)
    int generationDegree = -1;      ///< number of sigma factors - 1
    int ghostsBefore = 0, ghostsAfter = 0;
    int smoothness = -1;            ///< certified C^k; -1 when not even convergence is proven
    int smoothnessByPaperTest = -1; ///< largest k the one-step (L = 1) test proves
    double holderLower = 0;         ///< k - log_m(min_L ||b_k^L||^(1/L)): a proven lower bound
    double holder = 0;              ///< estimate: k - log_m(rho), rho from powers of the subdivision matrices
    std::vector<DifferenceTest> tests;
    std::vector<std::string> notes;
};

SchemeReport analyzeScheme(const Scheme& scheme, int maxL = 0);

/// Divides p by sigma (exactly, when the remainder is below tolerance).
bool divideBySigma(const Symbol& p, Symbol& quotient);

/// ||S_b^L||_inf: the largest sum of |coefficients| over a residue class mod m^L
/// of b(z) b(z^m) ... b(z^(m^(L-1))).
double iteratedNorm(const Symbol& b, int L);

}  // namespace relief::subdiv

namespace relief::subdiv {

/// Plain-language notes for a report: each source paper's own (sufficient)
/// conditions for these parameters, which hold and which fail, and where the
/// certificate proves more than the papers claim (or a figure claims more than
/// its printed parameters give).
std::vector<std::string> explainReport(const SchemeReport& report, const std::string& family,
                                       const std::map<std::string, double>& params);

/// "C1 (Hölder ~1.68)" or "convergence not proven (Hölder ~0.00)".
std::string certifiedClass(const SchemeReport& report);

}  // namespace relief::subdiv
