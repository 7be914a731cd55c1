#pragma once
// A folder of a test's own under the build tree, named with the process id:
// two runs of the suite at once never share one, and nothing lands in /tmp.
#include <unistd.h>

#include <filesystem>
#include <string>

namespace relief::testing {

/// The source tree: its scenes, templates and test data.
inline const std::filesystem::path kSourceDir = RELIEF_SOURCE_DIR;

inline std::filesystem::path freshTestDir(const std::string& name) {
    const std::filesystem::path dir =
        std::filesystem::path(RELIEF_TEST_WORK_DIR) / (name + "-" + std::to_string(::getpid()));
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    return dir;
}

}  // namespace relief::testing
