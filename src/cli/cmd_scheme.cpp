#include "cli/cli_common.h"

// relief check, relief curve: what a scheme gives, and refined curves drawn.
#include <iostream>
#include <memory>
#include <optional>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "core/atomic_file.h"
#include "core/number_format.h"
#include "curves/curve_file.h"
#include "figures/curve_figure.h"
#include "pipeline/surface.h"
#include "subdiv/analysis.h"
#include "subdiv/resolve.h"
#include "subdiv/refine.h"

namespace relief::cli {

namespace {

struct CheckOptions {
    std::string scheme;
    std::string preset;
    std::vector<std::string> params;
    bool json = false;
    bool list = false;
};

std::string weightList(const std::vector<double>& w) {
    std::string out;
    for (double v : w) out += (out.empty() ? "" : ", ") + relief::formatShortest(v == 0 ? 0.0 : v);
    return out;
}


// --scheme / --preset / --param, as on the command line of check and curve:
// the spec resolveScheme takes, each key located at its option.
relief::scene::SchemeSpec schemeSpec(const std::string& schemeName, const std::string& presetName,
                                     const std::map<std::string, double>& params) {
    relief::scene::SchemeSpec spec;
    spec.name = schemeName;
    spec.preset = presetName;
    spec.params = params;
    spec.allowNonconvergent = true;  // what the scheme gives is the answer, not a warning
    spec.locs.keys["subdivision.scheme"] = {"--scheme", 0, 0};
    spec.locs.keys["subdivision.preset"] = {"--preset", 0, 0};
    for (const auto& [k, v] : params) spec.locs.keys["subdivision." + k] = {"--param " + k, 0, 0};
    return spec;
}

std::optional<relief::subdiv::ResolvedScheme> resolveScheme(const std::string& schemeName,
                                                            const std::string& presetName,
                                                            const std::map<std::string, double>& params) {
    relief::Diagnostics diags;
    auto resolved = relief::subdiv::resolveScheme(schemeSpec(schemeName, presetName, params), diags);
    printDiagnostics(diags, false);  // errors, or warnings (caveats)
    return resolved;
}

// `relief check`: what a scheme and its parameters give.
int runCheck(const CheckOptions& o) {
    std::map<std::string, double> params;
    if (!parseParams(o.params, params)) return code(Exit::BadInput);
    if (o.list) {
        std::cout << relief::subdiv::schemeTableMarkdown();
        return code(Exit::Ok);
    }
    auto resolved = resolveScheme(o.scheme, o.preset, params);
    if (!resolved) return code(Exit::BadInput);
    const std::string& family = resolved->family;
    const relief::subdiv::Scheme* scheme = &resolved->scheme;
    const std::map<std::string, double>& resolvedParams = resolved->params;
    const auto& rep = resolved->report;
    const auto notes = relief::subdiv::explainReport(rep, family, resolvedParams);

    if (o.json) {
        nlohmann::ordered_json j;
        j["scheme"] = family;
        if (!o.preset.empty()) j["preset"] = o.preset;
        j["parameters"] = resolvedParams;
        j["arity"] = scheme->arity;
        nlohmann::ordered_json rules = nlohmann::ordered_json::array();
        for (const auto& r : scheme->rules)
            rules.push_back({{"offset", r.offset}, {"weights", r.weights}});
        j["rules"] = rules;
        j["symbol"] = {{"first_power", rep.symbol.first}, {"coefficients", rep.symbol.coeffs}};
        j["sum_rules"] = rep.sumRules;
        j["interpolating"] = rep.interpolating;
        j["support_width"] = rep.supportWidth;
        j["reproduction_degree"] = rep.reproductionDegree;
        j["generation_degree"] = rep.generationDegree;
        j["ghost_points"] = {{"before", rep.ghostsBefore}, {"after", rep.ghostsAfter}};
        j["smoothness"] = rep.smoothness;
        j["smoothness_by_paper_test"] = rep.smoothnessByPaperTest;
        j["holder"] = rep.holder;
        j["holder_lower_bound"] = rep.holderLower;
        nlohmann::ordered_json tests = nlohmann::ordered_json::array();
        for (const auto& t : rep.tests)
            tests.push_back({{"k", t.k}, {"proved_at_L", t.provedAtL}, {"norm_L1", t.normAtL1},
                             {"best_norm_root", t.bestNormRoot}});
        j["difference_tests"] = tests;
        j["notes"] = notes;
        std::cout << j.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) << '\n';
        return code(Exit::Ok);
    }
    std::cout << fmt::format("scheme {}{}: arity {}\n", family,
                             o.preset.empty() ? "" : " (preset " + o.preset + ")", scheme->arity);
    std::string p;
    for (const auto& [k, v] : resolvedParams) p += fmt::format("{}{} = {}", p.empty() ? "" : ", ", k, relief::formatShortest(v));
    if (!p.empty()) std::cout << "  parameters: " << p << '\n';
    for (size_t r = 0; r < scheme->rules.size(); ++r)
        std::cout << fmt::format("  P'[{}i+{}] = ({}) . P[i{:+d} ...]\n", scheme->arity, r,
                                 weightList(scheme->rules[r].weights), scheme->rules[r].offset);
    std::cout << fmt::format("  symbol a(z): z^{} * ({})\n", rep.symbol.first, weightList(rep.symbol.coeffs));
    std::cout << fmt::format("  sum rules: {}\n", rep.sumRules ? "hold (every child position sums to 1)" : "FAIL");
    std::cout << fmt::format("  {}; support width {} intervals; reproduces polynomials of degree {}; "
                             "generates degree {}\n",
                             rep.interpolating ? "interpolating" : "approximating",
                             relief::formatShortest(rep.supportWidth), rep.reproductionDegree,
                             rep.generationDegree);
    std::cout << fmt::format("  ghost points per side: {} before, {} after\n", rep.ghostsBefore, rep.ghostsAfter);
    for (const auto& t : rep.tests)
        std::cout << fmt::format("  C{} test: one-step norm {:.6f} ({}); {}\n", t.k, t.normAtL1,
                                 t.normAtL1 < 1 ? "< 1, proved by the papers' test" : ">= 1",
                                 t.provedAtL ? fmt::format("proved at L = {}", t.provedAtL)
                                             : std::string("not proved up to the L tried"));
    std::cout << fmt::format("  certified: {}; Hölder exponent ~ {:.3f} (proven lower bound {:.3f})\n",
                             rep.smoothness < 0 ? std::string("convergence not proven")
                                                : fmt::format("C{}", rep.smoothness),
                             rep.holder, rep.holderLower);
    for (const auto& n : notes) std::cout << "  note: " << n << '\n';
    return code(Exit::Ok);
}

struct CurveOptions {
    std::string polygon;
    CheckOptions scheme;
    std::vector<std::string> sets;  ///< one curve per entry: "k=v,k=v"
    std::string vary;               ///< "k=v1,v2,..."
    int depth = 5;
    std::string output;
    std::string points;
    std::string title;
};


// `relief curve`: refine a 2-D control polygon with one or more parameter sets.
int runCurve(const CurveOptions& o) {
    relief::Diagnostics diags;
    auto polygon = relief::curves::readCurveFile(o.polygon, diags);
    if (!polygon) {
        printDiagnostics(diags, false);
        return code(Exit::BadInput);
    }
    std::map<std::string, double> base;
    if (!parseParams(o.scheme.params, base)) return code(Exit::BadInput);

    // The parameter sets: --set entries, or --vary values, or the base alone.
    std::vector<std::map<std::string, double>> sets;
    std::vector<std::string> labels;
    for (const auto& set : o.sets) {
        auto p = base;
        if (!parseParams(split(set, ','), p)) return code(Exit::BadInput);
        sets.push_back(p);
        labels.push_back(set);
    }
    if (!o.vary.empty()) {
        const auto eq = o.vary.find('=');
        if (eq == std::string::npos) {
            std::cerr << "relief: error: --vary KEY=V1,V2,... \n";
            return code(Exit::BadInput);
        }
        const std::string key = o.vary.substr(0, eq);
        for (const auto& v : split(o.vary.substr(eq + 1), ',')) {
            auto p = base;
            if (!parseParams({key + "=" + v}, p)) return code(Exit::BadInput);
            sets.push_back(p);
            labels.push_back(key + " = " + v);
        }
    }
    if (sets.empty()) {
        sets.push_back(base);
        labels.push_back("");
    }
    std::vector<relief::figures::CurveVariant> variants;
    for (size_t i = 0; i < sets.size(); ++i)
        variants.push_back({labels[i], schemeSpec(o.scheme.scheme, o.scheme.preset, sets[i])});
    const std::string title =
        o.title.empty() ? fmt::format("{} refined {} times", fs::path(o.polygon).filename().string(), o.depth)
                        : o.title;
    const auto figure = relief::figures::curveFigure(*polygon, o.polygon, variants, o.depth, title, diags);
    printDiagnostics(diags, figure.has_value());
    if (!figure) return code(Exit::BadInput);
    const auto& refinedFiles = figure->refined;
    const fs::path svgPath = o.output.empty()
                                 ? fs::path("out") / (fs::path(o.polygon).stem().string() + ".svg")
                                 : fs::path(o.output);
    createParentFolder(svgPath);
    relief::writeFileAtomically(svgPath, figure->svg);
    std::cerr << "wrote " << svgPath.string() << '\n';
    if (!o.points.empty()) {
        for (size_t i = 0; i < refinedFiles.size(); ++i) {
            fs::path p = o.points;
            if (refinedFiles.size() > 1)
                p = p.parent_path() / fmt::format("{}.{}{}", p.stem().string(), i + 1, p.extension().string());
            createParentFolder(p);
            relief::writeFileAtomically(p, relief::curves::curveFileJson(refinedFiles[i]));
            std::cerr << "wrote " << p.string() << " (" << refinedFiles[i].points.size() << " points)\n";
        }
    }
    return code(Exit::Ok);
}

// "dlg4, four-point-4p, ...", from the scheme table.
std::string familyNames() {
    std::string names;
    for (const auto& f : relief::subdiv::schemeFamilies()) names += (names.empty() ? "" : ", ") + f.name;
    return names + " (relief check --list)";
}

}  // namespace

