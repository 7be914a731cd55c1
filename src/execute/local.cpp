// Tiles on this machine: `jobs` POV-Ray processes at once, each with its share of the cores.
#include "execute/local.h"

#include <algorithm>
#include <atomic>
#include <map>
#include <mutex>
#include <thread>

#include <fmt/format.h>

#include "core/stopwatch.h"
#include "plan/tiles.h"

namespace relief::execute {

Result runLocal(const std::vector<Task>& tasks, const std::vector<const plan::RenderPlan*>& plans,
                const Options& options, const std::function<void(const Progress&)>& progress) {
    Result result;
    const int cores = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
    const int jobs = std::clamp(options.jobs > 0 ? options.jobs : cores, 1, std::max<int>(1, static_cast<int>(tasks.size())));
    plan::TileOptions tile;
    tile.threads = std::max(1, cores / jobs);
    tile.sandbox = options.sandbox;
    std::atomic<bool> stop{false};
    tile.cancelled = [&] { return stop.load() || (options.cancelled && options.cancelled()); };
    std::atomic<size_t> next{0};
    std::mutex mutex;
    size_t done = 0;
    const auto t0 = Clock::now();
    result.taskErrors.assign(tasks.size(), "not rendered");
    auto worker = [&] {
        for (size_t i = next++; i < tasks.size() && !tile.cancelled(); i = next++) {
            const plan::RenderPlan& plan = *plans[i];
            plan::TileOptions one = tile;
            if (tasks.size() == 1) one.progress = options.povray;  // a still in one piece: POV-Ray's own progress
            const render::RenderResult r = plan::renderTile(plan, tasks[i].tile, one);
            std::string error;
            if (!r.ok && !r.cancelled) error = plan.tiles == 1 ? r.error  // one piece: POV-Ray's words are the whole story
                                                               : fmt::format("tile {} of {} (rows {}..{} of {}): {}",
                                                                             tasks[i].tile + 1, plan.tiles,
                                                                             plan::tileRows(plan.height, plan.tiles, tasks[i].tile).first,
                                                                             plan::tileRows(plan.height, plan.tiles, tasks[i].tile).last,
                                                                             plan.still.filename().string(), r.error);
            if (r.cancelled) error = "stopped";
            if (options.onTaskDone) options.onTaskDone(i, error);
            std::lock_guard lock(mutex);
            result.taskErrors[i] = error;
            if (!r.ok) {
                if (!r.cancelled && result.error.empty()) {
                    result.error = error;
                    result.badInput = r.cannotWriteOutput;
                }
                if (options.stopOnFailure) stop = true;  // the other tiles stop too: the still cannot be made
                continue;
            }
            ++done;
            if (progress) progress({done, tasks.size(), secondsSince(t0)});
        }
    };
    std::vector<std::thread> threads;
    for (int j = 1; j < jobs; ++j) threads.emplace_back(worker);
    worker();
    for (auto& t : threads) t.join();
    result.cancelled = result.error.empty() && options.cancelled && options.cancelled();
    result.ok = result.error.empty() && !result.cancelled && done == tasks.size();
    if (!result.ok && !options.stopOnFailure && !result.cancelled) result.badInput = false;
    return result;
}

}  // namespace relief::execute
