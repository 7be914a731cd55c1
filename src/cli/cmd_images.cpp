#include "cli/cli_common.h"

// relief diff, relief test, relief sweep: images compared, regression runs, contact sheets.
#include <cmath>
#include <iostream>
#include <memory>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "compare/compare_images.h"
#include "core/number_format.h"
#include "core/stopwatch.h"
#include "core/text_escape.h"
#include "figures/sweep.h"
#include "pipeline/job.h"
#include "regress/regress.h"

namespace relief::cli {

namespace {

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
    j["psnr"] = jsonNumber(d.psnr);
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
                      {"psnr", jsonNumber(c.psnr)}});
    j["per_channel"] = ch;
    j["thresholds"] = {{"fail", t.fail}, {"failpercent", t.failPercent},
                       {"hardfail", t.hardFail < 1e300 ? nlohmann::ordered_json(t.hardFail) : nlohmann::ordered_json("inf")},
                       {"warn", t.warn}, {"warnpercent", t.warnPercent},
                       {"hardwarn", t.hardWarn < 1e300 ? nlohmann::ordered_json(t.hardWarn) : nlohmann::ordered_json("inf")},
                       {"allowfailures", t.allowFailures}};
    return j;
}

// idiff's exit code for a verdict.
Exit exitFor(relief::compare::Verdict v) {
    using relief::compare::Verdict;
    switch (v) {
        case Verdict::Pass: return Exit::Ok;
        case Verdict::Warning: return Exit::DiffWarning;
        case Verdict::Failure: return Exit::DiffFailure;
        case Verdict::NotComparable: return Exit::DiffNotComparable;
        case Verdict::FileError: return Exit::DiffFileError;
    }
    return Exit::Internal;
}

