#include "subdiv/analysis.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace relief::subdiv {

namespace {

constexpr double kTolerance = 1e-12;

// Spectral radius of a square matrix by Gelfand's formula on repeated squaring
// with normalisation: robust for complex and defective eigenvalues.
double spectralRadius(std::vector<std::vector<double>> t) {
    const size_t n = t.size();
    double logScale = 0;
    double power = 1;  // t holds T^power / (the scale in logScale)
    for (int step = 0; step < 24; ++step) {
        double norm = 0;
        for (const auto& row : t) {
            double s = 0;
            for (double v : row) s += std::fabs(v);
            norm = std::max(norm, s);
        }
        if (norm == 0) return 0;
        for (auto& row : t)
            for (double& v : row) v /= norm;
        logScale += std::log(norm) / power;
        std::vector<std::vector<double>> sq(n, std::vector<double>(n, 0.0));
        for (size_t i = 0; i < n; ++i)
            for (size_t k = 0; k < n; ++k)
                if (t[i][k] != 0)
                    for (size_t j = 0; j < n; ++j) sq[i][j] += t[i][k] * t[k][j];
        t = std::move(sq);
        power *= 2;
    }
    double norm = 0;
    for (const auto& row : t) {
        double s = 0;
        for (double v : row) s += std::fabs(v);
        norm = std::max(norm, s);
    }
    return norm == 0 ? 0 : std::exp(logScale + std::log(norm) / power);
}

// Subdivision matrices T_r of the scheme with symbol b on the invariant
// neighbourhood of the support: (T_r)_{ij} = b_{m i + r - j} (indices shifted
// to start at 0).
std::vector<std::vector<std::vector<double>>> subdivisionMatrices(const Symbol& b) {
    const int m = b.arity;
    const int len = static_cast<int>(b.coeffs.size());
    const int n = std::max(1, (len - 1 + m - 2) / (m - 1));
    std::vector<std::vector<std::vector<double>>> mats;
    for (int r = 0; r < m; ++r) {
        std::vector<std::vector<double>> t(n, std::vector<double>(n, 0.0));
        for (int i = 0; i < n; ++i)
            for (int j = 0; j < n; ++j) {
                const int k = m * i + r - j;
                if (k >= 0 && k < len) t[i][j] = b.coeffs[k];
            }
        mats.push_back(std::move(t));
    }
    return mats;
}

std::vector<std::vector<double>> matmul(const std::vector<std::vector<double>>& a,
                                        const std::vector<std::vector<double>>& b) {
    const size_t n = a.size();
    std::vector<std::vector<double>> c(n, std::vector<double>(n, 0.0));
    for (size_t i = 0; i < n; ++i)
        for (size_t k = 0; k < n; ++k)
            for (size_t j = 0; j < n; ++j) c[i][j] += a[i][k] * b[k][j];
    return c;
}

}  // namespace

Symbol symbolOf(const Scheme& s) {
    const int m = s.arity;
    int lo = 1 << 30, hi = -(1 << 30);
    for (int r = 0; r < m; ++r)
        for (size_t idx = 0; idx < s.rules[r].weights.size(); ++idx) {
            const int k = r - m * (s.rules[r].offset + static_cast<int>(idx));
            lo = std::min(lo, k);
            hi = std::max(hi, k);
        }
    Symbol sym{m, lo, std::vector<double>(static_cast<size_t>(hi - lo + 1), 0.0)};
    for (int r = 0; r < m; ++r)
        for (size_t idx = 0; idx < s.rules[r].weights.size(); ++idx) {
            const int k = r - m * (s.rules[r].offset + static_cast<int>(idx));
            sym.coeffs[static_cast<size_t>(k - lo)] = s.rules[r].weights[idx];
        }
    // Trim zero coefficients at both ends (e.g. lambda = 0 in paper 000's scheme).
    while (sym.coeffs.size() > 1 && std::fabs(sym.coeffs.back()) < kTolerance) sym.coeffs.pop_back();
    while (sym.coeffs.size() > 1 && std::fabs(sym.coeffs.front()) < kTolerance) {
        sym.coeffs.erase(sym.coeffs.begin());
        ++sym.first;
    }
    return sym;
}

