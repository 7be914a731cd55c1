#pragma once
// The one way render plans' tiles are rendered, for a still, a film's
// frames, a sweep's stills and a test suite's cases: the tiles each plan
// still lacks, through an executor (execute/: this machine's cores or a Slurm
// job array), their progress told the same way, a plan's end told as soon as
// its last tile is in.
#include <cstddef>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "core/diagnostics.h"
#include "execute/execute.h"
#include "pipeline/progress.h"
#include "plan/plan.h"

namespace relief {

enum class JobStatus { Ok, BadInput, ToolFailed, Cancelled };

/// How rendering some plans ended.
struct PlansRendered {
    JobStatus status = JobStatus::Ok;
    std::string error;            ///< the first failure: POV-Ray's words, or the executor's
    double wallSeconds = 0;
    int tiles = 0;                ///< the tiles this run rendered
};

struct PlansProgress {
    ProgressFn progress;     ///< may be empty
    std::string_view what;   ///< "tiles", "frames", "stills": what the line counts
    /// The units before these plans and in all (a film rendered in two runs:
    /// its first frame, then the rest); 0: these plans are all there are.
    size_t before = 0, total = 0;
    /// Told as soon as plan i's tiles are all rendered ("") or one failed
    /// (why), from whichever thread ran its last task; never for a plan whose
    /// tiles did not run (the executor failed before them, or stopped).
    std::function<void(size_t plan, const std::string& error)> onPlanDone;
};

/// Renders the tiles `plans` lack (with `execution`; its job folder, when it
/// names none, the first plan's slurm/). The line counts a lone plan's tiles,
/// else the plans ("frames: 3 of 120 rendered, 9 s, about 351 s left"). A
/// failure that is not a tile's (an unreadable plan, no cluster) goes to
/// `diags`.
PlansRendered renderPlans(const std::vector<const plan::RenderPlan*>& plans, const execute::Options& execution,
                          const PlansProgress& progress, Diagnostics& diags);

/// The plan's tiles still to render, as tasks for execute::run.
std::vector<execute::Task> tasksOf(const plan::RenderPlan& plan);

}  // namespace relief
