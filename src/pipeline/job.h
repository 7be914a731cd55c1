#pragma once
// A job: one scene file to a .pov and its sidecar (relief compile), or all
// the way to a still (relief render, test, sweep): compiled into a render
// plan (plan/), its tiles rendered (run_plans.h: here or on Slurm), the plan
// finished (the tiles stitched, the overlays drawn, the outputs written as one
// set); and a kept plan resumed.
#include <filesystem>
#include <memory>
#include <optional>
#include <vector>

#include "annotate/overlay.h"
#include "core/diagnostics.h"
#include "core/output_set.h"
#include "core/png_file.h"
#include "execute/execute.h"
#include "pipeline/compile.h"
#include "pipeline/progress.h"
#include "pipeline/run_plans.h"
#include "plan/plan.h"
#include "render/povray.h"

namespace relief {

/// Output paths derived from a scene: the .pov and the .json sidecar sit
/// beside the still (or stand in for it when only compiling).
struct OutputPaths {
    std::filesystem::path still, pov, sidecar;  ///< still: .png, .pdf or .svg
};
OutputPaths outputPathsFor(const std::filesystem::path& still);

/// One scene file to a .pov and its sidecar, or all the way to a PNG: what
/// `relief compile`, `relief render`, `relief test` and `relief sweep` do.
struct SceneJob {
    enum class Until { Pov, Png };
    Until until = Until::Png;
    std::filesystem::path scenePath;
    scene::SceneOverrides overrides;
    /// The PNG (Until::Png) or the .pov (Until::Pov) to write; "" = the
    /// scene's [render] output, else out/<scene>.png (a .pov: out/<scene>.pov).
    std::filesystem::path output;
    std::filesystem::path templatesDir;
    std::filesystem::path dumpNetPath;
    std::filesystem::path dumpSurfacePath;  ///< the refined surface rendered (--dump-surface)
    int threads = 0;            ///< refiner threads; 0 = all cores
    bool stillOnly = false;     ///< keep the PNG alone (relief test): no .pov, PNGs or sidecar beside it
    /// Where the outputs are declared and staged. Null: a set of the job's
    /// own, committed when the job succeeds. Given (relief sweep): the caller
    /// commits it with its own outputs, so that the whole sweep appears at once.
    OutputSet* outputs = nullptr;
    // Until::Png: the render plan and how its tiles are rendered.
    int tiles = 1;                          ///< strips of the still, each rendered on its own
    std::filesystem::path planDir;          ///< "" = <still>.plan beside the still
    bool keepPlan = false;                  ///< leave the plan after a render that succeeded
    execute::Options execution;             ///< here or on Slurm, how many at once, POV-Ray sandboxed or not
};

struct JobOutcome {
    JobStatus status = JobStatus::BadInput;
    OutputPaths paths;
    std::optional<CompileResult> compiled;
    render::RenderResult render;     ///< POV-Ray's timings (summed over the tiles) and error text (Until::Png)
    std::optional<annotate::OverlayRecord> overlays;  ///< what was drawn over the still
    std::filesystem::path plan;      ///< a render's plan, kept when the render did not finish (--resume)
    int tiles = 0;                   ///< the tiles rendered by this run
};

/// Loads, compiles and (Until::Png) renders; writes the .pov, the JSON sidecar
/// and the PNG as one set (core/output_set.h: nothing when a stage fails),
/// creating the output folders. Diagnostics go to `diags` (an output that
/// cannot be written too), progress to `progress` (may be empty). A render
/// compiles into a plan (planJob), renders its tiles (execute::run) and
/// finishes it (finishJob).
JobOutcome runSceneJob(const SceneJob& job, Diagnostics& diags, const ProgressFn& progress);

/// A job compiled into its render plan, not yet rendered.
struct PlannedJob {
    SceneJob job;
    JobOutcome outcome;                 ///< status Ok when planned; paths, compiled
    std::optional<plan::RenderPlan> plan;
    std::unique_ptr<OutputSet> ownOutputs;  ///< job.outputs, unless the caller gave a set
    std::optional<plan::PlanLock> lock;     ///< the plan is this job's while it renders
    OutputSet& outputs() { return job.outputs ? *job.outputs : *ownOutputs; }
};

/// Loads the scene, declares the outputs, compiles into the plan's folder
/// (made whole, then named; a stale plan there is replaced) and writes its
/// plan.json. outcome.status says how it went.
PlannedJob planJob(const SceneJob& job, Diagnostics& diags, const ProgressFn& progress);

/// The render plan's fields for a compiled scene: the still's size and
/// POV-Ray's options, where the still and sidecar go, the overlays and their
/// facts, the sidecar so far (compiling into plan.dir adds its files).
void describeRender(plan::RenderPlan& plan, const scene::SceneSpec& scene, const CompileResult& compiled,
                    const OutputPaths& paths, int tiles);

/// The plan's tiles stitched into the still's pixels, no overlays; nullopt with the reason.
std::optional<PngImage8> stitchedStill(const plan::RenderPlan& plan, Diagnostics& diags);

/// The still of a plan whose tiles are rendered: the tiles stitched, the
/// overlays drawn (`overlays` says what they show); nullopt with the reason.
std::optional<PngImage8> stillOfPlan(const plan::RenderPlan& plan, std::optional<annotate::OverlayRecord>& overlays,
                                     Diagnostics& diags);

/// A plan whose tiles are rendered, finished: the tiles stitched, the
/// overlays drawn, the still, the .pov, its PNGs and the sidecar (with every
/// tile's record) written into `outputs`; `commit`: and moved into place, the
/// plan removed (unless `keepPlan`). False with the reason in `diags`.
bool finishPlan(const plan::RenderPlan& plan, OutputSet& outputs, bool stillOnly, bool commit, bool keepPlan,
                JobOutcome& outcome, Diagnostics& diags);

/// `relief render --resume PLAN`: the plan's missing tiles rendered, then finished.
JobOutcome resumePlan(const std::filesystem::path& planDir, const execute::Options& execution, bool keepPlan,
                      Diagnostics& diags, const ProgressFn& progress);

}  // namespace relief
