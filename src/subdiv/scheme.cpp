#include "subdiv/scheme.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "core/number_format.h"
#include "core/text_distance.h"

namespace relief::subdiv {

int Scheme::ghostsBefore() const {
    int g = 0;
    for (const Rule& rule : rules) g = std::max(g, -rule.offset);
    return g;
}

int Scheme::ghostsAfter() const {
    // Child position 0 exists for the last coarse point i = n-1; the others
    // only up to i = n-2.
    int g = 0;
    for (size_t r = 0; r < rules.size(); ++r) {
        const int last = rules[r].offset + static_cast<int>(rules[r].weights.size()) - 1;
        g = std::max(g, last - (r == 0 ? 0 : 1));
    }
    return g;
}

Scheme dlgFourPoint(double w) {
    return {"dlg4", 2, {{0, {1.0}}, {-1, {-w, 0.5 + w, 0.5 + w, -w}}},
            Boundary::PointReflection};
}

Scheme fourPoint4p(double lambda, double mu, double nu, double omega) {
    // Paper 001, eq. (1), expanded (schemes.md): d_i = P_i - [nu P_{i-1} + (1-nu) P_{i+1}].
    const double a = 2 * omega * nu, b = 2 * omega * (1 - nu);
    return {"four-point-4p",
            2,
            {{-1, {lambda, 1 - lambda - mu, mu}}, {-1, {-a, 0.5 + b, 0.5 + a, -b}}},
            Boundary::PointReflection};
}

Scheme binary3p(double lambda, double mu, double omega) {
    // Paper 000, Definition 2. Note its sign: the classic 4-point is omega = -w.
    return {"binary-3p",
            2,
            {{-2, {lambda, mu, 1 - 2 * mu - 2 * lambda, mu, lambda}},
             {-1, {omega, 0.5 - omega, 0.5 - omega, omega}}},
            Boundary::PointReflection};
}

Scheme ternaryBlend(double alpha, double beta, double gamma) {
    // Paper 004, eq. (3) in the form of schemes.md (OCR fix: Delta p_i = 2p_i - p_{i-1} - p_{i+1}).
    return {"ternary-blend",
            3,
            {{-1, {-alpha, 1 + 2 * alpha, -alpha}},
             {-1, {-beta, 2.0 / 3 + 2 * beta - gamma, 1.0 / 3 - beta + 2 * gamma, -gamma}},
             {-1, {-gamma, 1.0 / 3 - beta + 2 * gamma, 2.0 / 3 + 2 * beta - gamma, -beta}}},
            Boundary::PointReflection};
}

Scheme ternaryFourPoint(double theta) {
    // Paper 004's 4-point ternary interpolating scheme (OCR fix: the second rule is
    // the mirror of the first).
    const double a = -theta / 9, b = 5.0 / 9 + theta / 3, c = 5.0 / 9 - theta / 3,
                 d = -1.0 / 9 + theta / 9;
    return {"ternary-4point",
            3,
            {{0, {1.0}}, {-1, {a, b, c, d}}, {-1, {d, c, b, a}}},
            Boundary::PointReflection};
}

Scheme ternaryBSpline(double eta) {
    // Paper 004's parametric cubic B-spline ternary scheme (eta = 1/27: cubic B-spline).
    return {"ternary-bspline",
            3,
            {{-1, {1.0 / 9 + eta, 7.0 / 9 - 2 * eta, 1.0 / 9 + eta}},
             {-1, {eta, 2.0 / 3 - 2 * eta, 1.0 / 3 + eta}},
             {0, {1.0 / 3 + eta, 2.0 / 3 - 2 * eta, eta}}},
            Boundary::PointReflection};
}

namespace {
bool near(double a, double b) { return std::fabs(a - b) < 1e-12; }
const char* holds(bool b) { return b ? "holds" : "fails"; }

// Paper 004's condition "C2 for lo < param < hi" (`range` as the paper writes it).
auto paper004C2Between(std::string param, double lo, double hi, std::string range) {
    return [=](const SchemeParams& p, int) {
        const double v = p.at(param);
        return std::vector<std::string>{
            fmt::format("paper 004: C2 for {}: {}", range, holds(v > lo && v < hi))};
    };
}
}  // namespace

const std::vector<SchemeFamily>& schemeFamilies() {
    static const std::vector<SchemeFamily> families{
        {"dlg4",
         "classic Dyn-Levin-Gregory 4-point interpolating scheme (w = 1/16: C1)",
         "Dyn, Levin and Gregory (1987)",
         {{"w", 1.0 / 16, -1, 1, "tension"}},
         [](const SchemeParams& p) { return dlgFourPoint(p.at("w")); },
         nullptr,
         nullptr},
        {"four-point-4p",
         "four-parameter four-point scheme of paper 001 (lambda = mu = 0, nu = 1/2: classic "
         "4-point with w = omega)",
         "paper 001",
         {{"lambda", 0, 0, 1, "shift of the old point towards its left neighbour"},
          {"mu", 0, 0, 1, "shift of the old point towards its right neighbour"},
          {"nu", 0.5, 0, 1, "offset parameter of d_i"},
          {"omega", 1.0 / 16, -1, 1, "tension"}},
         [](const SchemeParams& p) {
             return fourPoint4p(p.at("lambda"), p.at("mu"), p.at("nu"), p.at("omega"));
         },
         [](const SchemeParams& p) {
             std::vector<std::string> w;
             if (p.at("lambda") != p.at("mu") || p.at("nu") != 0.5)
                 w.push_back(fmt::format(
                     "four-point-4p with lambda = {}, mu = {}, nu = {} is not symmetric: the "
                     "surface shifts by about (mu - lambda) of a net cell per level and the net's "
                     "edges drift; for terrain use lambda = mu and nu = 1/2",
                     formatShortest(p.at("lambda")), formatShortest(p.at("mu")),
                     formatShortest(p.at("nu"))));
             if (p.at("lambda") + p.at("mu") > 1)
                 w.push_back("four-point-4p: lambda + mu > 1 is outside the paper's range "
                             "0 < lambda + mu <= 1");
             return w;
         },
         [](const SchemeParams& p, int smoothness) {
             // Each theorem pairs an equality (sigma^(k+1) divides the symbol)
             // with a one-step norm inequality; the equalities are reported
             // here, the norm tests in the report's difference tests.
             const double l = p.at("lambda"), mu = p.at("mu"), nu = p.at("nu"), w = p.at("omega");
             const bool c1 = near(mu - l + 4 * w - 8 * w * nu, 0);
             const bool c2 = c1 && near(l, 1.0 / 8 - 4 * w * nu);
             std::vector<std::string> notes{fmt::format(
                 "paper 001, Theorem 2 (C1) equality mu - lambda + 4 omega - 8 omega nu = 0: {}; "
                 "Theorem 3 (C2) equality lambda = 1/8 - 4 omega nu: {}",
                 holds(c1), holds(c2))};
             if (near(l, 1.0 / 80) && near(mu, 1.0 / 16) && near(nu, 0.5) && near(w, 1.0 / 32))
                 notes.push_back(fmt::format("paper 001 Fig. 2(b)'s caption says C2, but its printed "
                                             "parameters give only C{}; lambda = mu = 1/16 (same "
                                             "omega) is C2 and is almost certainly what was meant",
                                             smoothness));
             if (!near(l, mu) || !near(nu, 0.5))
                 notes.push_back("not symmetric (lambda != mu or nu != 1/2): the limit shifts by "
                                 "about (mu - lambda) of an interval per level");
             return notes;
         }},
        {"binary-3p",
         "three-parameter binary 9-point scheme of paper 000 (lambda = mu = 0, omega = -1/16: "
         "classic 4-point; omega = 4 lambda + 1/32, mu = 4 lambda + 3/16: C4)",
         "paper 000",
         {{"lambda", 0, -1, 1, "weight of the second neighbours of an old point"},
          {"mu", 0, -1, 1, "weight of the first neighbours of an old point"},
          {"omega", -1.0 / 16, -1, 1, "outer weight of the new point (sign opposite paper 001)"}},
         [](const SchemeParams& p) {
             return binary3p(p.at("lambda"), p.at("mu"), p.at("omega"));
         },
         nullptr,
         [](const SchemeParams& p, int smoothness) {
             const double l = p.at("lambda"), mu = p.at("mu"), w = p.at("omega");
             const bool c2 = near(4 * l - 2 * w + mu, 1.0 / 8);
             const bool c4 = near(w, 4 * l + 1.0 / 32) && near(mu, 4 * l + 3.0 / 16);
             std::vector<std::string> notes{fmt::format(
                 "paper 000, Theorem 3 (C2 family) 4 lambda - 2 omega + mu = 1/8: {}; Theorem 4 "
                 "(C4) omega = 4 lambda + 1/32, mu = 4 lambda + 3/16, -1/64 < lambda < 3/64: {}",
                 holds(c2), holds(c4 && l > -1.0 / 64 && l < 3.0 / 64))};
             if (c4 && smoothness > 4)
                 notes.push_back(fmt::format(
                     "the certificate proves C{} here, more than Theorem 4's C4", smoothness));
             if (near(l, 0) && near(mu, 0) && near(w, 1.0 / 16))
                 notes.push_back("omega = +1/16 is not the classic 4-point in this paper's sign "
                                 "convention (that is omega = -1/16)");
             return notes;
         }},
        {"ternary-blend",
         "ternary blending scheme of paper 004 (interpolating when alpha = 0; presets for its "
         "special cases)",
         "paper 004",
         {{"alpha", 0, -1, 1, "weight of the neighbours of an old point"},
          {"beta", 5.0 / 81, -1, 1, "outer weight next to the old point"},
          {"gamma", 4.0 / 81, -1, 1, "outer weight on the far side"}},
         [](const SchemeParams& p) {
             return ternaryBlend(p.at("alpha"), p.at("beta"), p.at("gamma"));
         },
         nullptr,
         [](const SchemeParams& p, int) {
             const double a = p.at("alpha"), b = p.at("beta"), g = p.at("gamma");
             const bool c2 = near(g, a - b + 1.0 / 9);
             const bool c3 = c2 && near(b, 5.0 / 81 + 2 * a / 3) && a > -7.0 / 27 && a < -4.0 / 27;
             return std::vector<std::string>{fmt::format(
                 "paper 004: C2 equality gamma = alpha - beta + 1/9: {}; C3 equalities, also beta "
                 "= 5/81 + 2 alpha/3 with -7/27 < alpha < -4/27: {}",
                 holds(c2), holds(c3))};
         }},
        {"ternary-4point",
         "4-point ternary interpolating scheme of paper 004 (C2 for 3/5 < theta < 2/3; the "
         "1-9 interpolating surface)",
         "paper 004",
         {{"theta", 19.0 / 30, -3, 3, "shape parameter"}},
         [](const SchemeParams& p) { return ternaryFourPoint(p.at("theta")); },
         nullptr,
         paper004C2Between("theta", 0.6, 2.0 / 3, "3/5 < theta < 2/3")},
        {"ternary-bspline",
         "parametric cubic B-spline ternary scheme of paper 004 (eta = 1/27: cubic B-spline; C2 "
         "for 0 < eta < 1/9)",
         "paper 004",
         {{"eta", 1.0 / 27, -1, 1, "shape parameter"}},
         [](const SchemeParams& p) { return ternaryBSpline(p.at("eta")); },
         nullptr,
         paper004C2Between("eta", 0, 1.0 / 9, "0 < eta < 1/9")},
    };
    return families;
}

const std::vector<Preset>& presets() {
    using Params = std::map<std::string, double>;
    auto fixed = [](Params p) { return [p](const Params&) { return p; }; };
    static const std::vector<Preset> list{
        {"classic-4point", "Dyn-Levin-Gregory 4-point, w = 1/16", "dlg4", {},
         fixed({{"w", 1.0 / 16}})},
        {"quintic-bspline", "paper 000, Theorem 4 with lambda = 0: the quintic B-spline",
         "binary-3p", {}, fixed({{"lambda", 0}, {"mu", 3.0 / 16}, {"omega", 1.0 / 32}})},
        {"deslauriers-dubuc", "Deslauriers-Dubuc ternary 4-point interpolating scheme",
         "ternary-blend", {}, fixed({{"alpha", 0}, {"beta", 5.0 / 81}, {"gamma", 4.0 / 81}})},
        {"hassan", "Hassan's ternary 4-point interpolating scheme (parameter mu)", "ternary-blend",
         {{"mu", 1.0 / 11, -1, 1, "Hassan's shape parameter"}},
         [](const Params& p) {
             const double mu = p.at("mu");
             return Params{{"alpha", 0}, {"beta", 1.0 / 18 + mu / 6}, {"gamma", 1.0 / 18 - mu / 6}};
         }},
        {"ternary-bspline-1", "ternary linear B-spline (the control polygon itself)",
         "ternary-blend", {}, fixed({{"alpha", 0}, {"beta", 0}, {"gamma", 0}})},
        {"ternary-bspline-2", "ternary quadratic B-spline", "ternary-blend", {},
         fixed({{"alpha", -1.0 / 9}, {"beta", 0}, {"gamma", 0}})},
        {"ternary-bspline-3", "ternary cubic B-spline", "ternary-blend", {},
         fixed({{"alpha", -4.0 / 27}, {"beta", -1.0 / 27}, {"gamma", 0}})},
        {"ternary-bspline-4", "ternary quartic B-spline", "ternary-blend", {},
         fixed({{"alpha", -5.0 / 27}, {"beta", -5.0 / 81}, {"gamma", -1.0 / 81}})},
        {"one-nine-surface", "paper 004's 1-9 interpolating surface: ternary 4-point, theta = 19/30",
         "ternary-4point", {}, fixed({{"theta", 19.0 / 30}})},
        {"gentle-mountains", "paper 001, terrain example 1", "four-point-4p", {},
         fixed({{"lambda", 7.0 / 32}, {"mu", 7.0 / 32}, {"nu", 0.5}, {"omega", 3.0 / 64}})},
        {"sharp-mountains", "paper 001, terrain example 2", "four-point-4p", {},
         fixed({{"lambda", 1.0 / 30}, {"mu", 1.0 / 30}, {"nu", 0.5}, {"omega", 1.0 / 3}})},
    };
    return list;
}

const Preset* findPreset(const std::string& name) {
    for (const auto& p : presets())
        if (p.name == name) return &p;
    return nullptr;
}

std::optional<Scheme> schemeFromMask(int arity, int first, const std::vector<double>& mask,
                                     const SourceLoc& loc, Diagnostics& diags) {
    if (arity != 2 && arity != 3) {
        diags.error(loc, fmt::format("mask arity = {} is not supported; use 2 (binary) or 3 "
                                     "(ternary)", arity));
        return std::nullopt;
    }
    if (mask.empty()) {
        diags.error(loc, "the mask is empty; give its coefficients a_k as a list of numbers");
        return std::nullopt;
    }
    Scheme s;
    s.name = "mask";
    s.arity = arity;
    const int last = first + static_cast<int>(mask.size()) - 1;
    for (int r = 0; r < arity; ++r) {
        // Coefficient a_{r - m J} multiplies P_{i+J}: J runs over the l with first <= r - m J <= last.
        const int jMin = static_cast<int>(std::ceil(static_cast<double>(r - last) / arity));
        const int jMax = static_cast<int>(std::floor(static_cast<double>(r - first) / arity));
        Rule rule{jMin, {}};
        double sum = 0;
        for (int j = jMin; j <= jMax; ++j) {
            const double w = mask[static_cast<size_t>(r - arity * j - first)];
            rule.weights.push_back(w);
            sum += w;
        }
        if (rule.weights.empty() || std::fabs(sum - 1) > 1e-9) {
            diags.error(loc, fmt::format("mask: the weights of child position {} sum to {}, not "
                                         "1; every position must (the sum rule), or the scheme "
                                         "cannot converge",
                                         r, formatShortest(sum)));
            return std::nullopt;
        }
        s.rules.push_back(std::move(rule));
    }
    return s;
}

const SchemeFamily* findSchemeFamily(const std::string& name) {
    for (const auto& f : schemeFamilies())
        if (f.name == name) return &f;
    return nullptr;
}

std::string schemeTableMarkdown() {
    auto range = [](const ParamSpec& p) {
        return fmt::format("{} = {} in [{}, {}]", p.name, formatShortest(p.defaultValue),
                           formatShortest(p.lo), formatShortest(p.hi));
    };
    std::string out = "| scheme | source | parameters (default, range) | what it is |\n|---|---|---|---|\n";
    for (const auto& f : schemeFamilies()) {
        std::string params;
        for (const auto& p : f.params) params += (params.empty() ? "" : "; ") + range(p);
        out += fmt::format("| `{}` | {} | {} | {} |\n", f.name, f.source, params, f.description);
    }
    out += "| `mask` | your own | `arity` (2 or 3), `mask` = [a_k, ...], `mask_first` | any "
           "binary or ternary scheme from its symbol's coefficients |\n";
    out += "\n| preset | scheme | own parameters (default, range) | what it is |\n|---|---|---|---|\n";
    for (const auto& p : presets()) {
        std::string params;
        for (const auto& q : p.params) params += (params.empty() ? "" : "; ") + range(q);
        out += fmt::format("| `{}` | `{}` | {} | {} |\n", p.name, p.family,
                           params.empty() ? "none" : params, p.description);
    }
    return out;
}

}  // namespace relief::subdiv
