#include "cli/cli_common.h"

// `relief diff|test|sweep` hand over to relief-images, the executable that
// links OpenImageIO, so that the other commands start in 0.03 s, not 0.18 s.
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <iostream>

namespace relief::cli {

namespace {

// Beside relief in a build tree; in libexec/relief when installed.
fs::path findImageHelper() {
    std::error_code ec;
    const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
    if (ec) return "relief-images";
    for (const fs::path& candidate : {exe.parent_path() / "relief-images",
                                      exe.parent_path().parent_path() / "libexec/relief/relief-images"})
        if (::access(candidate.c_str(), X_OK) == 0) return candidate;
    return exe.parent_path() / "relief-images";
}

}  // namespace

void addImageCommandEntries(CLI::App& app) {
    for (const auto& c : kImageCommands) app.add_subcommand(c.name, c.description)->allow_extras();
}

int runImageHelper(int argc, char** argv) {
    const fs::path helper = findImageHelper();
    std::vector<char*> args(argv, argv + argc);
    args.push_back(nullptr);
    ::execv(helper.c_str(), args.data());
    std::cerr << "relief: error: cannot run " << helper.string() << " for `relief " << argv[1]
              << "`: " << std::strerror(errno) << "; build or install it with relief (cmake --build)\n";
    return code(Exit::Internal);
}

}  // namespace relief::cli
