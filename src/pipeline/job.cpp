// A scene job: compile into a render plan, render its tiles (here or on
// Slurm), finish the still; or compile only. The outputs are one set
// (core/output_set.h), the plan kept when the render does not finish.
#include <unistd.h>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "core/atomic_file.h"
#include "core/input_file.h"
#include "core/png_file.h"
#include "core/stopwatch.h"
#include "core/text_escape.h"
#include "pipeline/job.h"
#include "pipeline/record.h"
#include "pipeline/run_plans.h"
#include "pipeline/working_folder.h"
#include "plan/tiles.h"

namespace relief {

namespace fs = std::filesystem;

namespace {

// The scene's [render] output, else out/<scene stem> with the extension.
fs::path defaultOutput(const fs::path& scenePath, const std::string& sceneOutput, const char* extension) {
    if (!sceneOutput.empty()) return sceneOutput;
    return fs::path("out") / (scenePath.stem().string() + extension);
}

// The job's outputs, named from the scene and the job.
OutputPaths jobPaths(const SceneJob& job, const LoadedScene& loaded) {
    if (job.until == SceneJob::Until::Png)
        return outputPathsFor(job.output.empty() ? defaultOutput(job.scenePath, loaded.scene.render.output, ".png")
                                                 : job.output);
    // Only compiling: the .pov is the output, and the scene's PNG name does not apply.
    OutputPaths paths;
    paths.pov = job.output.empty() ? defaultOutput(job.scenePath, "", ".pov") : job.output;
    paths.sidecar = paths.pov;
    paths.sidecar.replace_extension(".json");
    return paths;
}

// The job's outputs, declared before any work is done, so that two of them
// with one name, or an output over an input, are refused at once: the still,
// the .pov, the net dump, the sidecar last (the seal of the set).
void declareOutputs(const SceneJob& job, const LoadedScene& loaded, const OutputPaths& paths, OutputSet& outputs) {
    const bool render = job.until == SceneJob::Until::Png;
    const char* given = job.output.empty() ? nullptr : "-o";
    if (render) outputs.add(paths.still, given ? given : "the still");
    if (!job.stillOnly) {
        outputs.add(paths.pov, !render && given ? given : "the .pov");
        if (!job.dumpNetPath.empty()) outputs.add(job.dumpNetPath, "--dump-net");
        if (!job.dumpSurfacePath.empty()) outputs.add(job.dumpSurfacePath, "--dump-surface");
        outputs.add(paths.sidecar, "the sidecar", true);
    }
    const scene::SceneSpec& s = loaded.scene;
    outputs.addInput(job.scenePath, "the scene file");
    outputs.addInput(s.samples.path, "samples.path");
    if (!s.look.texture.drapeImage.empty()) outputs.addInput(s.look.texture.drapeImage, "texture.image");
    if (!s.look.texture.ramp.cptPath.empty())
        outputs.addInput(job.scenePath.parent_path() / s.look.texture.ramp.cptPath, "texture.cpt");
}

// The scene's own output name stays in the current folder, links resolved too.
bool outputStaysHere(const SceneJob& job, const LoadedScene& loaded, Diagnostics& diags) {
    const std::string& output = loaded.scene.render.output;
    if (!job.output.empty() || output.empty() || job.until != SceneJob::Until::Png || pathInside(output, "."))
        return true;
    diags.error(loaded.scene.render.locs.at("render.output"),
                fmt::format("render.output = \"{}\" leads out of the current folder through a link; give -o to write "
                            "there",
                            printableExcerpt(output, 200)));
    return false;
}

// A still written as a document (.pdf, .svg), or nothing: a PNG.
std::optional<annotate::DocumentFormat> documentFormatOf(const fs::path& still) {
    const std::string extension = asciiLower(still.extension().string());
    if (extension == ".pdf") return annotate::DocumentFormat::Pdf;
    if (extension == ".svg") return annotate::DocumentFormat::Svg;
    return std::nullopt;
}

// A still is a .png, or a .pdf or .svg with vector text over the image.
bool stillFormatKnown(const SceneJob& job, const OutputPaths& paths, Diagnostics& diags) {
    const std::string extension = asciiLower(paths.still.extension().string());
    if (job.until != SceneJob::Until::Png || extension == ".png" || documentFormatOf(paths.still)) return true;
    diags.error({paths.still.string(), 0, 0}, "a still is written as .png, .pdf or .svg (the image with the "
                                              "overlays as vector text over it): give -o one of them");
    return false;
}

CompileOptions compileOptions(const SceneJob& job, const OutputPaths& paths, const ProgressFn& progress) {
    CompileOptions c;
    c.povPath = paths.pov;
    c.templatesDir = job.templatesDir;
    c.dumpNetPath = job.dumpNetPath;
    c.dumpSurfacePath = job.dumpSurfacePath;
    c.threads = job.threads;
    c.progress = progress;
    return c;
}

// relief compile: the .pov, its PNGs and the sidecar, staged in the set.
void compileOnly(PlannedJob& p, const LoadedScene& loaded, Diagnostics& diags, const ProgressFn& progress) {
    OutputSet& outputs = p.outputs();
    CompileOptions copts = compileOptions(p.job, p.outcome.paths, progress);
    copts.writeAt = [&](const fs::path& final, std::string_view role) {
        return outputs.contains(final) ? outputs.staged(final) : outputs.add(final, role);
    };
    p.outcome.compiled = compileScene(loaded, copts, diags);
    if (!p.outcome.compiled) return;
    writeFileAtomically(outputs.staged(p.outcome.paths.sidecar),
                        sidecarText(sidecarJson(loaded.scene, *p.outcome.compiled, p.outcome.paths)));
    p.outcome.status = JobStatus::Ok;
}

// Whether `dir` holds a render plan of some relief (its plan.json says "relief_plan").
bool isRenderPlan(const fs::path& dir) {
    std::string problem;
    const auto text = readInputFile(dir / "plan.json", 1 << 26, problem);
    if (!text) return false;
    const auto j = nlohmann::json::parse(*text, nullptr, false);
    return j.is_object() && j.contains("relief_plan");
}

// A render: the compiled scene and its facts in a plan, made in a private
// folder and named when whole.
void compileIntoPlan(PlannedJob& p, const LoadedScene& loaded, Diagnostics& diags, const ProgressFn& progress) {
    const SceneJob& job = p.job;
    const OutputPaths& paths = p.outcome.paths;
    const fs::path asked = job.planDir.empty() ? paths.still.parent_path() / (paths.still.stem().string() + ".plan")
                                               : job.planDir;
    createParentFolder(asked);
    PrivateFolder building(asked.has_parent_path() ? asked.parent_path() : fs::path("."), "plan");
    p.lock = plan::PlanLock::take(building.path());  // held until the render ends; it moves with the folder
    plan::RenderPlan plan;
    plan.dir = building.path();
    CompileOptions copts = compileOptions(job, paths, progress);
    copts.writeAt = [&](const fs::path& final, std::string_view role) {
        plan::PlanFile f{final.filename().string(), fs::absolute(final), std::string(role), ""};
        // The plan holds its outputs by file name, and writes them beside itself when read back.
        const auto taken = [&](const plan::PlanFile& g) { return g.name == f.name; };
        if (plan.pov.name == f.name || std::any_of(plan.reads.begin(), plan.reads.end(), taken) ||
            std::any_of(plan.extras.begin(), plan.extras.end(), taken))
            throw OutputError(final, fmt::format("has the file name of another output of the render ({}): a render "
                                                 "plan holds its outputs by name; give {} another name",
                                                 f.name, role));
        if (role == "the .pov") plan.pov = f;
        else if (role == "--dump-net" || role == "--dump-surface") plan.extras.push_back(f);
        else plan.reads.push_back(f);
        return plan.dir / f.name;
    };
    p.outcome.compiled = compileScene(loaded, copts, diags);
    if (!p.outcome.compiled) return;
    describeRender(plan, loaded.scene, *p.outcome.compiled, paths, job.tiles);
    plan::copyTemplates(plan, job.templatesDir);
    if (!writePlan(plan, diags)) return;
    // Named when whole (the lock goes with it); another render onto the same
    // name may take the name first, and this one takes the next.
    static const WorkingFolderKind kPlanFolder{"the render plan", "a render plan", "give --plan", isRenderPlan};
    const std::optional<fs::path> dir = nameWorkingFolder(building.path(), asked, kPlanFolder, diags);
    if (!dir) return;
    plan.dir = *dir;
    p.plan = std::move(plan);
    p.outcome.plan = p.plan->dir;
    p.outcome.status = JobStatus::Ok;
}

// A plan's file in the set: a hard link (no copy of a 100 MB .pov), else a copy.
void stagePlanFile(const plan::RenderPlan& plan, const plan::PlanFile& f, OutputSet& outputs) {
    linkOrCopy(plan.dir / f.name, outputs.contains(f.final) ? outputs.staged(f.final) : outputs.add(f.final, f.role));
}

// An output that cannot be made is reported at its file; any other I/O failure as it is.
void reportWriteFailure(const std::runtime_error& e, Diagnostics& diags) {
    if (const auto* out = dynamic_cast<const OutputError*>(&e))
        diags.error(out->at(), out->problem());
    else
        diags.error({}, e.what());
}

// The still written once: a PNG (with its resolution when render.dpi gives
// one), or a document with the ray-traced image in it and the overlays as
// vectors and text over it.
bool writeStill(const plan::RenderPlan& plan, OutputSet& outputs, RenderFacts& facts, Diagnostics& diags) {
    const auto document = documentFormatOf(plan.still);
    std::optional<annotate::OverlayRecord> record;
    auto still = document ? stitchedStill(plan, diags) : stillOfPlan(plan, record, diags);
    if (!still) return false;
    const fs::path at = outputs.contains(plan.still) ? outputs.staged(plan.still) : outputs.add(plan.still, "the still");
    if (!document) {
        facts.overlays = record;
        writePngAtomically(at, {still->width, still->height, still->channels, false, still->pixels.data(), -1, plan.dpi});
        return true;
    }
    annotate::DocumentRequest request{*document, at, plan.dpi > 0 ? plan.dpi : scene::RenderSpec::kDocumentDpi,
                                      plan.overlays, plan.overlaySpec, plan.overlayFacts};
    annotate::OverlayRecord drawn;
    if (!annotate::writeDocument(*still, request, {shownPath(plan.still).string(), 0, 0}, diags, &drawn)) return false;
    if (plan.overlays) facts.overlays = drawn;
    return true;
}

}  // namespace

OutputPaths outputPathsFor(const std::filesystem::path& still) {
    OutputPaths p;
    p.still = still;
    p.pov = still;
    p.pov.replace_extension(".pov");
    p.sidecar = still;
    p.sidecar.replace_extension(".json");
    return p;
}

void describeRender(plan::RenderPlan& plan, const scene::SceneSpec& s, const CompileResult& compiled,
                    const OutputPaths& paths, int tiles) {
    plan.povrayVersion = plan::povrayVersion();
    plan.width = s.render.width;
    plan.height = s.render.height;
    plan.tiles = std::clamp(tiles, 1, s.render.height);
    const scene::QualityLevel& quality = scene::qualityLevel(s.render.quality);
    plan.antialias = s.render.antialias && quality.antialias;
    plan.antialiasThreshold = quality.antialiasThreshold;
    plan.antialiasDepth = quality.antialiasDepth;
    plan.alpha = s.render.background == scene::Background::Transparent;
    plan.timeoutS = s.render.timeoutS;
    plan.dpi = s.render.dpi.value_or(0);
    plan.still = fs::absolute(paths.still);
    plan.sidecar = fs::absolute(paths.sidecar);
    plan.overlays = annotate::overlaysWanted(s.overlay, s.render.width);
    plan.overlaySpec = s.overlay;
    plan.overlaySpec.locs = {};
    plan.overlayFacts = compiled.view.overlayFacts;
    plan.sidecar0 = sidecarJson(s, compiled, paths);
}

std::optional<PngImage8> stitchedStill(const plan::RenderPlan& plan, Diagnostics& diags) {
    return plan::stitchTiles(plan, diags);
}

std::optional<PngImage8> stillOfPlan(const plan::RenderPlan& plan, std::optional<annotate::OverlayRecord>& overlays,
                                     Diagnostics& diags) {
    auto still = stitchedStill(plan, diags);
    if (!still || !plan.overlays) return still;
    annotate::OverlayRecord record;
    if (!annotate::drawOverlays(*still, plan.overlaySpec, plan.overlayFacts, {shownPath(plan.still).string(), 0, 0},
                                diags, &record))
        return std::nullopt;
    overlays = record;
    return still;
}

PlannedJob planJob(const SceneJob& job, Diagnostics& diags, const ProgressFn& progress) {
    PlannedJob p;
    p.job = job;
    if (!job.outputs) p.ownOutputs = std::make_unique<OutputSet>();
    try {
        if (progress) progress({ProgressEvent::Stage::Reading, "reading " + job.scenePath.string(), -1});
        auto loaded = loadScene(job.scenePath, diags, job.overrides);
        if (!loaded) return p;
        p.outcome.paths = jobPaths(job, *loaded);
        if (!outputStaysHere(job, *loaded, diags) || !stillFormatKnown(job, p.outcome.paths, diags)) return p;
        declareOutputs(job, *loaded, p.outcome.paths, p.outputs());
        if (progress)
            progress({ProgressEvent::Stage::Compiling,
                      fmt::format("compiling {} ({}, {})", job.scenePath.string(), loaded->resolved.family,
                                  depthLabel(loaded->scene.subdivision)),
                      -1});
        if (job.until == SceneJob::Until::Pov) compileOnly(p, *loaded, diags, progress);
        else compileIntoPlan(p, *loaded, diags, progress);
    } catch (const std::runtime_error& e) {  // an output that cannot be made: bad input like any other
        reportWriteFailure(e, diags);
        p.outcome.status = JobStatus::BadInput;
    }
    return p;
}


bool finishPlan(const plan::RenderPlan& plan, OutputSet& outputs, bool stillOnly, bool commit, bool keepPlan,
                JobOutcome& outcome, Diagnostics& diags) {
    const auto t0 = Clock::now();
    try {
        RenderFacts facts;
        facts.perspective = plan.overlayFacts.perspective;
        if (!writeStill(plan, outputs, facts, diags)) return false;
        for (int k = 0; k < plan.tiles; ++k) {
            std::string problem;
            if (auto r = plan::readTileRecord(plan, k, problem)) facts.tiles.push_back(*r);
        }
        for (const auto& t : facts.tiles) {
            outcome.render.parseSeconds += t.parseSeconds;
            outcome.render.traceSeconds += t.traceSeconds;
            outcome.render.wallSeconds = std::max(outcome.render.wallSeconds, t.wallSeconds);
        }
        outcome.render.ok = true;
        outcome.overlays = facts.overlays;
        if (!stillOnly) {
            stagePlanFile(plan, plan.pov, outputs);
            for (const auto& f : plan.reads) stagePlanFile(plan, f, outputs);
            for (const auto& f : plan.extras) stagePlanFile(plan, f, outputs);
            nlohmann::ordered_json sidecar = plan.sidecar0;
            facts.wallSeconds = outcome.render.wallSeconds;
            facts.finishSeconds = secondsSince(t0);
            addRenderToSidecar(sidecar, facts);
            const fs::path at =
                outputs.contains(plan.sidecar) ? outputs.staged(plan.sidecar) : outputs.add(plan.sidecar, "the sidecar", true);
            writeFileAtomically(at, sidecarText(sidecar));
        }
        if (!commit) return true;
        outputs.commit();
    } catch (const std::runtime_error& e) {
        reportWriteFailure(e, diags);
        return false;
    }
    if (!keepPlan) {
        std::error_code ec;
        fs::remove_all(plan.dir, ec);
        outcome.plan.clear();
    }
    return true;
}

namespace {

// The tiles rendered (POV-Ray sandboxed unless `execution` says not); the outcome says how, when not all were.
bool renderTiles(const plan::RenderPlan& plan, const execute::Options& execution, JobOutcome& outcome,
                 Diagnostics& diags, const ProgressFn& progress) {
    const PlansRendered r = renderPlans({&plan}, execution, {progress, "tiles", 0, 0, {}}, diags);
    outcome.tiles = r.tiles;
    outcome.render.wallSeconds = r.wallSeconds;
    outcome.status = r.status;
    outcome.render.error = r.error;
    return r.status == JobStatus::Ok;
}

}  // namespace

JobOutcome runSceneJob(const SceneJob& job, Diagnostics& diags, const ProgressFn& progress) {
    PlannedJob p = planJob(job, diags, progress);
    if (p.outcome.status != JobStatus::Ok) return std::move(p.outcome);
    if (job.until == SceneJob::Until::Pov) {
        if (!job.outputs) {
            try {
                p.ownOutputs->commit();
            } catch (const std::runtime_error& e) {
                reportWriteFailure(e, diags);
                p.outcome.status = JobStatus::BadInput;
            }
        }
        return std::move(p.outcome);
    }
    if (!renderTiles(*p.plan, job.execution, p.outcome, diags, progress)) return std::move(p.outcome);
    if (progress) progress({ProgressEvent::Stage::Finishing, "finishing " + p.outcome.paths.still.string(), -1});
    if (!finishPlan(*p.plan, p.outputs(), job.stillOnly, !job.outputs, job.keepPlan || job.outputs, p.outcome, diags))
        p.outcome.status = JobStatus::BadInput;
    return std::move(p.outcome);
}

JobOutcome resumePlan(const fs::path& planDir, const execute::Options& execution, bool keepPlan, Diagnostics& diags,
                      const ProgressFn& progress) {
    JobOutcome outcome;  // without a plan to resume until it is read and ours
    auto plan = plan::readPlan(planDir, diags);
    if (!plan || !plan::checkRenderable(*plan, diags)) return outcome;
    const auto lock = plan::PlanLock::take(plan->dir, diags);
    if (!lock) return outcome;
    outcome.plan = planDir;
    outcome.paths = outputPathsFor(plan->still);
    if (!renderTiles(*plan, execution, outcome, diags, progress)) return outcome;
    OutputSet outputs;
    outcome.status = finishPlan(*plan, outputs, false, true, keepPlan, outcome, diags) ? JobStatus::Ok : JobStatus::BadInput;
    return outcome;
}

}  // namespace relief