// `relief diff`: idiff's metrics, thresholds, verdict and exit codes.
int runDiff(const DiffOptions& o) {
    using relief::compare::Verdict;
    const auto d = relief::compare::compareImages(o.a, o.b, o.t);
    if (!o.diffImage.empty() && (d.verdict != Verdict::FileError && d.verdict != Verdict::NotComparable)) {
        createParentFolder(o.diffImage);
        const std::string err = relief::compare::writeDifferenceImage(o.a, o.b, o.diffImage);
        if (!err.empty()) {
            std::cerr << "relief: error: " << relief::terminalText(err) << '\n';
            return code(Exit::DiffFileError);
        }
    }
    if (o.json) {
        std::cout << differenceJson(d, o.t).dump(2, ' ', false, nlohmann::json::error_handler_t::replace) << '\n';
        return code(exitFor(d.verdict));
    }
    if (d.verdict == Verdict::FileError || d.verdict == Verdict::NotComparable) {
        std::cerr << "relief: error: " << relief::terminalText(d.error) << '\n';
        std::cout << relief::compare::verdictName(d.verdict) << '\n';
        return code(exitFor(d.verdict));
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
    return code(exitFor(d.verdict));
}

struct TestOptions {
    std::string manifest;
    std::string report = "out/test-report";
    std::string templates;
    int jobs = 2;
    ExecutionOptions execution;
    bool update = false;
    bool noSandbox = false;
};

// `relief test`: render every case of a manifest, compare, report.
int runTest(const TestOptions& o) {
    relief::Diagnostics diags;
    auto manifest = relief::regress::readManifest(o.manifest, diags);
    if (!manifest || (o.update && !relief::regress::checkUpdatable(*manifest, diags))) {
        printDiagnostics(diags, false);
        return code(Exit::BadInput);
    }
    if (const std::string refusal = relief::regress::ReportFolder::refusal(o.report, *manifest); !refusal.empty()) {
        std::cerr << "relief: error: " << terminalText(refusal, 1000) << '\n';
        return code(Exit::BadInput);
    }
    raiseOpenFileLimit();
    relief::regress::ReportFolder report(o.report, *manifest);
    relief::regress::RunOptions ro;
    ro.reportDir = report.staged();
    ro.templatesDir = findTemplates(o.templates);
    ro.jobs = o.jobs;
    ro.update = o.update;
    ro.manifestArgument = o.manifest;
    installInterruptHandler();
    ro.execution = executionOf(o.execution, o.noSandbox);
    ro.execution.jobs = o.execution.executor == "slurm" ? o.jobs : 0;
    // Slurm's job folder beside the report, where the paths its messages name stay true.
    ro.execution.jobDir = report.path().parent_path() / (report.path().filename().string() + ".slurm");
    const auto t0 = Clock::now();
    std::cout << fmt::format("relief test: {} cases from {}, {} render{} at a time\n",
                             manifest->cases.size(), o.manifest, o.jobs, o.jobs == 1 ? "" : "s");
    auto results = relief::regress::runCases(
        *manifest, ro, [](const relief::regress::CaseResult& r, size_t done, size_t total) {
            std::cout << fmt::format("[{}/{}] {:<7} {} ({:.1f} s): {}\n", done, total,
                                     relief::regress::statusName(r.status), r.testCase->name,
                                     r.seconds, relief::terminalText(r.message))
                      << std::flush;
        });
    if (interrupted()) {
        std::cerr << "relief test: interrupted; no report written\n";
        return code(Exit::Interrupted);
    }
    const double wall = secondsSince(t0);
    relief::regress::writeReport(*manifest, results, ro, wall);
    try {
        report.publish();
    } catch (const std::runtime_error& e) {
        std::cerr << "relief: error: " << terminalText(e.what(), 1000) << '\n';
        return code(Exit::BadInput);
    }
    size_t failed = 0;
    for (const auto& r : results)
        failed += r.status == relief::regress::CaseStatus::Fail ||
                  r.status == relief::regress::CaseStatus::Error ||
                  r.status == relief::regress::CaseStatus::New;
    std::cout << fmt::format("report: {}/index.html (also summary.json, junit.xml)\n", o.report);
    if (failed && !o.update)
        std::cout << fmt::format("to accept the new images: relief test {} --update\n",
                                 relief::terminalText(relief::shellQuoted(o.manifest), 500));
    std::cout << fmt::format("{} passed, {} failed\n", results.size() - failed, failed);
    return code(failed && !o.update ? Exit::TestCaseFailed : Exit::Ok);
}

struct SweepOptions {
    CommonOptions common;
    std::vector<std::string> vary;
    int columns = 0;
    ExecutionOptions execution;
};

// `relief sweep`: one still per parameter combination, then a contact sheet.
int runSweep(const SweepOptions& o) {
    raiseOpenFileLimit();  // a lock for each combination until it is rendered
    std::vector<relief::figures::Variation> variations;
    for (const auto& v : o.vary) {
        const auto eq = v.find('=');
        if (eq == std::string::npos || eq == 0 || eq + 1 == v.size()) {
            std::cerr << "relief: error: --vary " << v << ": write section.key=V1,V2,...\n";
            return code(Exit::BadInput);
        }
        variations.push_back({v.substr(0, eq), split(v.substr(eq + 1), ',')});
    }
    relief::figures::SweepRequest request;
    request.scenePath = o.common.scene;
    if (!parseOverrides(o.common.sets, request.base)) return code(Exit::BadInput);
    request.variations = variations;
    request.sheet = o.common.output.empty()
                        ? fs::path("out") / (fs::path(o.common.scene).stem().string() + "-sweep.png")
                        : fs::path(o.common.output);
    request.templatesDir = findTemplates(o.common.templates);
    request.threads = o.common.threads;
    request.columns = o.columns;
    request.tiles = o.execution.tiles;
    installInterruptHandler();
    request.execution = executionOf(o.execution, o.common.noSandbox);
    Progress progress(o.common.quiet);
    using Kind = relief::figures::SweepEvent::Kind;
    const auto result = relief::figures::runSweep(request, [&](const relief::figures::SweepEvent& e) {
        const std::string still = fmt::format("[{}/{}] {}", e.index, e.total, e.label);
        if (e.kind == Kind::Started) {
            progress.show(still);
        } else if (e.kind == Kind::Rendering) {
            progress.show(e.render->text, e.render->percent);
        } else {
            progress.done();
            const bool ok = e.outcome->status == relief::JobStatus::Ok;
            printDiagnostics(*e.diags, ok);
            if (e.outcome->status == relief::JobStatus::ToolFailed)
                std::cerr << "relief: POV-Ray failed:\n" << relief::terminalText(e.outcome->render.error, 8000, true) << '\n';
            if (ok && !o.common.quiet)
                std::cerr << fmt::format("{} -> {} ({})\n", still, e.outcome->paths.still.string(),
                                         e.outcome->compiled->surface.certified);
        }
    });
    if (result.status == relief::JobStatus::Cancelled) {
        std::cerr << "relief: interrupted; nothing written\n";
        return code(Exit::Interrupted);
    }
    if (result.status != relief::JobStatus::Ok)
        return code(result.status == relief::JobStatus::ToolFailed ? Exit::ToolFailed : Exit::BadInput);
    if (!result.sheetWritten) {
        std::cerr << "relief: error: " << relief::terminalText(result.sheetMessage) << '\n';
        return code(Exit::BadInput);
    }
    if (!result.sheetMessage.empty()) std::cerr << "relief: " << result.sheetMessage << '\n';
    if (!o.common.quiet)
        std::cerr << "wrote " << relief::terminalText(request.sheet.string(), 500) << " (" << result.tiles.size()
                  << " stills)\n";
    return code(Exit::Ok);
}

}  // namespace

