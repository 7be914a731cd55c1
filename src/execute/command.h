#pragma once
// A command of the system's (sbatch, squeue, scancel, sinfo, ffmpeg), run to its end.
#include <filesystem>
#include <string>
#include <vector>

namespace relief::execute {

struct CommandOutput {
    int status = -1;        ///< its exit status; -1 when it could not run or was killed
    bool timedOut = false;  ///< killed at the time limit
    std::string output;     ///< stdout and stderr together
};

struct CommandOptions {
    /// Where it runs ("": here). A tool that takes names for patterns
    /// (ffmpeg's image sequences) gets fixed names relative to it.
    std::filesystem::path workingDir;
    double timeoutSeconds = 0;  ///< killed after this long (0: never)
};

/// Runs argv[0] (found on PATH) with the environment, stdin from /dev/null.
CommandOutput runCommand(const std::vector<std::string>& argv, const CommandOptions& options = {});

/// The first line of `text` that says something, cut to 300 bytes.
std::string firstLine(const std::string& text);

}  // namespace relief::execute
