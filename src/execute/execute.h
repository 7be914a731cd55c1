#pragma once
// Tiles rendered many at once: on this machine's cores, or as a job array on
// a Slurm cluster. Input: tasks (a plan and a tile of it). Output: every
// task's tile and record in its plan's folder, or the first task that failed,
// named with what went wrong. The plans' folders must be seen by whoever runs
// the tasks (docs/distributed.md).
#include <cstddef>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "core/source_loc.h"
#include "render/povray.h"

namespace relief::execute {

struct Task {
    std::filesystem::path plan;  ///< the plan's folder (absolute)
    int tile = 0;
};

enum class Executor { Local, Slurm };

struct Options {
    Executor executor = Executor::Local;
    /// Tasks at once: local, POV-Ray processes (0: as many as cores, each with
    /// its share of the threads); Slurm, array tasks running at once (0: as
    /// many as the cluster gives).
    int jobs = 0;
    std::string slurmArgs;             ///< passed to sbatch, split at spaces ("--partition=x --time=10")
    std::filesystem::path jobDir;      ///< Slurm: the batch script, the task list and the logs
    std::function<bool()> cancelled;   ///< asked often; true stops every task (scancel on Slurm)
    render::ProgressFn povray;         ///< POV-Ray's own lines, when one task runs here alone (may be empty)
    /// true: the first task that fails stops the rest (one still's tiles);
    /// false: every task runs, each failure its own (a test suite's cases).
    bool stopOnFailure = true;
    /// Told of each task as it ends ("" or why it failed), from whichever
    /// thread ran it: a caller can finish a plan as soon as its tiles are in.
    std::function<void(size_t task, const std::string& error)> onTaskDone;
};

struct Progress {
    size_t done = 0, total = 0;
    double seconds = 0;  ///< since the start
};

struct Result {
    bool ok = false;
    bool cancelled = false;
    bool badInput = false;  ///< not a task's failure: Slurm missing or not answering, a plan unreadable
    std::string error;      ///< the first failure: "tile 3 of 7: ...", "task 2 (Slurm job 15_2) FAILED: ..."
    SourceLoc at;           ///< where that failure belongs, when it is a file's (an unreadable plan)
    std::vector<std::string> taskErrors;  ///< per task: "" or why it failed (or did not run)
};

/// Runs every task; `progress` (may be empty) hears each one that finishes.
Result run(const std::vector<Task>& tasks, const Options& options, const std::function<void(const Progress&)>& progress);

/// One task of a Slurm job array, as the batch script asks for it: line
/// `index` of the task list `tasksFile`. Returns "" or why it failed.
std::string runListedTask(const std::filesystem::path& tasksFile, int index,
                          const std::function<bool()>& cancelled = {});

}  // namespace relief::execute
