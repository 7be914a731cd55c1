#pragma once
// Tiles rendered many at once: on this machine's cores, or as a job array on
// a Slurm cluster. Input: tasks (a plan and a tile of it). Output: every
// task's tile and record in its plan's folder, or the first task that failed,
// named with what went wrong. The plans' folders must be seen by whoever runs
// the tasks (docs/distributed.md).
#include <cstddef>
#include <filesystem>
#include <functional>
#include <optional>
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
    /// POV-Ray in its bubblewrap sandbox. Only the command that runs POV-Ray
    /// turns it off (--no-sandbox), never a plan: on Slurm the batch script
    /// (which sbatch copies when the job is submitted) carries the choice.
    bool sandbox = true;
    /// Passed to sbatch, split into words as a POSIX shell splits them
    /// (quotes and backslashes honoured, nothing expanded): "--job-name='a b' --time=10".
    std::string slurmArgs;
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

/// --slurm-args split into sbatch's words as a POSIX shell splits them
/// (GLib's g_shell_parse_argv: quotes and backslashes, no expansion);
/// nullopt with `problem` when a quote is not closed.
std::optional<std::vector<std::string>> slurmArgWords(const std::string& text, std::string& problem);

/// A task list, as a Slurm task reads it: the file and the SHA-256 the
/// batch script holds for it (the list sits on a shared disk, the script is
/// sbatch's copy), the task's line, and how POV-Ray runs.
struct ListedTask {
    std::filesystem::path tasksFile;
    std::string tasksSha256;
    int index = -1;
    bool sandbox = true;
};

/// One task of a Slurm job array, as the batch script asks for it: line
/// `index` of the task list, once the list is the one submitted and the plan
/// it names verifies and is the one listed. Returns "" or why it failed.
std::string runListedTask(const ListedTask& task, const std::function<bool()>& cancelled = {});

}  // namespace relief::execute
