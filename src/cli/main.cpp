// relief: the command line. src/cli/ is the only code that prints or exits;
// everything else is the relief_core library. Each subcommand is in its own
// cmd_*.cpp and only parses its arguments, calls the library and prints.
#include <iostream>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include "cli/cli_common.h"
#include "relief/version.h"

using namespace relief::cli;

int main(int argc, char** argv) {
    CLI::App app{fmt::format(
        "relief {}: compiles georeferenced elevation samples into a ray-traced still.\n"
        "scene file (TOML) -> control net (GeographicLib, GDAL) -> subdivision -> POV-Ray "
        "mesh2 -> PNG",
        relief::kVersion)};
    app.footer(std::string("\n") + kExitCodes + "\nScene format: docs/scene-format.md");
    app.set_version_flag("--version", fmt::format("relief {}", relief::kVersion));
    app.require_subcommand(1);

    std::vector<Command> commands;
    addSceneCommands(app, commands);
    addSchemeCommands(app, commands);
    addImageCommands(app, commands);
    addGeometryCommands(app, commands);

    try {
        app.parse(argc, argv);
    } catch (const CLI::Success& e) {
        return app.exit(e);
    } catch (const CLI::ParseError& e) {
        app.exit(e);
        for (const auto& c : commands)
            if (c.app->parsed()) return c.parseErrorCode;
        return code(Exit::BadInput);
    }
    try {
        for (const auto& c : commands)
            if (c.app->parsed()) return c.run();
        return code(Exit::BadInput);
    } catch (const std::runtime_error& e) {  // I/O: cannot write an output
        std::cerr << "relief: error: " << e.what() << '\n';
        return code(Exit::BadInput);
    } catch (const std::exception& e) {
        std::cerr << "relief: internal error: " << e.what() << '\n';
        return code(Exit::Internal);
    }
}
