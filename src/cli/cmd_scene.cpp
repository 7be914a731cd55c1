#include "cli/cli_common.h"

// relief compile, relief render: one scene file to a .pov, or all the way to a
// PNG; and the render's steps on their own: relief plan, render-tile, finish.
// Every one of them calls pipeline/job.h.
#include <iostream>
#include <memory>

#include <fmt/format.h>

#include "core/text_escape.h"
#include "core/atomic_file.h"
#include "pipeline/job.h"

namespace relief::cli {

namespace {

struct SceneOptions {
    CommonOptions common;
    std::string dumpNet;
    std::string dumpSurface;
    ExecutionOptions execution;
    std::string plan;    ///< --plan: the plan's folder
    std::string resume;  ///< --resume PLAN
    bool keepPlan = false;
};

relief::SceneJob sceneJob(const SceneOptions& o, relief::SceneJob::Until until, bool& ok) {
    relief::SceneJob job;
    job.until = until;
    job.scenePath = o.common.scene;
    ok = parseOverrides(o.common.sets, job.overrides);
    job.output = o.common.output;
    job.templatesDir = findTemplates(o.common.templates);
    job.dumpNetPath = o.dumpNet;
    job.dumpSurfacePath = o.dumpSurface;
    job.threads = o.common.threads;
    job.tiles = o.execution.tiles;
    job.planDir = o.plan;
    job.keepPlan = o.keepPlan;
    job.execution = executionOf(o.execution, o.common.noSandbox);
    return job;
}

void printWritten(const relief::JobOutcome& outcome, bool rendered) {
    const auto& c = outcome.compiled->surface;
    const auto& t = outcome.compiled->terrain;
    std::cerr << fmt::format("scheme {}: {}\n", c.schemeFamily, c.certified);
    if (c.autoDepth) std::cerr << c.depthReason << '\n';
    // What POV-Ray gets: every vertex, the adaptive mesh, or the height field's PNGs.
    const std::string pov = terminalText(outcome.paths.pov.string(), 500);
    switch (c.geometry.kind) {
        case scene::GeometryKind::HeightField:
            std::cerr << fmt::format("wrote {} (a height field of {} x {} nodes: {}, {})\n", pov, c.estimate.rows,
                                     c.estimate.cols, terminalText(t.heightPng.string(), 500),
                                     terminalText(t.drapePng.string(), 500));
            break;
        case scene::GeometryKind::Adaptive:
            std::cerr << fmt::format("wrote {} (an adaptive mesh2: {} triangles of the full {:.0f}, {:.1f} MB)\n", pov,
                                     t.meshTriangles, c.estimate.triangles, outcome.compiled->povBytes / 1e6);
            break;
        default:
            std::cerr << fmt::format("wrote {} ({} x {} vertices, {} triangles, {:.1f} MB)\n", pov, c.estimate.rows,
                                     c.estimate.cols, t.meshTriangles, outcome.compiled->povBytes / 1e6);
    }
    if (rendered)
        std::cerr << fmt::format("wrote {} ({} x {}{}; POV-Ray parse {:.2f} s, trace {:.2f} s)\n",
                                 terminalText(outcome.paths.still.string(), 500), outcome.compiled->view.widthPx,
                                 outcome.compiled->view.heightPx,
                                 outcome.tiles > 1 ? fmt::format(", {} tiles", outcome.tiles) : std::string(),
                                 outcome.render.parseSeconds, outcome.render.traceSeconds);
}

// How a job that did not finish ended, and its exit code.
int reportFailure(const relief::JobOutcome& outcome, const relief::Diagnostics& diags, const std::string& scene) {
    const std::string kept = keptForResume("the render plan is", "render", outcome.plan);
    switch (outcome.status) {
        case relief::JobStatus::Cancelled:
            printDiagnostics(diags, false);
            std::cerr << "relief: interrupted; nothing written\n" << kept;
            return code(Exit::Interrupted);
        case relief::JobStatus::ToolFailed:
            printDiagnostics(diags, false);
            std::cerr << "relief: POV-Ray failed on the scene compiled from " << terminalText(scene, 500)
                      << (outcome.plan.empty() ? " (nothing written; relief compile writes the .pov to look at):\n"
                                               : " (nothing written; the plan keeps the .pov):\n")
                      << terminalText(outcome.render.error, 8000, true) << '\n'
                      << kept;
            return code(Exit::ToolFailed);
        default:
            printDiagnostics(diags, false);
            std::cerr << kept;
            return code(Exit::BadInput);
    }
}

// `relief compile` (until the .pov) and `relief render` (until the PNG, or a plan resumed).
int runScene(const SceneOptions& o, relief::SceneJob::Until until) {
    relief::Diagnostics diags;
    Progress progress(o.common.quiet);
    // Rendering stops its POV-Rays and keeps the plan on Ctrl-C; compiling alone has nothing to
    // stop, and the default action ends it at once (its outputs are whole or absent).
    if (until == relief::SceneJob::Until::Png || !o.resume.empty()) installInterruptHandler();
    relief::JobOutcome outcome;
    if (!o.resume.empty()) {
        outcome = relief::resumePlan(o.resume, executionOf(o.execution, o.common.noSandbox), o.keepPlan, diags,
                                     showing(progress));
    } else {
        bool ok = true;
        const relief::SceneJob job = sceneJob(o, until, ok);
        if (!ok) return code(Exit::BadInput);
        outcome = relief::runSceneJob(job, diags, showing(progress));
    }
    progress.done();
    if (outcome.status != relief::JobStatus::Ok)
        return reportFailure(outcome, diags, o.resume.empty() ? o.common.scene : o.resume);
    printDiagnostics(diags, true);  // warnings
    if (!o.common.quiet && outcome.compiled) printWritten(outcome, until == relief::SceneJob::Until::Png);
    if (!o.common.quiet && !outcome.compiled)
        std::cerr << fmt::format("wrote {} (from the plan {}; POV-Ray parse {:.2f} s, trace {:.2f} s)\n",
                                 terminalText(outcome.paths.still.string(), 500), terminalText(o.resume, 500),
                                 outcome.render.parseSeconds, outcome.render.traceSeconds);
    return code(Exit::Ok);
}

// `relief plan`: compile into a render plan and stop there.
int runPlan(const SceneOptions& o) {
    relief::Diagnostics diags;
    Progress progress(o.common.quiet);
    bool ok = true;
    const relief::SceneJob job = sceneJob(o, relief::SceneJob::Until::Png, ok);
    if (!ok) return code(Exit::BadInput);
    relief::PlannedJob planned = relief::planJob(job, diags, showing(progress));
    progress.done();
    if (planned.outcome.status != relief::JobStatus::Ok) return reportFailure(planned.outcome, diags, o.common.scene);
    printDiagnostics(diags, true);
    std::cout << planned.plan->dir.string() << '\n';
    if (!o.common.quiet)
        std::cerr << fmt::format("planned {} tile{} of {}: relief render-tile {} --tile K (K from 0), then relief "
                                 "finish {} (which writes {}, beside the plan)\n",
                                 planned.plan->tiles, planned.plan->tiles == 1 ? "" : "s",
                                 terminalText(planned.outcome.paths.still.string(), 500),
                                 terminalText(shellQuoted(planned.plan->dir.string()), 500),
                                 terminalText(shellQuoted(planned.plan->dir.string()), 500),
                                 terminalText((planned.plan->dir.parent_path() /
                                               planned.plan->still.filename()).string(), 500));
    return code(Exit::Ok);
}

struct TileOptions {
    std::string plan, tasks, tasksSha256;
    int tile = -1, index = -1, threads = 0;
    bool noSandbox = false;
};

// `relief render-tile`: one tile of a plan, or one task of a Slurm job's list (what a Slurm task runs).
int runRenderTile(const TileOptions& o) {
    installInterruptHandler();
    if (!o.tasks.empty()) {
        const std::string error = relief::execute::runListedTask({o.tasks, o.tasksSha256, o.index, !o.noSandbox},
                                                                 [] { return interrupted(); });
        if (error.empty()) return code(Exit::Ok);
        std::cerr << "relief: error: " << terminalText(error, 8000, true) << '\n';
        return code(interrupted() ? Exit::Interrupted : Exit::ToolFailed);
    }
    ExecutionOptions one;
    one.jobs = 1;
    relief::execute::Options e = executionOf(one, o.noSandbox);
    relief::Diagnostics diags;
    auto plan = relief::plan::readPlan(o.plan, diags);
    if (!plan) {
        printDiagnostics(diags, false);
        return code(Exit::BadInput);
    }
    if (o.tile < 0 || o.tile >= plan->tiles) {
        std::cerr << fmt::format("relief: error: --tile {}: the plan has tiles 0 to {}\n", o.tile, plan->tiles - 1);
        return code(Exit::BadInput);
    }
    const auto r = relief::execute::run({{plan->dir, o.tile}}, e, {});
    if (r.ok) return code(Exit::Ok);
    if (r.badInput && !r.at.file.empty()) {
        diags.error(r.at, r.error);
        printDiagnostics(diags, false);
    } else {
        std::cerr << "relief: error: " << terminalText(r.error, 8000, true) << '\n';
    }
    return code(interrupted() ? Exit::Interrupted : r.badInput ? Exit::BadInput : Exit::ToolFailed);
}

// `relief finish`: a plan whose tiles are all rendered, made into the still and its set.
int runFinish(const std::string& planDir, bool keepPlan) {
    relief::Diagnostics diags;
    relief::execute::Options none;
    none.cancelled = [] { return false; };
    auto plan = relief::plan::readPlan(planDir, diags);
    const auto lock = plan ? relief::plan::PlanLock::take(plan->dir, diags) : std::nullopt;
    if (!lock) {
        printDiagnostics(diags, false);
        return code(Exit::BadInput);
    }
    // A tile rendered but not right (another plan's, another POV-Ray's) is named by stitching; one not there is counted.
    std::vector<int> missing;
    for (int k = 0; k < plan->tiles; ++k)
        if (!std::filesystem::exists(relief::plan::tileRecordPath(*plan, k))) missing.push_back(k);
    if (!missing.empty()) {
        std::cerr << fmt::format("relief: error: {} of the plan's {} tiles are not rendered (the first: --tile {}): "
                                 "relief render-tile, or relief render --resume {}\n",
                                 missing.size(), plan->tiles, missing.front(), terminalText(shellQuoted(planDir), 500));
        return code(Exit::BadInput);
    }
    relief::OutputSet outputs;
    relief::JobOutcome outcome;
    if (!relief::finishPlan(*plan, outputs, false, true, keepPlan, outcome, diags)) {
        printDiagnostics(diags, false);
        return code(Exit::BadInput);
    }
    std::cerr << fmt::format("wrote {}\n", terminalText(plan->still.string(), 500));
    return code(Exit::Ok);
}

void addCommonSceneOptions(CLI::App* sub, SceneOptions& o, const char* outputHelp, bool sceneRequired) {
    auto* scene = sub->add_option("scene", o.common.scene,
                                  "scene file (TOML), or a DEM alone: a raster GDAL opens or a CSV of lon,lat,elev "
                                  "(relief makes the scene: relief init shows it)");
    if (sceneRequired) scene->required();
    sub->add_option("-o,--output", o.common.output, outputHelp);
    sub->add_option("--templates", o.common.templates,
                    "folder with scene.pov.in (default: $RELIEF_TEMPLATES, the installed share/relief/templates, or "
                    "the source tree's)");
    sub->add_option("--threads", o.common.threads, "refiner threads (0: all cores)")->check(CLI::Range(0, 256));
    sub->add_flag("-q,--quiet", o.common.quiet, "print errors only");
    sub->add_option("--set", o.common.sets,
                    "override a scene key: section.key=value, the value as TOML writes it (render.width=320, "
                    "subdivision.omega=1/32, camera.position=[-3.17,55.94,600], overlay.contours={interval_m=10}, "
                    "lighting.datetime=2026-06-21T09:00:00+01:00); repeatable");
}

// `render` renders the plan it makes; `plan` only writes it (and keeps it): how many tiles it
// has is its to say, where and how many at once are not.
void addRenderOptions(CLI::App* sub, SceneOptions& o, bool renders) {
    sub->add_option("--dump-net", o.dumpNet, "also write the control net (.csv or .asc)");
    sub->add_option("--dump-surface", o.dumpSurface, "also write the refined surface rendered (.csv or .asc)");
    sub->add_flag("--no-sandbox", o.common.noSandbox,
                  "run POV-Ray without its bubblewrap sandbox (only for scenes you trust; see docs/security.md)");
    sub->add_option("--plan", o.plan, "the render plan's folder (default: <still>.plan beside the still)");
    if (!renders) {
        addTilesOption(sub, o.execution);
        return;
    }
    addExecutionOptions(sub, o.execution, true,
                        "tiles at once (0: as many as cores here, each POV-Ray with its share of them; on Slurm, as "
                        "many as the cluster runs)");
    sub->add_flag("--keep-plan", o.keepPlan, "keep the plan (its .pov, PNGs and tiles) after the still is made");
}

}  // namespace

void addSceneCommands(CLI::App& app, std::vector<Command>& out) {
    auto o = std::make_shared<SceneOptions>();
    CLI::App* compile = app.add_subcommand("compile", "write the POV-Ray scene (.pov) and a JSON sidecar; no rendering");
    addCommonSceneOptions(compile, *o, "the .pov to write (default: out/<scene name>.pov)", true);
    compile->add_option("--dump-net", o->dumpNet,
                        "also write the control net: .csv (x,y,z in the frame, metres) or .asc (ESRI ASCII grid; "
                        "needs net.spacing_m)");
    compile->add_option("--dump-surface", o->dumpSurface,
                        "also write the refined surface, as rendered: .csv (x,y,z) or .asc (needs net.spacing_m)");
    out.push_back({compile, [o] { return runScene(*o, relief::SceneJob::Until::Pov); }});

    CLI::App* render = app.add_subcommand(
        "render", "compile into a render plan, render its tiles with POV-Ray (here or on Slurm) and finish the still "
                  "(.png, .pov and .json sidecar)");
    addCommonSceneOptions(render, *o, "the PNG to write (default: [render] output, else out/<scene name>.png)", false);
    addRenderOptions(render, *o, true);
    render->add_option("--resume", o->resume, "render a kept plan's missing tiles and finish it (no scene file)");
    render->callback([render, o] {
        if (o->resume.empty() && o->common.scene.empty()) throw CLI::RequiredError("scene");
        if (!o->resume.empty() && !o->common.scene.empty())
            throw CLI::ValidationError("--resume", "give a plan to resume or a scene to render, not both");
        (void)render;
    });
    out.push_back({render, [o] { return runScene(*o, relief::SceneJob::Until::Png); }});

    CLI::App* plan = app.add_subcommand(
        "plan", "compile into a render plan (a folder anyone who sees it can render: relief render-tile, relief "
                "finish) and print its path");
    addCommonSceneOptions(plan, *o, "the PNG the plan makes (default: [render] output, else out/<scene name>.png)",
                          true);
    addRenderOptions(plan, *o, false);
    out.push_back({plan, [o] { return runPlan(*o); }});

}

void addPlanStepCommands(CLI::App& app, std::vector<Command>& out) {
    auto t = std::make_shared<TileOptions>();
    CLI::App* tile = app.add_subcommand("render-tile", "render one tile of a render plan (what each Slurm task runs)");
    tile->add_option("plan", t->plan, "the render plan's folder");
    tile->add_option("--tile", t->tile, "the tile, from 0");
    tile->add_option("--tasks", t->tasks, "a task list (relief's Slurm job: a line a task) ...");
    tile->add_option("--tasks-sha256", t->tasksSha256, "... the SHA-256 it was submitted with ...");
    tile->add_option("--index", t->index, "... and the line of it to run, from 0 ($SLURM_ARRAY_TASK_ID)");
    tile->add_flag("--no-sandbox", t->noSandbox,
                   "run POV-Ray without its bubblewrap sandbox (only for plans you trust; a plan never turns it off)");
    tile->callback([t] {
        if (t->tasks.empty() == t->plan.empty() || t->tasks.empty() != t->tasksSha256.empty())
            throw CLI::ValidationError("render-tile", "give PLAN --tile K, or --tasks LIST --tasks-sha256 H --index K");
    });
    out.push_back({tile, [t] { return runRenderTile(*t); }});

    auto f = std::make_shared<std::pair<std::string, bool>>();
    CLI::App* finish = app.add_subcommand("finish", "make the still of a render plan whose tiles are all rendered");
    finish->add_option("plan", f->first, "the render plan's folder")->required();
    finish->add_flag("--keep-plan", f->second, "keep the plan after the still is made");
    out.push_back({finish, [f] { return runFinish(f->first, f->second); }});
}

}  // namespace relief::cli
