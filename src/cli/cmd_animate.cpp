#include "cli/cli_common.h"

// relief animate: the film of a scene's [animation] (pipeline/film.h).
#include <iostream>
#include <memory>

#include <fmt/format.h>

#include "core/text_escape.h"
#include "pipeline/film.h"

namespace relief::cli {

namespace {

struct AnimateOptions {
    CommonOptions common;
    ExecutionOptions execution;
    std::string frames;
    std::string resume;  ///< --resume DIR: a film's kept working folder
};

// `relief animate`: the film of a scene's [animation].
int runAnimate(const AnimateOptions& o) {
    relief::Diagnostics diags;
    Progress progress(o.common.quiet);
    installInterruptHandler();
    relief::AnimateJob job;
    job.scenePath = o.common.scene;
    if (!parseOverrides(o.common.sets, job.overrides)) return code(Exit::BadInput);
    job.output = o.common.output;
    job.framesDir = o.frames;
    job.templatesDir = findTemplates(o.common.templates);
    job.threads = o.common.threads;
    job.tiles = o.execution.tiles;
    job.execution = executionOf(o.execution, o.common.noSandbox);
    const relief::AnimateOutcome outcome =
        o.resume.empty() ? relief::runAnimateJob(job, diags, showing(progress))
                         : relief::resumeFilm(o.resume, job.execution, o.frames, diags, showing(progress));
    progress.done();
    const std::string kept = keptForResume("the film's frames are", "animate", outcome.workDir);
    switch (outcome.status) {
        case relief::JobStatus::Ok:
            break;
        case relief::JobStatus::Cancelled:
            printDiagnostics(diags, false);
            std::cerr << "relief: interrupted; nothing written\n" << kept;
            return code(Exit::Interrupted);
        case relief::JobStatus::ToolFailed:
            printDiagnostics(diags, false);
            std::cerr << "relief: error: " << terminalText(outcome.toolError, 8000, true) << " (nothing written)\n"
                      << kept;
            return code(Exit::ToolFailed);
        default:
            printDiagnostics(diags, false);
            std::cerr << kept;
            return code(Exit::BadInput);
    }
    printDiagnostics(diags, true);
    if (!o.common.quiet) {
        int kept = 0;
        for (const auto& f : outcome.frames) kept += f.fileNumber > 0;
        std::cerr << fmt::format(
            "wrote {} ({} frames{}, {} terrain{} compiled; compile {:.1f} s, render {:.1f} s, "
            "encode {:.1f} s) and {}\n",
            terminalText(outcome.film.string(), 500), kept,
            kept < int(outcome.frames.size()) ? fmt::format(", {} at night left out", outcome.frames.size() - kept)
                                              : "",
            outcome.terrains, outcome.terrains == 1 ? "" : "s", outcome.compileSeconds, outcome.renderSeconds,
            outcome.encodeSeconds, terminalText(outcome.sidecar.string(), 500));
    }
    return code(Exit::Ok);
}

}  // namespace

void addAnimateCommands(CLI::App& app, std::vector<Command>& out) {
    auto a = std::make_shared<AnimateOptions>();
    CLI::App* animate = app.add_subcommand(
        "animate",
        "render the film of the scene's [animation] (an orbit, a flyover, the sun through a day, keys varied): "
        "every frame through the render plan's executors, encoded by ffmpeg");
    animate->add_option("scene", a->common.scene, "scene file (TOML) with an [animation] section");
    animate->add_option("--resume", a->resume,
                        "finish a film a run did not: render the missing frames of its kept working folder "
                        "(<film>.film), encode it (no scene file)");
    animate->add_option("-o,--output", a->common.output,
                        "the film: .mp4 (H.264), .webm (VP9) or .gif (default: out/<scene name>.mp4)");
    animate->add_option("--frames", a->frames,
                        "also keep every frame's PNG in this folder (frame-00001.png, ...); with --resume, where a "
                        "film whose first run kept them keeps them");
    animate->add_option("--templates", a->common.templates, "folder with scene.pov.in");
    animate->add_option("--threads", a->common.threads, "refiner threads (0: all cores)")->check(CLI::Range(0, 256));
    animate->add_flag("-q,--quiet", a->common.quiet, "print errors only");
    animate->add_option("--set", a->common.sets, "override a scene key: section.key=value; repeatable");
    animate->add_flag("--no-sandbox", a->common.noSandbox, "run POV-Ray without its bubblewrap sandbox");
    addExecutionOptions(animate, a->execution, true,
                        "tiles at once, of every frame (0: as many as cores here; on Slurm, as many as the cluster "
                        "runs)");
    animate->callback([a] {
        if (a->resume.empty() && a->common.scene.empty()) throw CLI::RequiredError("scene");
        if (!a->resume.empty() && !a->common.scene.empty())
            throw CLI::ValidationError("--resume", "give a film's folder to resume or a scene, not both");
        if (!a->resume.empty() && (!a->common.output.empty() || !a->common.sets.empty()))
            throw CLI::ValidationError("--resume", "the film's folder says what it makes: no -o or --set");
    });
    out.push_back({animate, [a] { return runAnimate(*a); }});

}

}  // namespace relief::cli