bool divideBySigma(const Symbol& p, Symbol& q) {
    // Synthetic division by 1 + z + ... + z^{m-1}, from the highest power down.
    const int m = p.arity;
    std::vector<double> rem = p.coeffs;
    const int n = static_cast<int>(rem.size());
    if (n < m) return false;
    std::vector<double> quot(static_cast<size_t>(n - m + 1), 0.0);
    for (int i = n - 1; i >= m - 1; --i) {
        const double c = rem[i];
        quot[static_cast<size_t>(i - (m - 1))] = c;
        for (int j = 0; j < m; ++j) rem[i - j] -= c;
    }
    double scale = 0;
    for (double v : p.coeffs) scale = std::max(scale, std::fabs(v));
    for (int i = 0; i < m - 1; ++i)
        if (std::fabs(rem[i]) > 1e-10 * std::max(scale, 1.0)) return false;
    q = {m, p.first, std::move(quot)};
    return true;
}

double iteratedNorm(const Symbol& b, int L) {
    const int m = b.arity;
    std::vector<double> prod = b.coeffs;
    long long stride = 1;
    for (int l = 1; l < L; ++l) {
        stride *= m;
        // prod(z) * b(z^stride), touching only b's nonzero terms.
        std::vector<double> next(prod.size() + (b.coeffs.size() - 1) * static_cast<size_t>(stride), 0.0);
        for (size_t j = 0; j < b.coeffs.size(); ++j) {
            const double bj = b.coeffs[j];
            if (bj == 0.0) continue;
            double* out = next.data() + j * static_cast<size_t>(stride);
            for (size_t i = 0; i < prod.size(); ++i) out[i] += bj * prod[i];
        }
        prod = std::move(next);
    }
    const long long period = stride * m;
    std::vector<double> sums(static_cast<size_t>(period), 0.0);
    // Residues are taken of the true exponent (first * (1 + m + ... )), which
    // only permutes the classes: the maximum is unchanged.
    for (size_t i = 0; i < prod.size(); ++i) sums[i % static_cast<size_t>(period)] += std::fabs(prod[i]);
    return *std::max_element(sums.begin(), sums.end());
}

