#include "pipeline/run_plans.h"

#include <algorithm>
#include <mutex>

#include <fmt/format.h>

#include "core/stopwatch.h"

namespace relief {

std::vector<execute::Task> tasksOf(const plan::RenderPlan& plan) {
    std::vector<execute::Task> tasks;
    for (int k : plan::missingTiles(plan)) tasks.push_back({plan.dir, k});
    return tasks;
}

namespace {

// "<what>: d of n rendered, s s, about s left", counting `units` made of `perUnit` tasks each.
ProgressEvent progressLine(const execute::Progress& p, const PlansProgress& told, size_t units, size_t perUnit) {
    const size_t total = told.total > 0 ? told.total : units;
    const size_t done = told.before + p.done / std::max<size_t>(1, perUnit);
    const std::string left = p.done > 0 && p.done < p.total
                                 ? fmt::format(", about {:.0f} s left",
                                               p.seconds / double(p.done) * double(p.total - p.done))
                                 : "";
    return {ProgressEvent::Stage::Tiles,
            fmt::format("{}: {} of {} rendered, {:.0f} s{}", told.what, done, total, p.seconds, left),
            static_cast<int>(100 * done / std::max<size_t>(1, total))};
}

}  // namespace

PlansRendered renderPlans(const std::vector<const plan::RenderPlan*>& plans, const execute::Options& execution,
                          const PlansProgress& told, Diagnostics& diags) {
    PlansRendered out;
    std::vector<execute::Task> tasks;
    std::vector<size_t> planOf, left(plans.size(), 0);
    for (size_t i = 0; i < plans.size(); ++i)
        for (const auto& t : tasksOf(*plans[i])) tasks.push_back(t), planOf.push_back(i), ++left[i];
    out.tiles = static_cast<int>(tasks.size());
    if (tasks.empty()) return out;
    execute::Options options = execution;
    if (options.jobDir.empty()) options.jobDir = plans.front()->dir / "slurm";
    const bool lone = plans.size() == 1;
    if (lone && told.progress)
        options.povray = [&](const render::RenderProgress& r) {
            told.progress({ProgressEvent::Stage::Rendering, r.text, r.percent});
        };
    std::mutex leftMutex;  // the executors tell of tasks from the threads that ran them
    if (told.onPlanDone)
        options.onTaskDone = [&](size_t task, const std::string& error) {
            const size_t i = planOf[task];
            {
                const std::lock_guard lock(leftMutex);
                if (left[i] == 0) return;  // told already: a tile of it failed
                left[i] = error.empty() ? left[i] - 1 : 0;
                if (left[i] > 0) return;
            }
            told.onPlanDone(i, error);
        };
    const size_t units = lone ? static_cast<size_t>(plans.front()->tiles) : plans.size();
    const size_t perUnit = lone ? 1 : std::max<size_t>(1, tasks.size() / plans.size());
    const auto t0 = Clock::now();
    const execute::Result r = execute::run(tasks, options, [&](const execute::Progress& p) {
        if (told.progress && !(lone && plans.front()->tiles == 1)) told.progress(progressLine(p, told, units, perUnit));
    });
    out.wallSeconds = secondsSince(t0);
    if (r.ok) return out;
    out.status = r.cancelled ? JobStatus::Cancelled : r.badInput ? JobStatus::BadInput : JobStatus::ToolFailed;
    out.error = r.error;
    if (r.badInput) diags.error(r.at, r.error);
    return out;
}

}  // namespace relief
