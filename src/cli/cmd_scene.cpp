#include "cli/cli_common.h"

// relief compile, relief render: one scene file to a .pov, or all the way to a PNG.
#include <iostream>
#include <memory>

#include <fmt/format.h>

#include "core/text_escape.h"

#include "pipeline.h"

namespace relief::cli {

namespace {

// `relief compile` (until the .pov) and `relief render` (until the PNG).
int runScene(const CommonOptions& o, const std::string& dumpNet, relief::SceneJob::Until until) {
    relief::Diagnostics diags;
    Progress progress(o.quiet);
    relief::SceneJob job;
    job.until = until;
    job.scenePath = o.scene;
    if (!parseOverrides(o.sets, job.overrides)) return code(Exit::BadInput);
    job.output = o.output;
    job.templatesDir = findTemplates(o.templates);
    job.dumpNetPath = dumpNet;
    job.threads = o.threads;
    job.sandbox = !o.noSandbox;
    const auto outcome = relief::runSceneJob(job, diags, [&](const relief::ProgressEvent& e) {
        // Each stage on a line of its own; the render's progress rewrites its line.
        if (e.stage == relief::ProgressEvent::Stage::Compiling && e.percent < 0) progress.done();
        progress.show(e);
    });
    progress.done();
    if (outcome.status == relief::JobStatus::BadInput) {
        printDiagnostics(diags, false);
        return code(Exit::BadInput);
    }
    printDiagnostics(diags, true);  // warnings
    if (outcome.status == relief::JobStatus::ToolFailed) {
        std::cerr << "relief: POV-Ray failed on the scene compiled from " << relief::terminalText(job.scenePath.string(), 500)
                  << " (nothing written; relief compile writes the .pov to look at):\n"
                  << relief::terminalText(outcome.render.error, 8000, true) << '\n';
        return code(Exit::ToolFailed);
    }
    if (!o.quiet) {
        const auto& c = *outcome.compiled;
        std::cerr << fmt::format("scheme {}: {}\n", c.schemeFamily, c.certified);
        if (c.autoDepth)
            std::cerr << relief::autoDepthSummary(*c.autoDepth, c.scene.subdivision.toleranceM) << '\n';
        // What POV-Ray gets: every vertex, the adaptive mesh, or the height field's PNGs.
        switch (c.geometry.kind) {
            case scene::GeometryKind::HeightField:
                std::cerr << fmt::format("wrote {} (a height field of {} x {} nodes: {}, {})\n",
                                         outcome.paths.pov.string(), c.estimate.rows, c.estimate.cols,
                                         c.heightPng.string(), c.drapePng.string());
                break;
            case scene::GeometryKind::Adaptive:
                std::cerr << fmt::format("wrote {} (an adaptive mesh2: {} triangles of the full {:.0f}, {:.1f} MB)\n",
                                         outcome.paths.pov.string(), c.meshTriangles, c.estimate.triangles,
                                         c.povBytes / 1e6);
                break;
            default:
                std::cerr << fmt::format("wrote {} ({} x {} vertices, {} triangles, {:.1f} MB)\n",
                                         outcome.paths.pov.string(), c.estimate.rows, c.estimate.cols,
                                         c.meshTriangles, c.povBytes / 1e6);
        }
        if (until == relief::SceneJob::Until::Png)
            std::cerr << fmt::format("wrote {} ({} x {}; POV-Ray parse {:.2f} s, trace {:.2f} s)\n",
                                     outcome.paths.png.string(), c.scene.render.width,
                                     c.scene.render.height, outcome.render.parseSeconds,
                                     outcome.render.traceSeconds);
    }
    return code(Exit::Ok);
}

}  // namespace

void addSceneCommands(CLI::App& app, std::vector<Command>& out) {
    struct Options {
        CommonOptions common;
        std::string dumpNet;
    };
    auto o = std::make_shared<Options>();
    auto addCommon = [o](CLI::App* sub, const char* outputHelp) {
        sub->add_option("scene", o->common.scene, "scene file (TOML)")->required();
        sub->add_option("-o,--output", o->common.output, outputHelp);
        sub->add_option("--templates", o->common.templates,
                        "folder with scene.pov.in (default: $RELIEF_TEMPLATES, the installed "
                        "share/relief/templates, or the source tree's)");
        sub->add_option("--threads", o->common.threads, "refiner and POV-Ray threads (0: all cores)")
            ->check(CLI::Range(0, 256));
        sub->add_flag("-q,--quiet", o->common.quiet, "print errors only");
        sub->add_option("--set", o->common.sets,
                        "override a scene key: section.key=value, the value as TOML writes it (render.width=320, "
                        "subdivision.omega=1/32, camera.position=[-3.17,55.94,600], "
                        "overlay.contours={interval_m=10}, lighting.datetime=2026-06-21T09:00:00+01:00); repeatable");
    };
    CLI::App* compile = app.add_subcommand(
        "compile", "write the POV-Ray scene (.pov) and a JSON sidecar; no rendering");
    addCommon(compile, "the .pov to write (default: out/<scene name>.pov)");
    compile->add_option("--dump-net", o->dumpNet,
                        "also write the control net: .csv (x,y,z in the frame, metres) or .asc "
                        "(ESRI ASCII grid; needs net.spacing_m)");
    out.push_back({compile, [o] { return runScene(o->common, o->dumpNet, relief::SceneJob::Until::Pov); }});
    CLI::App* render = app.add_subcommand(
        "render", "compile, then render the still with POV-Ray (.png, .pov and .json sidecar)");
    addCommon(render, "the PNG to write (default: [render] output, else out/<scene name>.png)");
    render->add_option("--dump-net", o->dumpNet, "also write the control net (.csv or .asc)");
    render->add_flag("--no-sandbox", o->common.noSandbox, "run POV-Ray without its bubblewrap sandbox (only for scenes you trust; see docs/security.md)");
    out.push_back({render, [o] { return runScene(o->common, o->dumpNet, relief::SceneJob::Until::Png); }});
}

}  // namespace relief::cli