void addImageCommands(CLI::App& app, std::vector<Command>& out) {
    auto diff = std::make_shared<DiffOptions>();
    CLI::App* diffCmd = app.add_subcommand(kImageCommands[0].name, kImageCommands[0].description);
    diffCmd->add_option("a", diff->a, "first image")->required();
    diffCmd->add_option("b", diff->b, "second image")->required();
    diffCmd->add_option("--fail", diff->t.fail, "a pixel fails when a channel differs by more (default 1e-6)");
    diffCmd->add_option("--failpercent", diff->t.failPercent, "allow this % of pixels to fail (default 0)");
    diffCmd->add_option("--hardfail", diff->t.hardFail, "fail if any pixel differs by more (default inf)");
    diffCmd->add_option("--warn", diff->t.warn, "a pixel warns when a channel differs by more (default 1e-6)");
    diffCmd->add_option("--warnpercent", diff->t.warnPercent, "allow this % of pixels to warn (default 0)");
    diffCmd->add_option("--hardwarn", diff->t.hardWarn, "warn if any pixel differs by more (default inf)");
    diffCmd->add_option("--allowfailures", diff->t.allowFailures, "this many pixels may fail by any amount (default 0)");
    diffCmd->add_option("--diff-image", diff->diffImage, "write a heat map of the difference (black: identical)");
    diffCmd->add_flag("--json", diff->json, "print the metrics and the verdict as one JSON object");
    out.push_back({diffCmd, [diff] { return runDiff(*diff); }, code(Exit::DiffFileError)});  // idiff's code for bad arguments

    auto test = std::make_shared<TestOptions>();
    CLI::App* testCmd = app.add_subcommand(kImageCommands[1].name, kImageCommands[1].description);
    testCmd->add_option("manifest", test->manifest, "manifest (TOML): [defaults] and [[case]] entries")->required();
    testCmd->add_option("--report", test->report, "report folder (default out/test-report)");
    testCmd->add_option("--jobs,-j", test->jobs, "renders at a time (default 2: measured faster on 2 cores; on "
                                                 "Slurm, array tasks at once)")
        ->check(CLI::Range(1, 100000));
    testCmd->add_option("--executor", test->execution.executor,
                        "where the cases render: local (default) or slurm (one array task a case; docs/distributed.md)")
        ->check(CLI::IsMember({"local", "slurm"}));
    testCmd->add_option("--slurm-args", test->execution.slurmArgs, "passed to sbatch, e.g. \"--partition=batch\"");
    testCmd->add_flag("--update", test->update, "bless the new images of failing or new cases as their references");
    testCmd->add_option("--templates", test->templates, "folder with scene.pov.in");
    testCmd->add_flag("--no-sandbox", test->noSandbox, "run POV-Ray without its bubblewrap sandbox (only for scenes you trust; see docs/security.md)");
    out.push_back({testCmd, [test] { return runTest(*test); }});

    auto sweep = std::make_shared<SweepOptions>();
    CLI::App* sweepCmd = app.add_subcommand(kImageCommands[2].name, kImageCommands[2].description);
    sweepCmd->add_option("scene", sweep->common.scene, "scene file (TOML)")->required();
    sweepCmd->add_option("--vary", sweep->vary, "section.key=V1,V2,... (fractions allowed); repeatable")->required();
    sweepCmd->add_option("--set", sweep->common.sets, "fixed override section.key=value; repeatable");
    sweepCmd->add_option("-o,--output", sweep->common.output, "contact sheet (default out/<scene>-sweep.png)");
    sweepCmd->add_option("--columns", sweep->columns, "tiles per row (default: the first --vary's count)");
    sweepCmd->add_option("--templates", sweep->common.templates, "folder with scene.pov.in");
    sweepCmd->add_option("--threads", sweep->common.threads, "refiner threads (0: all cores)");
    addExecutionOptions(sweepCmd, sweep->execution, true,
                        "stills (or tiles) at once (0: as many as cores here; on Slurm, as many as the cluster runs)");
    sweepCmd->add_flag("-q,--quiet", sweep->common.quiet, "print errors only");
    sweepCmd->add_flag("--no-sandbox", sweep->common.noSandbox, "run POV-Ray without its bubblewrap sandbox (only for scenes you trust; see docs/security.md)");
    out.push_back({sweepCmd, [sweep] { return runSweep(*sweep); }});
}

}  // namespace relief::cli
