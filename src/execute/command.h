#pragma once
// A command of the system's (sbatch, squeue, scancel, sinfo), run to its end.
#include <string>
#include <vector>

namespace relief::execute {

struct CommandOutput {
    int status = -1;     ///< its exit status; -1 when it could not run or was killed
    std::string output;  ///< stdout and stderr together
};

/// Runs argv[0] (found on PATH) with the environment, stdin from /dev/null.
CommandOutput runCommand(const std::vector<std::string>& argv);

/// The first line of `text` that says something, cut to 300 bytes.
std::string firstLine(const std::string& text);

}  // namespace relief::execute
