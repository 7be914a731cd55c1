#include "execute/execute.h"

#include <algorithm>
#include <cstdlib>
#include <map>
#include <memory>
#include <sstream>

#include <fmt/format.h>

#include "core/hash.h"
#include "core/input_file.h"
#include "core/text_escape.h"
#include "execute/local.h"
#include "plan/tiles.h"

namespace relief::execute {

namespace fs = std::filesystem;

Result run(const std::vector<Task>& tasks, const Options& options, const std::function<void(const Progress&)>& progress) {
    Result result;
    if (tasks.empty()) {
        result.ok = true;
        return result;
    }
    // Each plan read once, however many of its tiles are tasks.
    std::map<fs::path, std::unique_ptr<plan::RenderPlan>> read;
    std::vector<const plan::RenderPlan*> plans;
    for (const auto& t : tasks) {
        auto& p = read[t.plan];
        if (!p) {
            Diagnostics diags;
            auto loaded = plan::readPlan(t.plan, diags);
            if (loaded && !plan::checkRenderable(*loaded, diags)) loaded.reset();
            if (!loaded) {
                result.badInput = true;
                result.at = diags.all().front().loc;
                result.error = diags.all().front().message;
                return result;
            }
            p = std::make_unique<plan::RenderPlan>(std::move(*loaded));
        }
        plans.push_back(p.get());
    }
    return options.executor == Executor::Slurm ? runSlurm(tasks, plans, options, progress)
                                               : runLocal(tasks, plans, options, progress);
}

std::string runListedTask(const ListedTask& task, const std::function<bool()>& cancelled) {
    std::string problem;
    const auto list = readInputFile(task.tasksFile, 64'000'000, problem);
    if (!list)
        return fmt::format("{}: cannot read the task list: {} (the job's folder must be on a filesystem every node sees)",
                           task.tasksFile.string(), problem);
    Sha256 h;
    h.add(*list);
    if (h.hex() != task.tasksSha256)
        return fmt::format("{}: the task list is not the one submitted (its SHA-256 changed since): submit the job again",
                           task.tasksFile.string());
    std::istringstream in(*list);
    std::string line;
    for (int i = 0; i <= task.index && std::getline(in, line); ++i) {
    }
    // tile, the plan's hash, the plan's folder
    const auto tab = line.find('\t'), tab2 = tab == std::string::npos ? tab : line.find('\t', tab + 1);
    if (task.index < 0 || tab2 == std::string::npos)
        return fmt::format("{}: has no task {}", task.tasksFile.string(), task.index);
    const int tile = std::atoi(line.substr(0, tab).c_str());
    Diagnostics diags;
    const auto plan = plan::readPlan(line.substr(tab2 + 1), diags);
    if (plan && plan->hash != line.substr(tab + 1, tab2 - tab - 1))
        diags.error({(plan->dir / "plan.json").string(), 0, 0},
                    "the render plan is not the one submitted (another plan was made in its folder since): submit "
                    "the job again");
    if (!plan || diags.hasErrors() || !plan::checkRenderable(*plan, diags))
        return diags.all().front().loc.file + ": " + diags.all().front().message;
    if (tile < 0 || tile >= plan->tiles) return fmt::format("the plan {} has no tile {}", plan->dir.string(), tile);
    // The CPUs Slurm gave the task (sbatch --cpus-per-task, through --slurm-args), one by default.
    plan::TileOptions options;
    const char* cpus = std::getenv("SLURM_CPUS_PER_TASK");
    options.threads = cpus ? std::max(1, std::atoi(cpus)) : 1;
    options.sandbox = task.sandbox;
    options.cancelled = cancelled;
    const render::RenderResult r = plan::renderTile(*plan, tile, options);
    return r.ok ? "" : fmt::format("tile {} of {}: {}", tile + 1, plan->tiles, r.error);
}

}  // namespace relief::execute
