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

const std::vector<SchemeFamily>& schemeFamilies() {
    static const std::vector<SchemeFamily> families{
        {"dlg4",
         "classic Dyn-Levin-Gregory 4-point interpolating scheme (w = 1/16: C1)",
         {{"w", 1.0 / 16, -1, 1, "tension"}},
         [](const std::map<std::string, double>& p) { return dlgFourPoint(p.at("w")); },
         nullptr},
        {"four-point-4p",
         "four-parameter four-point scheme of paper 001 (lambda = mu = 0, nu = 1/2: classic "
         "4-point with w = omega)",
         {{"lambda", 0, 0, 1, "shift of the old point towards its left neighbour"},
          {"mu", 0, 0, 1, "shift of the old point towards its right neighbour"},
          {"nu", 0.5, 0, 1, "offset parameter of d_i"},
          {"omega", 1.0 / 16, -1, 1, "tension"}},
         [](const std::map<std::string, double>& p) {
             return fourPoint4p(p.at("lambda"), p.at("mu"), p.at("nu"), p.at("omega"));
         },
         [](const std::map<std::string, double>& p) {
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
         }},
        {"binary-3p",
         "three-parameter binary 9-point scheme of paper 000 (lambda = mu = 0, omega = -1/16: "
         "classic 4-point; omega = 4 lambda + 1/32, mu = 4 lambda + 3/16: C4)",
         {{"lambda", 0, -1, 1, "weight of the second neighbours of an old point"},
          {"mu", 0, -1, 1, "weight of the first neighbours of an old point"},
          {"omega", -1.0 / 16, -1, 1, "outer weight of the new point (sign opposite paper 001)"}},
         [](const std::map<std::string, double>& p) {
             return binary3p(p.at("lambda"), p.at("mu"), p.at("omega"));
         },
         nullptr},
    };
    return families;
}

const SchemeFamily* findSchemeFamily(const std::string& name) {
    for (const auto& f : schemeFamilies())
        if (f.name == name) return &f;
    return nullptr;
}

std::optional<Scheme> makeScheme(const std::string& name, const SourceLoc& nameLoc,
                                 const std::map<std::string, double>& params,
                                 const std::map<std::string, SourceLoc>& paramLocs,
                                 Diagnostics& diags,
                                 std::map<std::string, double>* resolvedParams) {
    const SchemeFamily* family = findSchemeFamily(name);
    if (!family) {
        std::vector<std::string> names;
        std::string list;
        for (const auto& f : schemeFamilies()) {
            names.push_back(f.name);
            list += (list.empty() ? "" : ", ") + ("\"" + f.name + "\"");
        }
        const std::string best = closestMatch(name, names);
        diags.error(nameLoc, fmt::format("unknown subdivision scheme \"{}\"{}; known: {}", name,
                                         best.empty() ? "" : " (did you mean \"" + best + "\"?)",
                                         list));
        return std::nullopt;
    }
    auto locOf = [&](const std::string& key) {
        auto it = paramLocs.find(key);
        return it == paramLocs.end() ? nameLoc : it->second;
    };
    std::vector<std::string> paramNames;
    for (const auto& p : family->params) paramNames.push_back(p.name);

    bool ok = true;
    for (const auto& [key, value] : params) {
        if (std::find(paramNames.begin(), paramNames.end(), key) != paramNames.end()) continue;
        const std::string best = closestMatch(key, paramNames);
        std::string expected;
        for (const auto& n : paramNames) expected += (expected.empty() ? "" : ", ") + n;
        diags.error(locOf(key),
                    fmt::format("unknown parameter \"{}\" for scheme \"{}\"{}; it takes: {}", key,
                                name, best.empty() ? "" : " (did you mean \"" + best + "\"?)",
                                expected));
        ok = false;
    }
    std::map<std::string, double> resolved;
    for (const auto& spec : family->params) {
        auto it = params.find(spec.name);
        const double v = it == params.end() ? spec.defaultValue : it->second;
        if (!(v >= spec.lo && v <= spec.hi)) {
            diags.error(locOf(spec.name),
                        fmt::format("{} = {} is outside [{}, {}] for scheme \"{}\" ({})",
                                    spec.name, formatShortest(v), formatShortest(spec.lo),
                                    formatShortest(spec.hi), name, spec.meaning));
            ok = false;
        }
        resolved[spec.name] = v;
    }
    if (!ok) return std::nullopt;
    if (family->caveats)
        for (auto& w : family->caveats(resolved)) diags.warning(nameLoc, std::move(w));
    if (resolvedParams) *resolvedParams = resolved;
    return family->build(resolved);
}

}  // namespace relief::subdiv
