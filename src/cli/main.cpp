// relief: the command line. The only code that prints or exits; everything
// else is the relief_core library.
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <tuple>
#include <cstdlib>
#include <filesystem>
#include <iostream>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include "core/atomic_file.h"
#include "core/number_format.h"
#include "pipeline.h"
#include "scene/read_scene.h"
#include "subdiv/analysis.h"
#include "subdiv/refine.h"
#include "curves/curve_file.h"
#include "curves/hausdorff.h"
#include "geo/profile.h"
#include "compare/compare_images.h"
#include "regress/regress.h"
#include "figures/sweep.h"
#include <chrono>
#include "emit/svg.h"
#include <nlohmann/json.hpp>
#include "relief/version.h"

namespace fs = std::filesystem;

namespace {

/// Exit codes (also in README.md and `relief --help`).
enum class Exit : int {
    Ok = 0,          ///< success
    Internal = 1,    ///< a bug in relief: please report it
    BadInput = 2,    ///< bad arguments, scene, samples or template; over budget; cannot write
    ToolFailed = 3,  ///< POV-Ray is missing or failed (its own error text is printed)
};

constexpr const char* kExitCodes =
    "Exit codes: 0 success; 1 internal error; 2 bad input (arguments, scene file, samples,\n"
    "template, output budget) or an output that cannot be written; 3 POV-Ray missing or failed.\n"
    "relief diff keeps idiff's: 0 pass, 1 warning, 2 failure, 3 images not comparable,\n"
    "4 file error or bad arguments. relief test: 0 all cases pass, 1 a case failed.";

int code(Exit e) { return static_cast<int>(e); }

void printDiagnostics(const relief::Diagnostics& diags, bool wrote) {
    // In file order, so a user fixes them top to bottom.
    auto sorted = diags.all();
    std::stable_sort(sorted.begin(), sorted.end(), [](const auto& a, const auto& b) {
        return std::tie(a.loc.file, a.loc.line) < std::tie(b.loc.file, b.loc.line);
    });
    for (const auto& d : sorted) std::cerr << relief::formatDiagnostic(d) << '\n';
    if (diags.errorCount() > 0)
        std::cerr << fmt::format("relief: {} error{}, {} warning{}; {}\n", diags.errorCount(),
                                 diags.errorCount() == 1 ? "" : "s", diags.warningCount(),
                                 diags.warningCount() == 1 ? "" : "s",
                                 wrote ? "output may be incomplete" : "nothing written");
}

// Where the templates are: --templates, $RELIEF_TEMPLATES, the installed
// share/relief/templates beside the binary, or the source tree.
fs::path findTemplates(const std::string& option) {
    if (!option.empty()) return option;
    if (const char* env = std::getenv("RELIEF_TEMPLATES")) return env;
    std::error_code ec;
    const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
    if (!ec) {
        const fs::path installed = exe.parent_path().parent_path() / "share/relief/templates";
        if (fs::exists(installed / "scene.pov.in", ec)) return installed;
    }
    return RELIEF_SOURCE_TEMPLATES_DIR;
}

void ensureParent(const fs::path& file) {
    if (file.has_parent_path()) fs::create_directories(file.parent_path());
}

// One status line, rewritten in place on a terminal.
class Progress {
public:
    explicit Progress(bool quiet) : quiet_(quiet), tty_(::isatty(STDERR_FILENO)) {}
    void show(const std::string& line) {
        if (quiet_) return;
        if (tty_) {
            std::cerr << "\r\033[K" << line << std::flush;
            open_ = true;
        } else if (line != last_) {
            // Not a terminal (a log): stage lines, and render progress per 10 %.
            const auto open = line.rfind('(');
            const int pct = open == std::string::npos ? -1 : std::atoi(line.c_str() + open + 1);
            if (pct < 0 || pct / 10 != lastDecile_) std::cerr << line << '\n';
            lastDecile_ = pct < 0 ? -1 : pct / 10;
        }
        last_ = line;
    }
    void done() {
        if (open_) std::cerr << "\r\033[K" << std::flush;
        open_ = false;
    }

private:
    bool quiet_, tty_, open_ = false;
    std::string last_;
    int lastDecile_ = -1;
};

struct CommonOptions {
    std::string scene;
    std::vector<std::string> sets;  ///< section.key=value overrides
    std::string output;
    std::string templates;
    int threads = 0;
    bool quiet = false;
};

// KEY=VALUE strings -> scene overrides (`section.key=value`).
bool parseOverrides(const std::vector<std::string>& list, relief::scene::SceneOverrides& out) {
    for (const auto& kv : list) {
        const auto eq = kv.find('=');
        if (eq == std::string::npos || eq == 0) {
            std::cerr << "relief: error: " << kv << ": write section.key=value, e.g. subdivision.omega=1/32\n";
            return false;
        }
        out.emplace_back(kv.substr(0, eq), kv.substr(eq + 1));
    }
    return true;
}

// `relief compile`: stages 1-4.
int runCompile(const CommonOptions& o, const std::string& dumpNet) {
    relief::Diagnostics diags;
    Progress progress(o.quiet);
    relief::scene::SceneOverrides overrides;
    if (!parseOverrides(o.sets, overrides)) return code(Exit::BadInput);
    progress.show("reading " + o.scene);
    auto loaded = relief::loadScene(o.scene, diags, overrides);
    if (!loaded) {
        progress.done();
        printDiagnostics(diags, false);
        return code(Exit::BadInput);
    }
    relief::OutputPaths paths;
    paths.pov = o.output.empty() ? fs::path("out") / (fs::path(o.scene).stem().string() + ".pov")
                                 : fs::path(o.output);
    paths.sidecar = paths.pov;
    paths.sidecar.replace_extension(".json");
    relief::CompileOptions copts;
    copts.povPath = paths.pov;
    copts.templatesDir = findTemplates(o.templates);
    copts.dumpNetPath = dumpNet;
    copts.threads = o.threads;
    if (!o.quiet)
        std::cerr << fmt::format("scheme {}: {}\n", loaded->schemeFamily,
                                 relief::certifiedClass(loaded->report));
    progress.show(fmt::format("compiling {} ({}, {})", o.scene, loaded->schemeFamily,
                              relief::depthLabel(loaded->scene)));
    ensureParent(paths.pov);
    if (!dumpNet.empty()) ensureParent(dumpNet);
    auto compiled = relief::compileScene(*loaded, copts, diags);
    progress.done();
    if (!compiled) {
        printDiagnostics(diags, false);
        return code(Exit::BadInput);
    }
    printDiagnostics(diags, true);  // warnings only
    if (!o.quiet && compiled->autoDepth)
        std::cerr << relief::autoDepthSummary(*compiled->autoDepth, compiled->scene.toleranceM) << '\n';
    if (!o.quiet)
        std::cerr << fmt::format("wrote {} ({} x {} vertices, {} triangles, {:.1f} MB)\n",
                                 paths.pov.string(), compiled->refinedRows,
                                 compiled->refinedCols,
                                 2LL * (compiled->refinedRows - 1) * (compiled->refinedCols - 1),
                                 compiled->povBytes / 1e6);
    relief::writeFileAtomically(paths.sidecar, relief::sidecarJson(*compiled, paths, nullptr));
    return code(Exit::Ok);
}

// `relief render`: compile, then POV-Ray.
int runRender(const CommonOptions& o, const std::string& dumpNet) {
    relief::Diagnostics diags;
    Progress progress(o.quiet);
    relief::RenderJob job;
    job.scenePath = o.scene;
    if (!parseOverrides(o.sets, job.overrides)) return code(Exit::BadInput);
    job.png = o.output;
    job.templatesDir = findTemplates(o.templates);
    job.dumpNetPath = dumpNet;
    job.threads = o.threads;
    if (!job.png.empty()) ensureParent(job.png);
    auto outcome = relief::renderSceneFile(job, diags, [&](const std::string& line) {
        if (line.rfind("compiling ", 0) == 0 && !o.quiet) {
            progress.done();
        }
        progress.show(line);
    });
    progress.done();
    if (outcome.status == relief::JobStatus::BadInput) {
        printDiagnostics(diags, false);
        return code(Exit::BadInput);
    }
    printDiagnostics(diags, true);  // warnings
    if (outcome.status == relief::JobStatus::ToolFailed) {
        std::cerr << "relief: POV-Ray failed on " << outcome.paths.pov.string() << ":\n"
                  << outcome.render.error << '\n';
        return code(Exit::ToolFailed);
    }
    if (!o.quiet) {
        const auto& c = *outcome.compiled;
        std::cerr << fmt::format("scheme {}: {}\n", outcome.schemeFamily, outcome.certified);
        if (c.autoDepth) std::cerr << relief::autoDepthSummary(*c.autoDepth, c.scene.toleranceM) << '\n';
        std::cerr << fmt::format("wrote {} ({} x {} vertices, {} triangles, {:.1f} MB)\n",
                                 outcome.paths.pov.string(), c.refinedRows, c.refinedCols,
                                 2LL * (c.refinedRows - 1) * (c.refinedCols - 1), c.povBytes / 1e6);
        std::cerr << fmt::format("wrote {} ({} x {}; POV-Ray parse {:.2f} s, trace {:.2f} s)\n",
                                 outcome.paths.png.string(), c.scene.width, c.scene.height,
                                 outcome.render.parseSeconds, outcome.render.traceSeconds);
    }
    return code(Exit::Ok);
}

struct CheckOptions {
    std::string scheme;
    std::string preset;
    std::vector<std::string> params;
    bool json = false;
};

std::string weightList(const std::vector<double>& w) {
    std::string out;
    for (double v : w) out += (out.empty() ? "" : ", ") + relief::formatShortest(v == 0 ? 0.0 : v);
    return out;
}

// KEY=VALUE list (values may be fractions) -> map; false with a message on bad input.
bool parseParams(const std::vector<std::string>& list, std::map<std::string, double>& out) {
    for (const auto& kv : list) {
        const auto eq = kv.find('=');
        const auto value = eq == std::string::npos
                               ? std::nullopt
                               : relief::scene::parseFraction(kv.substr(eq + 1));
        if (!value) {
            std::cerr << "relief: error: " << kv
                      << ": write KEY=VALUE, the value a number or a fraction such as 7/32\n";
            return false;
        }
        out[kv.substr(0, eq)] = *value;
    }
    return true;
}

struct ResolvedScheme {
    std::string family;
    relief::subdiv::Scheme scheme;
    std::map<std::string, double> params;  ///< every parameter, defaults filled in
};

// --scheme / --preset / --param, as on the command line of check and curve.
std::optional<ResolvedScheme> resolveScheme(const std::string& schemeName,
                                            const std::string& presetName,
                                            std::map<std::string, double> params) {
    relief::Diagnostics diags;
    std::map<std::string, relief::SourceLoc> locs;
    for (const auto& [k, v] : params) locs[k] = {"--param " + k, 0, 0};
    ResolvedScheme out;
    out.family = schemeName;
    if (!presetName.empty()) {
        std::map<std::string, double> familyParams;
        if (!relief::subdiv::resolvePreset(presetName, {"--preset", 0, 0}, params, locs, diags,
                                           out.family, familyParams)) {
            printDiagnostics(diags, false);
            return std::nullopt;
        }
        if (!schemeName.empty() && schemeName != out.family) {
            std::cerr << fmt::format("relief: error: preset \"{}\" belongs to scheme \"{}\", not "
                                     "\"{}\"\n",
                                     presetName, out.family, schemeName);
            return std::nullopt;
        }
        params = familyParams;
        locs.clear();
    } else if (schemeName.empty()) {
        std::cerr << "relief: error: give --scheme NAME or --preset NAME\n";
        return std::nullopt;
    }
    auto scheme = relief::subdiv::makeScheme(out.family, {"--scheme", 0, 0}, params, locs, diags,
                                             &out.params);
    if (!scheme) {
        printDiagnostics(diags, false);
        return std::nullopt;
    }
    printDiagnostics(diags, false);  // warnings
    out.scheme = std::move(*scheme);
    return out;
}

// `relief check`: what a scheme and its parameters give.
int runCheck(const CheckOptions& o) {
    std::map<std::string, double> params;
    if (!parseParams(o.params, params)) return code(Exit::BadInput);
    auto resolved = resolveScheme(o.scheme, o.preset, params);
    if (!resolved) return code(Exit::BadInput);
    const std::string& family = resolved->family;
    const relief::subdiv::Scheme* scheme = &resolved->scheme;
    const std::map<std::string, double>& resolvedParams = resolved->params;
    const auto rep = relief::subdiv::analyzeScheme(*scheme);
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
        std::cout << j.dump(2) << '\n';
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

std::vector<std::string> split(const std::string& s, char sep) {
    std::vector<std::string> out;
    size_t start = 0;
    while (true) {
        const size_t e = s.find(sep, start);
        out.push_back(s.substr(start, e == std::string::npos ? std::string::npos : e - start));
        if (e == std::string::npos) break;
        start = e + 1;
    }
    return out;
}

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
    if (polygon->type != "polyline") {
        std::cerr << "relief: error: " << o.polygon << ": relief curve refines a control polygon "
                  << "(\"type\": \"polyline\"), not a " << polygon->type << "\n";
        return code(Exit::BadInput);
    }
    std::vector<relief::Vec3> control;
    for (const auto& p : polygon->points) control.push_back({p.x, p.y, 0});

    relief::emit::SvgCurve controlCurve{"control polygon", polygon->points, polygon->closed};
    std::vector<relief::emit::SvgCurve> curves;
    std::vector<relief::curves::CurveFile> refinedFiles;
    for (size_t i = 0; i < sets.size(); ++i) {
        auto resolved = resolveScheme(o.scheme.scheme, o.scheme.preset, sets[i]);
        if (!resolved) return code(Exit::BadInput);
        if (!polygon->closed &&
            static_cast<int>(control.size()) < relief::subdiv::minPoints(resolved->scheme)) {
            std::cerr << fmt::format("relief: error: {}: an open polygon needs at least {} points "
                                     "for {}\n",
                                     o.polygon, relief::subdiv::minPoints(resolved->scheme),
                                     resolved->family);
            return code(Exit::BadInput);
        }
        const auto report = relief::subdiv::analyzeScheme(resolved->scheme);
        const auto refined =
            relief::subdiv::refineCurveLevels(resolved->scheme, control, polygon->closed, o.depth);
        relief::curves::CurveFile file{"polyline", polygon->closed, {}};
        for (const auto& v : refined) file.points.push_back({v.x, v.y});
        std::string label = resolved->family;
        if (!labels[i].empty()) label += ": " + labels[i];
        else {
            std::string p;
            for (const auto& [k, v] : resolved->params)
                p += fmt::format("{}{} = {}", p.empty() ? "" : ", ", k, relief::formatShortest(v));
            if (!p.empty()) label += ": " + p;
        }
        label += fmt::format(" ({})", relief::certifiedClass(report));
        curves.push_back({label, file.points, polygon->closed});
        refinedFiles.push_back(std::move(file));
    }
    const fs::path svgPath = o.output.empty()
                                 ? fs::path("out") / (fs::path(o.polygon).stem().string() + ".svg")
                                 : fs::path(o.output);
    ensureParent(svgPath);
    const std::string title =
        o.title.empty() ? fmt::format("{} refined {} times", fs::path(o.polygon).filename().string(), o.depth)
                        : o.title;
    relief::writeFileAtomically(svgPath, relief::emit::curvesSvg(title, controlCurve, curves));
    std::cerr << "wrote " << svgPath.string() << '\n';
    if (!o.points.empty()) {
        for (size_t i = 0; i < refinedFiles.size(); ++i) {
            fs::path p = o.points;
            if (refinedFiles.size() > 1)
                p = p.parent_path() / fmt::format("{}.{}{}", p.stem().string(), i + 1, p.extension().string());
            ensureParent(p);
            relief::writeFileAtomically(p, relief::curves::curveFileJson(refinedFiles[i]));
            std::cerr << "wrote " << p.string() << " (" << refinedFiles[i].points.size() << " points)\n";
        }
    }
    return code(Exit::Ok);
}

struct DiffOptions {
    std::string a, b;
    relief::compare::Thresholds t;
    std::string diffImage;
    bool json = false;
};

nlohmann::ordered_json differenceJson(const relief::compare::ImageDifference& d,
                                      const relief::compare::Thresholds& t) {
    nlohmann::ordered_json j;
    j["verdict"] = relief::compare::verdictName(d.verdict);
    if (!d.error.empty()) j["error"] = d.error;
    j["width"] = d.width;
    j["height"] = d.height;
    j["channels"] = d.channels;
    j["max_error"] = d.maxError;
    j["max_error_at"] = {d.maxX, d.maxY};
    j["max_error_channel"] = d.maxChannel;
    j["mean_error"] = d.meanError;
    j["rms_error"] = d.rmsError;
    j["psnr"] = std::isfinite(d.psnr) ? nlohmann::ordered_json(d.psnr) : nlohmann::ordered_json("inf");
    j["failing_pixels"] = d.failingPixels;
    j["failing_percent"] = d.failingPercent;
    j["warning_pixels"] = d.warningPixels;
    j["warning_percent"] = d.warningPercent;
    j["constant_a"] = d.constantA;
    j["constant_b"] = d.constantB;
    nlohmann::ordered_json ch = nlohmann::ordered_json::array();
    for (const auto& c : d.perChannel)
        ch.push_back({{"name", c.name}, {"max_error", c.maxError}, {"max_error_at", {c.maxX, c.maxY}},
                      {"mean_error", c.meanError}, {"rms_error", c.rmsError},
                      {"psnr", std::isfinite(c.psnr) ? nlohmann::ordered_json(c.psnr) : nlohmann::ordered_json("inf")}});
    j["per_channel"] = ch;
    j["thresholds"] = {{"fail", t.fail}, {"failpercent", t.failPercent},
                       {"hardfail", t.hardFail < 1e300 ? nlohmann::ordered_json(t.hardFail) : nlohmann::ordered_json("inf")},
                       {"warn", t.warn}, {"warnpercent", t.warnPercent},
                       {"hardwarn", t.hardWarn < 1e300 ? nlohmann::ordered_json(t.hardWarn) : nlohmann::ordered_json("inf")},
                       {"allowfailures", t.allowFailures}};
    return j;
}

// `relief diff`: idiff's metrics, thresholds, verdict and exit codes.
int runDiff(const DiffOptions& o) {
    using relief::compare::Verdict;
    const auto d = relief::compare::compareImages(o.a, o.b, o.t);
    if (!o.diffImage.empty() && (d.verdict != Verdict::FileError && d.verdict != Verdict::NotComparable)) {
        ensureParent(o.diffImage);
        const std::string err = relief::compare::writeDifferenceImage(o.a, o.b, o.diffImage);
        if (!err.empty()) {
            std::cerr << "relief: error: " << err << '\n';
            return 4;
        }
    }
    if (o.json) {
        std::cout << differenceJson(d, o.t).dump(2) << '\n';
        return static_cast<int>(d.verdict);
    }
    if (d.verdict == Verdict::FileError || d.verdict == Verdict::NotComparable) {
        std::cerr << "relief: error: " << d.error << '\n';
        std::cout << relief::compare::verdictName(d.verdict) << '\n';
        return static_cast<int>(d.verdict);
    }
    std::cout << fmt::format("Comparing {} and {} ({} x {}, {} channels)\n", o.a, o.b, d.width,
                             d.height, d.channels);
    std::cout << fmt::format("  {:<9} {:>10} {:>14} {:>11} {:>11} {:>8}\n", "channel", "max error",
                             "at (x, y)", "mean", "RMS", "PSNR");
    for (const auto& c : d.perChannel)
        std::cout << fmt::format("  {:<9} {:>10.6f} {:>14} {:>11.3e} {:>11.3e} {:>8.2f}\n", c.name,
                                 c.maxError, fmt::format("({}, {})", c.maxX, c.maxY), c.meanError,
                                 c.rmsError, c.psnr);
    std::cout << fmt::format("  {:<9} {:>10.6f} {:>14} {:>11.3e} {:>11.3e} {:>8.2f}\n", "all",
                             d.maxError, fmt::format("({}, {})", d.maxX, d.maxY), d.meanError,
                             d.rmsError, d.psnr);
    std::cout << fmt::format("  {} pixels ({:.4f} %) over fail {}; {} pixels ({:.4f} %) over warn {}\n",
                             d.failingPixels, d.failingPercent, relief::formatShortest(o.t.fail),
                             d.warningPixels, d.warningPercent, relief::formatShortest(o.t.warn));
    if (d.constantA) std::cout << "  note: " << o.a << " is a constant image (every pixel one colour)\n";
    if (d.constantB) std::cout << "  note: " << o.b << " is a constant image (every pixel one colour)\n";
    if (!o.diffImage.empty()) std::cout << "  difference image: " << o.diffImage << '\n';
    std::cout << relief::compare::verdictName(d.verdict) << '\n';
    return static_cast<int>(d.verdict);
}

struct TestOptions {
    std::string manifest;
    std::string report = "out/test-report";
    std::string templates;
    int jobs = 2;
    bool update = false;
};

// `relief test`: render every case of a manifest, compare, report.
int runTest(const TestOptions& o) {
    relief::Diagnostics diags;
    auto manifest = relief::regress::readManifest(o.manifest, diags);
    if (!manifest) {
        printDiagnostics(diags, false);
        return code(Exit::BadInput);
    }
    relief::regress::RunOptions ro;
    ro.reportDir = o.report;
    ro.templatesDir = findTemplates(o.templates);
    ro.jobs = o.jobs;
    ro.update = o.update;
    ro.manifestArgument = o.manifest;
    const auto t0 = std::chrono::steady_clock::now();
    std::cout << fmt::format("relief test: {} cases from {}, {} render{} at a time\n",
                             manifest->cases.size(), o.manifest, o.jobs, o.jobs == 1 ? "" : "s");
    auto results = relief::regress::runCases(
        *manifest, ro, [](const relief::regress::CaseResult& r, size_t done, size_t total) {
            std::cout << fmt::format("[{}/{}] {:<7} {} ({:.1f} s): {}\n", done, total,
                                     relief::regress::statusName(r.status), r.testCase->name,
                                     r.seconds, r.message)
                      << std::flush;
        });
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    relief::regress::writeReport(*manifest, results, ro, wall);
    size_t failed = 0;
    for (const auto& r : results)
        failed += r.status == relief::regress::CaseStatus::Fail ||
                  r.status == relief::regress::CaseStatus::Error ||
                  r.status == relief::regress::CaseStatus::New;
    std::cout << fmt::format("report: {}/index.html (also summary.json, junit.xml)\n", o.report);
    if (failed && !o.update)
        std::cout << fmt::format("to accept the new images: relief test {} --update\n", o.manifest);
    std::cout << fmt::format("{} passed, {} failed\n", results.size() - failed, failed);
    return failed && !o.update ? 1 : 0;
}

struct SweepOptions {
    CommonOptions common;
    std::vector<std::string> vary;
    int columns = 0;
};

// `relief sweep`: one still per parameter combination, then a contact sheet.
int runSweep(const SweepOptions& o) {
    std::vector<relief::figures::Variation> variations;
    for (const auto& v : o.vary) {
        const auto eq = v.find('=');
        if (eq == std::string::npos || eq == 0 || eq + 1 == v.size()) {
            std::cerr << "relief: error: --vary " << v << ": write section.key=V1,V2,...\n";
            return code(Exit::BadInput);
        }
        variations.push_back({v.substr(0, eq), split(v.substr(eq + 1), ',')});
    }
    relief::scene::SceneOverrides base;
    if (!parseOverrides(o.common.sets, base)) return code(Exit::BadInput);
    const auto combos = relief::figures::combinations(variations);
    const std::string stem = fs::path(o.common.scene).stem().string();
    const fs::path sheet = o.common.output.empty() ? fs::path("out") / (stem + "-sweep.png")
                                                   : fs::path(o.common.output);
    const fs::path stills = sheet.parent_path() / (sheet.stem().string() + "-stills");
    fs::create_directories(stills);
    std::vector<relief::figures::Tile> tiles;
    for (size_t i = 0; i < combos.size(); ++i) {
        std::string label;
        for (const auto& [k, v] : combos[i])
            label += fmt::format("{}{} = {}", label.empty() ? "" : ", ", k.substr(k.find('.') + 1), v);
        relief::RenderJob job;
        job.scenePath = o.common.scene;
        job.overrides = base;
        job.overrides.insert(job.overrides.end(), combos[i].begin(), combos[i].end());
        job.png = stills / fmt::format("{:03}.png", i + 1);
        job.templatesDir = findTemplates(o.common.templates);
        job.threads = o.common.threads;
        Progress progress(o.common.quiet);
        progress.show(fmt::format("[{}/{}] {}", i + 1, combos.size(), label));
        relief::Diagnostics diags;
        const auto outcome = relief::renderSceneFile(job, diags, [&](const std::string& line) {
            if (line.rfind("povray: Rendered", 0) == 0)
                progress.show(fmt::format("[{}/{}] {}: {}", i + 1, combos.size(), label, line.substr(8)));
        });
        progress.done();
        if (outcome.status != relief::JobStatus::Ok) {
            printDiagnostics(diags, false);
            if (outcome.status == relief::JobStatus::ToolFailed)
                std::cerr << "relief: POV-Ray failed:\n" << outcome.render.error << '\n';
            return code(outcome.status == relief::JobStatus::ToolFailed ? Exit::ToolFailed : Exit::BadInput);
        }
        printDiagnostics(diags, true);
        if (!o.common.quiet)
            std::cerr << fmt::format("[{}/{}] {} -> {} ({})\n", i + 1, combos.size(), label,
                                     outcome.paths.png.string(), outcome.certified);
        tiles.push_back({outcome.paths.png, fmt::format("{}\n{}", label, outcome.certified)});
    }
    const int columns = o.columns > 0 ? o.columns
                                      : (variations.empty() ? 1 : static_cast<int>(variations[0].values.size()));
    const std::string err = relief::figures::writeContactSheet(tiles, columns, fs::path(o.common.scene).filename().string(), sheet);
    if (!err.empty() && err.rfind("warning", 0) != 0) {
        std::cerr << "relief: error: " << err << '\n';
        return code(Exit::BadInput);
    }
    if (!err.empty()) std::cerr << "relief: " << err << '\n';
    std::cerr << "wrote " << sheet.string() << " (" << tiles.size() << " stills)\n";
    return code(Exit::Ok);
}

struct HausdorffOptions {
    std::string a, b;
    bool json = false;
};

// `relief hausdorff`: exact h(A, B), h(B, A) and H with witnesses.
int runHausdorff(const HausdorffOptions& o) {
    relief::Diagnostics diags;
    auto fa = relief::curves::readCurveFile(o.a, diags);
    auto fb = relief::curves::readCurveFile(o.b, diags);
    if (!fa || !fb) {
        printDiagnostics(diags, false);
        return code(Exit::BadInput);
    }
    const auto A = relief::curves::toBezier(*fa), B = relief::curves::toBezier(*fb);
    const auto r = relief::curves::hausdorff(A, B);
    auto side = [](const relief::curves::OneSided& s) {
        nlohmann::ordered_json j{{"value", s.value},
                                 {"case", relief::curves::caseName(s.kind)},
                                 {"point", {s.a.x, s.a.y}},
                                 {"param", s.paramA},
                                 {"foot", {s.foot.point.x, s.foot.point.y}},
                                 {"foot_param", s.foot.param}};
        if (s.kind == relief::curves::WitnessCase::OneToTwo)
            j["second_foot"] = {{"point", {s.secondFoot.point.x, s.secondFoot.point.y}},
                                {"param", s.secondFoot.param}};
        return j;
    };
    if (o.json) {
        nlohmann::ordered_json j;
        j["h_ab"] = r.ab.value;
        j["h_ba"] = r.ba.value;
        j["H"] = r.H;
        j["witness_ab"] = side(r.ab);
        j["witness_ba"] = side(r.ba);
        std::cout << j.dump(2) << '\n';
        return code(Exit::Ok);
    }
    auto print = [](const char* name, const relief::curves::OneSided& s, const char* from, const char* to) {
        std::cout << fmt::format("{} = {:.12g}  ({})\n", name, s.value, relief::curves::caseName(s.kind));
        std::cout << fmt::format("    on {}: ({:.12g}, {:.12g}) at parameter {:.12g}\n", from, s.a.x, s.a.y, s.paramA);
        std::cout << fmt::format("    on {}: ({:.12g}, {:.12g}) at parameter {:.12g}\n", to, s.foot.point.x,
                                 s.foot.point.y, s.foot.param);
        if (s.kind == relief::curves::WitnessCase::OneToTwo)
            std::cout << fmt::format("    and    ({:.12g}, {:.12g}) at parameter {:.12g}\n",
                                     s.secondFoot.point.x, s.secondFoot.point.y, s.secondFoot.param);
    };
    print("h(A, B)", r.ab, "A", "B");
    print("h(B, A)", r.ba, "B", "A");
    std::cout << fmt::format("H = {:.12g}\n", r.H);
    return code(Exit::Ok);
}

struct ProfileOptions {
    CommonOptions common;
    std::string from, to;
    int samples = 1001;
    double exaggeration = 0;  ///< plot only; 0 = choose
};

bool parseLonLat(const std::string& text, double& lon, double& lat) {
    const auto parts = split(text, ',');
    if (parts.size() != 2) return false;
    char* end = nullptr;
    lon = std::strtod(parts[0].c_str(), &end);
    if (end == parts[0].c_str() || *end) return false;
    lat = std::strtod(parts[1].c_str(), &end);
    if (end == parts[1].c_str() || *end) return false;
    return std::fabs(lat) <= 90 && std::fabs(lon) <= 180;
}

// `relief profile`: the refined and the control-net surface cut along a geodesic.
int runProfile(const ProfileOptions& o) {
    double lon1, lat1, lon2, lat2;
    if (!parseLonLat(o.from, lon1, lat1) || !parseLonLat(o.to, lon2, lat2)) {
        std::cerr << "relief: error: --from and --to take LON,LAT in WGS84 degrees (e.g. "
                     "174.7640,-36.8770), |lat| <= 90, |lon| <= 180\n";
        return code(Exit::BadInput);
    }
    relief::Diagnostics diags;
    relief::scene::SceneOverrides overrides;
    if (!parseOverrides(o.common.sets, overrides)) return code(Exit::BadInput);
    auto loaded = relief::loadScene(o.common.scene, diags, overrides);
    auto surface = loaded ? relief::buildSurface(*loaded, diags) : std::nullopt;
    if (!surface) {
        printDiagnostics(diags, false);
        return code(Exit::BadInput);
    }
    const auto& net = surface->net;
    const auto line = relief::geo::geodesicProfile(net.frame, lat1, lon1, lat2, lon2, o.samples);
    relief::curves::CurveFile refined{"polyline", false, {}}, control{"polyline", false, {}};
    for (const auto& p : line) {
        const auto zr = relief::geo::sampleLattice(surface->refined, net.x0, net.y0, surface->refinedDx,
                                                   surface->refinedDy, p.x, p.y);
        const auto zc = relief::geo::sampleLattice(net.grid, net.x0, net.y0, net.dx, net.dy, p.x, p.y);
        if (!zr || !zc) {
            std::cerr << fmt::format("relief: error: the profile leaves the net {:.0f} m from the start "
                                     "(lat {:.6f}, lon {:.6f}); the net covers x {:.0f}..{:.0f} m, y "
                                     "{:.0f}..{:.0f} m in {}: choose points inside it\n",
                                     p.distanceM, p.latDeg, p.lonDeg, net.x0,
                                     net.x0 + (net.grid.cols - 1) * net.dx, net.y0,
                                     net.y0 + (net.grid.rows - 1) * net.dy, net.frame.describe());
            return code(Exit::BadInput);
        }
        refined.points.push_back({p.distanceM, *zr});
        control.points.push_back({p.distanceM, *zc});
    }
    const std::string stem = fs::path(o.common.scene).stem().string();
    const fs::path svg = o.common.output.empty() ? fs::path("out") / (stem + "-profile.svg") : fs::path(o.common.output);
    fs::path curveRefined = svg, curveNet = svg;
    curveRefined.replace_extension(".json");
    curveNet.replace_filename(svg.stem().string() + "-net.json");
    ensureParent(svg);
    double zmin = 1e300, zmax = -1e300;
    for (const auto& p : refined.points) zmin = std::min(zmin, p.y), zmax = std::max(zmax, p.y);
    const double length = line.back().distanceM;
    // Plot: relief about a third of the length unless asked otherwise.
    const double ve = o.exaggeration > 0 ? o.exaggeration
                                         : std::max(1.0, std::round(0.3 * length / std::max(zmax - zmin, 1e-9)));
    relief::emit::SvgAxes axes{true, ve, "distance along the geodesic (m)", "elevation (m)"};
    const std::string title = fmt::format("{}: profile, {:.0f} m, vertical exaggeration {:g}",
                                          fs::path(o.common.scene).filename().string(), length, ve);
    relief::writeFileAtomically(
        svg, relief::emit::curvesSvg(title, {"control net (bilinear)", control.points, false},
                                     {{fmt::format("refined: {} depth {} ({})", loaded->schemeFamily,
                                                   surface->depth, relief::certifiedClass(loaded->report)),
                                       refined.points, false}},
                                     axes));
    relief::writeFileAtomically(curveRefined, relief::curves::curveFileJson(refined));
    relief::writeFileAtomically(curveNet, relief::curves::curveFileJson(control));
    std::cerr << fmt::format("wrote {}, {} (refined) and {} (control net): {} points over {:.1f} m, "
                             "elevation {:.1f}..{:.1f} m\n",
                             svg.string(), curveRefined.string(), curveNet.string(), line.size(), length,
                             zmin, zmax);
    return code(Exit::Ok);
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{fmt::format(
        "relief {}: compiles georeferenced elevation samples into a ray-traced still.\n"
        "scene file (TOML) -> control net (GeographicLib, GDAL) -> subdivision -> POV-Ray "
        "mesh2 -> PNG",
        relief::kVersion)};
    app.footer(std::string("\n") + kExitCodes + "\nScene format: docs/scene-format.md");
    app.set_version_flag("--version", fmt::format("relief {}", relief::kVersion));
    app.require_subcommand(1);

    CommonOptions common;
    std::string dumpNet;
    auto addCommon = [&](CLI::App* sub, const char* outputHelp) {
        sub->add_option("scene", common.scene, "scene file (TOML)")->required();
        sub->add_option("-o,--output", common.output, outputHelp);
        sub->add_option("--templates", common.templates,
                        "folder with scene.pov.in (default: $RELIEF_TEMPLATES, the installed "
                        "share/relief/templates, or the source tree's)");
        sub->add_option("--threads", common.threads, "refiner and POV-Ray threads (0: all cores)")
            ->check(CLI::Range(0, 256));
        sub->add_flag("-q,--quiet", common.quiet, "print errors only");
        sub->add_option("--set", common.sets,
                        "override a scene key: section.key=value (e.g. render.width=320, "
                        "subdivision.omega=1/32); repeatable");
    };
    CLI::App* compile = app.add_subcommand(
        "compile", "write the POV-Ray scene (.pov) and a JSON sidecar; no rendering");
    addCommon(compile, "the .pov to write (default: out/<scene name>.pov)");
    compile->add_option("--dump-net", dumpNet,
                        "also write the control net: .csv (x,y,z in the frame, metres) or .asc "
                        "(ESRI ASCII grid; needs net.spacing_m)");
    CLI::App* render = app.add_subcommand(
        "render", "compile, then render the still with POV-Ray (.png, .pov and .json sidecar)");
    addCommon(render, "the PNG to write (default: [render] output, else out/<scene name>.png)");
    render->add_option("--dump-net", dumpNet, "also write the control net (.csv or .asc)");

    CheckOptions check;
    CLI::App* checkCmd = app.add_subcommand(
        "check", "what a scheme and its parameters give: mask, interpolation, support, "
                 "reproduction, certified smoothness (difference-scheme test), Hölder estimate");
    checkCmd->add_option("--scheme", check.scheme,
                         "dlg4, four-point-4p, binary-3p, ternary-blend, ternary-4point, "
                         "ternary-bspline");
    checkCmd->add_option("--preset", check.preset, "a named special case, e.g. hassan, deslauriers-dubuc");
    checkCmd->add_option("--param", check.params, "KEY=VALUE (fractions such as 7/32 allowed); repeatable");
    checkCmd->add_flag("--json", check.json, "one JSON object");

    CurveOptions curve;
    CLI::App* curveCmd = app.add_subcommand(
        "curve", "refine a 2-D control polygon (open or closed) and draw it as SVG; --set or "
                 "--vary draws several parameter sets in one figure");
    curveCmd->add_option("polygon", curve.polygon, "curve file: {\"type\": \"polyline\", \"closed\": "
                                                   "false, \"points\": [[x, y], ...]}")->required();
    curveCmd->add_option("--scheme", curve.scheme.scheme, "scheme name (see relief check)");
    curveCmd->add_option("--preset", curve.scheme.preset, "a named special case");
    curveCmd->add_option("--param", curve.scheme.params, "KEY=VALUE for every curve; repeatable");
    curveCmd->add_option("--set", curve.sets, "one curve's parameters: \"k=v,k=v\"; repeatable");
    curveCmd->add_option("--vary", curve.vary, "KEY=V1,V2,...: one curve per value");
    curveCmd->add_option("--depth", curve.depth, "refinement levels")->check(CLI::Range(0, 12));
    curveCmd->add_option("-o,--output", curve.output, "SVG to write (default out/<polygon>.svg)");
    curveCmd->add_option("--points", curve.points, "also write the refined points as curve files");
    curveCmd->add_option("--title", curve.title, "figure title");

    DiffOptions diff;
    CLI::App* diffCmd = app.add_subcommand(
        "diff", "compare two images (OpenImageIO), with idiff's thresholds and exit codes: "
                "0 PASS, 1 WARNING, 2 FAILURE, 3 not comparable (different sizes or channel "
                "counts), 4 file error or bad arguments");
    diffCmd->add_option("a", diff.a, "first image")->required();
    diffCmd->add_option("b", diff.b, "second image")->required();
    diffCmd->add_option("--fail", diff.t.fail, "a pixel fails when a channel differs by more (default 1e-6)");
    diffCmd->add_option("--failpercent", diff.t.failPercent, "allow this % of pixels to fail (default 0)");
    diffCmd->add_option("--hardfail", diff.t.hardFail, "fail if any pixel differs by more (default inf)");
    diffCmd->add_option("--warn", diff.t.warn, "a pixel warns when a channel differs by more (default 1e-6)");
    diffCmd->add_option("--warnpercent", diff.t.warnPercent, "allow this % of pixels to warn (default 0)");
    diffCmd->add_option("--hardwarn", diff.t.hardWarn, "warn if any pixel differs by more (default inf)");
    diffCmd->add_option("--allowfailures", diff.t.allowFailures, "this many pixels may fail by any amount (default 0)");
    diffCmd->add_option("--diff-image", diff.diffImage, "write a heat map of the difference (black: identical)");
    diffCmd->add_flag("--json", diff.json, "print the metrics and the verdict as one JSON object");

    TestOptions test;
    CLI::App* testCmd = app.add_subcommand(
        "test", "render every case of a manifest, compare with its reference images, write an "
                "HTML report (and summary.json, junit.xml); exit 1 when a case fails");
    testCmd->add_option("manifest", test.manifest, "manifest (TOML): [defaults] and [[case]] entries")->required();
    testCmd->add_option("--report", test.report, "report folder (default out/test-report)");
    testCmd->add_option("--jobs,-j", test.jobs, "renders at a time (default 2: measured faster on 2 cores)")
        ->check(CLI::Range(1, 64));
    testCmd->add_flag("--update", test.update, "bless the new images of failing or new cases as their references");
    testCmd->add_option("--templates", test.templates, "folder with scene.pov.in");

    SweepOptions sweep;
    CLI::App* sweepCmd = app.add_subcommand(
        "sweep", "render one still per combination of --vary values and assemble a labelled "
                 "contact sheet (one PNG)");
    sweepCmd->add_option("scene", sweep.common.scene, "scene file (TOML)")->required();
    sweepCmd->add_option("--vary", sweep.vary, "section.key=V1,V2,... (fractions allowed); repeatable")->required();
    sweepCmd->add_option("--set", sweep.common.sets, "fixed override section.key=value; repeatable");
    sweepCmd->add_option("-o,--output", sweep.common.output, "contact sheet (default out/<scene>-sweep.png)");
    sweepCmd->add_option("--columns", sweep.columns, "tiles per row (default: the first --vary's count)");
    sweepCmd->add_option("--templates", sweep.common.templates, "folder with scene.pov.in");
    sweepCmd->add_option("--threads", sweep.common.threads, "threads (0: all cores)");
    sweepCmd->add_flag("-q,--quiet", sweep.common.quiet, "print errors only");

    HausdorffOptions hd;
    CLI::App* hdCmd = app.add_subcommand(
        "hausdorff", "exact Hausdorff distance between two planar curves (paper 003): h(A,B), "
                     "h(B,A), H, the witness points and which of the four cases each is");
    hdCmd->add_option("a", hd.a, "curve file A (docs/curve-format.md)")->required();
    hdCmd->add_option("b", hd.b, "curve file B")->required();
    hdCmd->add_flag("--json", hd.json, "one JSON object with h_ab, h_ba, H and the witnesses");

    ProfileOptions profile;
    CLI::App* profileCmd = app.add_subcommand(
        "profile", "cut the refined surface (and the control net) along the geodesic between two "
                   "points: a curve file (distance, elevation in metres) and an SVG plot");
    profileCmd->add_option("scene", profile.common.scene, "scene file (TOML)")->required();
    profileCmd->add_option("--from", profile.from, "start: LON,LAT (WGS84 degrees)")->required();
    profileCmd->add_option("--to", profile.to, "end: LON,LAT")->required();
    profileCmd->add_option("--samples", profile.samples, "points along the line (default 1001)")
        ->check(CLI::Range(2, 1000000));
    profileCmd->add_option("--exaggeration", profile.exaggeration, "vertical exaggeration of the plot (default: chosen)");
    profileCmd->add_option("-o,--output", profile.common.output,
                           "SVG (default out/<scene>-profile.svg); curve files beside it");
    profileCmd->add_option("--set", profile.common.sets, "override a scene key: section.key=value");

    try {
        app.parse(argc, argv);
    } catch (const CLI::Success& e) {
        return app.exit(e);
    } catch (const CLI::ParseError& e) {
        app.exit(e);
        return diffCmd->parsed() ? 4 : code(Exit::BadInput);  // diff keeps idiff's codes
    }
    try {
        if (checkCmd->parsed()) return runCheck(check);
        if (curveCmd->parsed()) return runCurve(curve);
        if (diffCmd->parsed()) return runDiff(diff);
        if (testCmd->parsed()) return runTest(test);
        if (sweepCmd->parsed()) return runSweep(sweep);
        if (hdCmd->parsed()) return runHausdorff(hd);
        if (profileCmd->parsed()) return runProfile(profile);
        return render->parsed() ? runRender(common, dumpNet) : runCompile(common, dumpNet);
    } catch (const std::runtime_error& e) {  // I/O: cannot write an output
        std::cerr << "relief: error: " << e.what() << '\n';
        return code(Exit::BadInput);
    } catch (const std::exception& e) {
        std::cerr << "relief: internal error: " << e.what() << '\n';
        return code(Exit::Internal);
    }
}