SchemeReport analyzeScheme(const Scheme& scheme, int maxL) {
    SchemeReport rep;
    const int m = scheme.arity;
    rep.symbol = symbolOf(scheme);
    rep.ghostsBefore = scheme.ghostsBefore();
    rep.ghostsAfter = scheme.ghostsAfter();
    if (maxL <= 0) maxL = m == 2 ? 14 : 9;  // iterated symbols of ~1e5 coefficients

    rep.sumRules = true;
    for (const Rule& r : scheme.rules)
        if (std::fabs(std::accumulate(r.weights.begin(), r.weights.end(), 0.0) - 1) > 1e-9)
            rep.sumRules = false;

    // Interpolating: child position 0 is the old point itself.
    {
        const Symbol& a = rep.symbol;
        rep.interpolating = true;
        for (size_t i = 0; i < a.coeffs.size(); ++i) {
            const int k = a.first + static_cast<int>(i);
            if (k % m != 0) continue;
            const double want = k == 0 ? 1.0 : 0.0;
            if (std::fabs(a.coeffs[i] - want) > 1e-12) rep.interpolating = false;
        }
    }
    rep.supportWidth = static_cast<double>(rep.symbol.coeffs.size() - 1) / (m - 1);

    // Polynomial reproduction in the primal parameterisation: data t^p at the
    // integers must come out as t^p at i + r/m.
    for (int p = 0; p <= 9; ++p) {
        bool ok = true;
        for (int r = 0; r < m && ok; ++r) {
            const Rule& rule = scheme.rules[r];
            for (int i = -3; i <= 3 && ok; ++i) {
                double v = 0;
                for (size_t j = 0; j < rule.weights.size(); ++j)
                    v += rule.weights[j] * std::pow(i + rule.offset + static_cast<int>(j), p);
                const double want = std::pow(i + static_cast<double>(r) / m, p);
                if (std::fabs(v - want) > 1e-9 * std::max(1.0, std::pow(6.0, p))) ok = false;
            }
        }
        if (!ok) break;
        rep.reproductionDegree = p;
    }

    // Factor sigma out as often as it divides.
    std::vector<Symbol> quotients;  // quotients[k] = a / sigma^(k+1)
    Symbol cur = rep.symbol;
    Symbol q;
    while (quotients.size() < 12 && divideBySigma(cur, q)) {
        quotients.push_back(q);
        cur = q;
    }
    rep.generationDegree = static_cast<int>(quotients.size()) - 1;

    for (int k = 0; k < static_cast<int>(quotients.size()); ++k) {
        Symbol b = quotients[k];
        for (double& c : b.coeffs) c *= std::pow(m, k);
        DifferenceTest t{k, true};
        double bestRoot = 1e300;
        for (int L = 1; L <= maxL; ++L) {
            const double norm = iteratedNorm(b, L);
            if (L == 1) t.normAtL1 = norm;
            bestRoot = std::min(bestRoot, std::pow(norm, 1.0 / L));
            if (norm < 1 - 1e-12 && t.provedAtL == 0) t.provedAtL = L;
            if (t.provedAtL && L >= t.provedAtL + 4) break;
        }
        t.bestNormRoot = bestRoot;
        rep.tests.push_back(t);
        if (t.provedAtL > 0 && rep.smoothness == k - 1) rep.smoothness = k;
        if (t.normAtL1 < 1 - 1e-12 && rep.smoothnessByPaperTest == k - 1)
            rep.smoothnessByPaperTest = k;
    }

    // Hölder exponent at the certified level k (or at k = 0 when nothing is proven).
    const int k = std::max(rep.smoothness, 0);
    if (k < static_cast<int>(rep.tests.size())) {
        rep.holderLower = k - std::log(rep.tests[k].bestNormRoot) / std::log(m);
        Symbol b = quotients[k];
        for (double& c : b.coeffs) c *= std::pow(m, k);
        const auto mats = subdivisionMatrices(b);
        double rho = 0;
        for (const auto& t : mats) rho = std::max(rho, spectralRadius(t));
        for (const auto& a : mats)
            for (const auto& c : mats) rho = std::max(rho, std::sqrt(spectralRadius(matmul(a, c))));
        rep.holder = rho > 0 ? k - std::log(rho) / std::log(m) : rep.holderLower;
        rep.holder = std::max(rep.holder, rep.holderLower);
    }
    return rep;
}

}  // namespace relief::subdiv

#include <fmt/format.h>

#include "core/number_format.h"

namespace relief::subdiv {

std::vector<std::string> explainReport(const SchemeReport& rep, const std::string& family,
                                       const std::map<std::string, double>& p) {
    std::vector<std::string> notes;
    if (const SchemeFamily* row = findSchemeFamily(family); row && row->paperConditions)
        notes = row->paperConditions(p, rep.smoothness);
    if (rep.smoothness > rep.smoothnessByPaperTest)
        notes.push_back(fmt::format(
            "the papers' one-step test (L = 1) proves {}; the certificate needs L = {} to prove C{}",
            rep.smoothnessByPaperTest < 0 ? std::string("nothing")
                                          : fmt::format("C{}", rep.smoothnessByPaperTest),
            rep.tests[rep.smoothness].provedAtL, rep.smoothness));
    if (rep.smoothness < 0)
        notes.push_back("convergence is not proven: the refined surface will look rough and "
                        "fractal-like, and may not settle as the depth grows");
    else if (rep.smoothness == 0)
        notes.push_back(fmt::format("only C0 (Hölder ~{:.2f}): rough, fractal-like terrain, as "
                                    "paper 001 notes for its sharp example",
                                    rep.holder));
    return notes;
}

std::string certifiedClass(const SchemeReport& r) {
    return r.smoothness < 0 ? fmt::format("convergence not proven (Hölder ~{:.2f})", r.holder)
                            : fmt::format("C{} (Hölder ~{:.2f})", r.smoothness, r.holder);
}

}  // namespace relief::subdiv
