#include "cli/cli_common.h"

// relief compile, relief render: one scene file to a .pov, or all the way to a PNG.
#include <iostream>
#include <memory>

#include <fmt/format.h>

#include "core/atomic_file.h"
#include "pipeline.h"

namespace relief::cli {

namespace {

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
                        "override a scene key: section.key=value (e.g. render.width=320, "
                        "subdivision.omega=1/32); repeatable");
    };
    CLI::App* compile = app.add_subcommand(
        "compile", "write the POV-Ray scene (.pov) and a JSON sidecar; no rendering");
    addCommon(compile, "the .pov to write (default: out/<scene name>.pov)");
    compile->add_option("--dump-net", o->dumpNet,
                        "also write the control net: .csv (x,y,z in the frame, metres) or .asc "
                        "(ESRI ASCII grid; needs net.spacing_m)");
    out.push_back({compile, [o] { return runCompile(o->common, o->dumpNet); }});
    CLI::App* render = app.add_subcommand(
        "render", "compile, then render the still with POV-Ray (.png, .pov and .json sidecar)");
    addCommon(render, "the PNG to write (default: [render] output, else out/<scene name>.png)");
    render->add_option("--dump-net", o->dumpNet, "also write the control net (.csv or .asc)");
    out.push_back({render, [o] { return runRender(o->common, o->dumpNet); }});
}

}  // namespace relief::cli