void addSchemeCommands(CLI::App& app, std::vector<Command>& out) {
    auto check = std::make_shared<CheckOptions>();
    CLI::App* checkCmd = app.add_subcommand(
        "check", "what a scheme and its parameters give: mask, interpolation, support, "
                 "reproduction, certified smoothness (difference-scheme test), Hölder estimate");
    checkCmd->add_option("--scheme", check->scheme, familyNames());
    checkCmd->add_option("--preset", check->preset, "a named special case, e.g. hassan, deslauriers-dubuc");
    checkCmd->add_option("--param", check->params, "KEY=VALUE (fractions such as 7/32 allowed); repeatable");
    checkCmd->add_flag("--json", check->json, "one JSON object");
    checkCmd->add_flag("--list", check->list,
                       "the scheme table (families, parameters, presets) as Markdown, as in docs/schemes.md");
    out.push_back({checkCmd, [check] { return runCheck(*check); }});

    auto curve = std::make_shared<CurveOptions>();
    CLI::App* curveCmd = app.add_subcommand(
        "curve", "refine a 2-D control polygon (open or closed) and draw it as SVG; --set or "
                 "--vary draws several parameter sets in one figure");
    curveCmd->add_option("polygon", curve->polygon, "curve file: {\"type\": \"polyline\", \"closed\": "
                                                    "false, \"points\": [[x, y], ...]}")->required();
    curveCmd->add_option("--scheme", curve->scheme.scheme, "scheme name (see relief check)");
    curveCmd->add_option("--preset", curve->scheme.preset, "a named special case");
    curveCmd->add_option("--param", curve->scheme.params, "KEY=VALUE for every curve; repeatable");
    curveCmd->add_option("--set", curve->sets, "one curve's parameters: \"k=v,k=v\"; repeatable");
    curveCmd->add_option("--vary", curve->vary, "KEY=V1,V2,...: one curve per value");
    curveCmd->add_option("--depth", curve->depth, "refinement levels")->check(CLI::Range(0, 12));
    curveCmd->add_option("-o,--output", curve->output, "SVG to write (default out/<polygon>.svg)");
    curveCmd->add_option("--points", curve->points, "also write the refined points as curve files");
    curveCmd->add_option("--title", curve->title, "figure title");
    out.push_back({curveCmd, [curve] { return runCurve(*curve); }});
}

}  // namespace relief::cli
