// relief-images: `relief diff`, `relief test` and `relief sweep`, the commands
// that read and write images with OpenImageIO. relief hands their command
// lines over unchanged (cli/image_helper.cpp); users never call it by name.
#include <fmt/format.h>

#include "cli/cli_common.h"
#include "relief/version.h"

int main(int argc, char** argv) {
    using namespace relief::cli;
    CLI::App app{fmt::format("relief {}: image commands", relief::kVersion), "relief"};
    app.footer("\n" + exitCodesHelp());
    app.set_version_flag("--version", fmt::format("relief {}", relief::kVersion));
    app.require_subcommand(1);

    std::vector<Command> commands;
    addImageCommands(app, commands);
    return runCommands(app, commands, argc, argv);
}
