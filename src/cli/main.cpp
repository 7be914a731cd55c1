// relief: the command line. src/cli/ is the only code that prints or exits;
// everything else is the relief_core library. Each subcommand is in its own
// cmd_*.cpp and only parses its arguments, calls the library and prints.
#include <fmt/format.h>

#include "cli/cli_common.h"
#include "relief/version.h"

int main(int argc, char** argv) {
    using namespace relief::cli;  // in main alone: relief's command files are compiled as one
    if (argc > 1 && isImageCommand(argv[1])) return runImageHelper(argc, argv);

    CLI::App app{fmt::format(
        "relief {}: compiles georeferenced elevation samples into a ray-traced still.\n"
        "scene file (TOML) -> control net (GeographicLib, GDAL) -> subdivision -> POV-Ray "
        "mesh2 -> PNG",
        relief::kVersion)};
    app.footer("\n" + exitCodesHelp() + "\nScene format: docs/scene-format.md");
    app.set_version_flag("--version", fmt::format("relief {}", relief::kVersion));
    app.require_subcommand(1);

    std::vector<Command> commands;
    addDataCommands(app, commands);
    addSceneCommands(app, commands);
    addAnimateCommands(app, commands);
    addPlanStepCommands(app, commands);
    addSchemeCommands(app, commands);
    addImageCommandEntries(app);
    addGeometryCommands(app, commands);
    addExportCommands(app, commands);
    addPreviewCommands(app, commands);
    return runCommands(app, commands, argc, argv);
}
