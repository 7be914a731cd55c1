// Tiles on a Slurm cluster: one job array, a task per tile, each running this
// same relief on its plan (`relief render-tile --tasks LIST --index K`). The
// command waits for the array by polling squeue (sbatch --wait never returns
// for some failed arrays), and Ctrl-C cancels it.
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>
#include <thread>

#include <fmt/format.h>
#include <glib.h>

#include "core/atomic_file.h"
#include "core/hash.h"
#include "core/input_file.h"
#include "core/stopwatch.h"
#include "core/text_escape.h"
#include "execute/command.h"
#include "execute/local.h"

namespace relief::execute {

namespace {

namespace fs = std::filesystem;

// The states a task of an array ends in (squeue's long names).
bool finalState(const std::string& s) {
    return s == "COMPLETED" || s == "FAILED" || s == "LOST" || s == "CANCELLED" || s == "TIMEOUT" || s == "NODE_FAIL" ||
           s == "OUT_OF_MEMORY" || s == "PREEMPTED" || s == "BOOT_FAIL" || s == "DEADLINE";
}

// Why the cluster cannot take the job, or "": its tools are here and it answers.
std::string clusterProblem() {
    for (const char* tool : {"sbatch", "squeue", "scancel", "sinfo"})
        if (runCommand({"sh", "-c", std::string("command -v ") + tool}).status != 0)
            return fmt::format("Slurm's {} is not on PATH (Debian: apt-get install slurm-client)", tool);
    // sinfo waits for the controller as long as slurm.conf's MessageTimeout (60 s by default): a cluster that
    // answers at all answers sooner.
    constexpr double kAnswerSeconds = 10;
    const CommandOutput info = runCommand({"sinfo", "-h", "-o", "%P"}, {{}, kAnswerSeconds});
    if (info.status == 0) return "";
    std::string problem = info.timedOut ? fmt::format("no Slurm cluster answers (sinfo had no answer in {:.0f} s: is "
                                                      "slurmctld running, and is this its slurm.conf?)",
                                                      kAnswerSeconds)
                                        : fmt::format("no Slurm cluster answers (sinfo: {})", firstLine(info.output));
    if (!std::getenv("SLURM_CONF"))
        problem += "; SLURM_CONF is not set: point it at the cluster's slurm.conf (or install the cluster's "
                   "configuration in /etc/slurm)";
    return problem;
}

// The relief that runs the tasks: this program, or the relief beside it when
// this is relief-images (relief test and sweep), in a build tree or installed
// (<prefix>/libexec/relief/relief-images, <prefix>/bin/relief). Every node
// must have it at that path.
std::string reliefProgram() {
    std::error_code ec;
    const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
    if (ec) return "relief";
    if (exe.filename() != "relief-images") return exe.string();
    for (const fs::path& p : {exe.parent_path() / "relief", exe.parent_path().parent_path().parent_path() / "bin" / "relief"})
        if (fs::exists(p, ec)) return p.string();
    return "relief";
}

// The task list (a line a task: the tile, the plan's hash, the plan's folder,
// tab-separated) and the batch script that runs line $SLURM_ARRAY_TASK_ID of
// it. sbatch keeps its own copy of the script when the job is submitted, so
// what the script holds (the list's SHA-256, whether POV-Ray is sandboxed)
// cannot be changed on the shared disk afterwards; the list's lines then pin
// each plan's hash.
fs::path writeJob(const std::vector<Task>& tasks, const std::vector<const plan::RenderPlan*>& plans, bool sandbox,
                  const fs::path& dir) {
    makeOwnFolder(dir);
    makeOwnFolder(dir / "logs");
    std::string list;
    for (size_t i = 0; i < tasks.size(); ++i)
        list += fmt::format("{}\t{}\t{}\n", tasks[i].tile, plans[i]->hash, tasks[i].plan.string());
    writeFileAtomically(dir / "tasks.txt", list);
    Sha256 h;
    h.add(list);
    const std::string script = fmt::format(
        "#!/bin/sh\n"
        "# relief's tiles as a Slurm job array: task $SLURM_ARRAY_TASK_ID renders line $SLURM_ARRAY_TASK_ID of the\n"
        "# task list (counted from 0), if the list is the one submitted. The plans' folders must be on a filesystem\n"
        "# every node sees.\n"
        "exec {} render-tile --tasks {} --tasks-sha256 {} --index \"$SLURM_ARRAY_TASK_ID\"{}\n",
        shellQuoted(reliefProgram()), shellQuoted(fs::absolute(dir / "tasks.txt").string()), h.hex(),
        sandbox ? "" : " --no-sandbox");
    writeFileAtomically(dir / "job.sh", script);
    return dir / "job.sh";
}

// sbatch's file names are patterns (%a: the task's index, %x: the job's name,
// %%: a %): a folder's own % is written %%.
std::string slurmPattern(const fs::path& dir, std::string_view pattern) {
    std::string out;
    for (const char c : dir.string()) out += c == '%' ? std::string("%%") : std::string(1, c);
    return out + "/" + std::string(pattern);
}

// The states squeue gives the array's tasks now (task index -> state).
std::map<int, std::string> taskStates(const std::string& job) {
    std::map<int, std::string> states;
    const CommandOutput q = runCommand({"squeue", "-h", "-r", "-j", job, "--states=all", "-o", "%K %T"});
    if (q.status != 0) return states;
    std::istringstream in(q.output);
    for (std::string line; std::getline(in, line);) {
        std::istringstream l(line);
        std::string index, state;
        if (l >> index >> state && index.find_first_not_of("0123456789") == std::string::npos)
            states[std::stoi(index)] = state;
    }
    return states;
}

// What a task's log says went wrong: relief's own error line, else the last
// line that says "error", else its last line.
std::string logSays(const fs::path& log) {
    std::string problem;
    const auto text = readInputHead(log, 1'000'000, problem);
    if (!text) return "its log is empty";
    std::vector<std::string> lines;
    std::istringstream in(*text);
    for (std::string line; std::getline(in, line);)
        if (line.find_first_not_of(" \t\r") != std::string::npos) lines.push_back(line);
    if (lines.empty()) return "its log is empty";
    for (size_t i = 0; i < lines.size(); ++i)
        if (lines[i].starts_with("relief: error: ")) return terminalText(lines[i].substr(15), 400);
    for (auto it = lines.rbegin(); it != lines.rend(); ++it)
        if (it->find("error") != std::string::npos) return terminalText(*it, 400);
    return terminalText(lines.back(), 400);
}

}  // namespace

std::optional<std::vector<std::string>> slurmArgWords(const std::string& text, std::string& problem) {
    if (text.find_first_not_of(" \t\n") == std::string::npos) return std::vector<std::string>{};
    gchar** argv = nullptr;
    GError* error = nullptr;
    if (!g_shell_parse_argv(text.c_str(), nullptr, &argv, &error)) {
        problem = fmt::format("\"{}\" cannot be split into words as a shell would ({}): close its quotes",
                              terminalText(text, 200), error ? terminalText(error->message, 200) : "?");
        g_clear_error(&error);
        return std::nullopt;
    }
    std::vector<std::string> words;
    for (gchar** w = argv; *w; ++w) words.emplace_back(*w);
    g_strfreev(argv);
    return words;
}

Result runSlurm(const std::vector<Task>& tasks, const std::vector<const plan::RenderPlan*>& plans,
                const Options& options, const std::function<void(const Progress&)>& progress) {
    Result result;
    if (std::string problem = clusterProblem(); !problem.empty()) {
        result.badInput = true;
        result.error = problem;
        return result;
    }
    std::string problem;
    const auto args = slurmArgWords(options.slurmArgs, problem);
    if (!args) {
        result.badInput = true;
        result.error = "--slurm-args: " + problem;
        return result;
    }
    const fs::path script = writeJob(tasks, plans, options.sandbox, options.jobDir);
    std::vector<std::string> sbatch{"sbatch",
                                    "--parsable",
                                    fmt::format("--array=0-{}{}", tasks.size() - 1,
                                                options.jobs > 0 ? fmt::format("%{}", options.jobs) : std::string()),
                                    "--output=" + slurmPattern(fs::absolute(options.jobDir) / "logs", "task-%a.log"),
                                    "--job-name=relief"};
    sbatch.insert(sbatch.end(), args->begin(), args->end());
    sbatch.push_back(script.string());
    const CommandOutput submitted = runCommand(sbatch);
    const std::string job = firstLine(submitted.output).substr(0, firstLine(submitted.output).find(';'));
    if (submitted.status != 0 || job.empty() || job.find_first_not_of("0123456789") != std::string::npos) {
        result.badInput = true;
        result.error = fmt::format("sbatch refused the job: {}", firstLine(submitted.output));
        return result;
    }
    const auto t0 = Clock::now();
    result.taskErrors.assign(tasks.size(), "not rendered");
    std::vector<bool> ended(tasks.size(), false);
    size_t endedCount = 0, completed = 0;
    // A task's outcome once it has ended: its tile's record, or why there is none.
    const auto outcomeOf = [&](size_t i, const std::string& state) {
        std::string problem;
        if (state == "COMPLETED" && plan::readTileRecord(*plans[i], tasks[i].tile, problem)) return std::string();
        const fs::path log = fs::absolute(options.jobDir) / "logs" / fmt::format("task-{}.log", i);
        return fmt::format("task {} (Slurm job {}_{}, tile {} of {}) {}: {}; its log: {}", i, job, i, tasks[i].tile + 1,
                           plans[i]->tiles, state, state == "COMPLETED" ? problem : logSays(log), log.string());
    };
    auto lastSeen = Clock::now();
    while (endedCount < tasks.size()) {
        if (options.cancelled && options.cancelled()) {
            runCommand({"scancel", job});
            result.cancelled = true;
            return result;
        }
        auto states = taskStates(job);
        // A job squeue no longer knows (cancelled and purged elsewhere): what has not ended is lost.
        if (!states.empty()) lastSeen = Clock::now();
        else if (Clock::now() - lastSeen > std::chrono::seconds(30))
            for (size_t i = 0; i < tasks.size(); ++i)
                if (!ended[i]) states[static_cast<int>(i)] = "LOST";
        for (const auto& [k, state] : states) {
            const auto i = static_cast<size_t>(k);
            if (i >= tasks.size() || ended[i] || !finalState(state)) continue;
            ended[i] = true;
            ++endedCount;
            result.taskErrors[i] = outcomeOf(i, state);
            completed += result.taskErrors[i].empty();
            if (options.onTaskDone) options.onTaskDone(i, result.taskErrors[i]);
            if (progress && result.taskErrors[i].empty())
                progress({completed, tasks.size(), secondsSince(t0)});
            // A still cannot be made without every tile: the rest of the array is cancelled.
            if (!result.taskErrors[i].empty() && options.stopOnFailure) {
                runCommand({"scancel", job});
                result.error = result.taskErrors[i];
                return result;
            }
        }
        if (endedCount < tasks.size()) std::this_thread::sleep_for(std::chrono::milliseconds(500));
    }
    for (const auto& e : result.taskErrors)
        if (!e.empty()) {
            result.error = e;
            return result;
        }
    result.ok = true;
    return result;
}

}  // namespace relief::execute
