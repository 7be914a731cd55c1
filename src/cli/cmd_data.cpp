#include "cli/cli_common.h"

// relief info, relief init: a DEM (or, for info, a scene) and what relief
// would make of it, known before doing it: pipeline/record.h says it.
#include <iostream>
#include <memory>

#include <fmt/format.h>

#include "core/atomic_file.h"
#include "core/text_escape.h"
#include "pipeline/record.h"

namespace relief::cli {

namespace {

// `relief info` and `relief init`: a DEM (or, for info, a scene) and what relief would make of it.
struct DataOptions {
    std::string input, output;
    std::vector<std::string> sets;
    bool json = false, force = false, quiet = false;
};

// How a command plans: relief info estimates (no net too large to read in a second is read),
// relief init reads the net it writes the scene for.
enum class Planning { Estimated, NetRead };

std::optional<std::pair<relief::LoadedScene, relief::Surface>> planned(const DataOptions& o, Planning planning,
                                                                       relief::Diagnostics& diags) {
    scene::SceneOverrides overrides;
    if (!parseOverrides(o.sets, overrides)) return std::nullopt;
    auto loaded = relief::loadScene(o.input, diags, overrides);
    if (!loaded) return std::nullopt;
    auto surface = planning == Planning::Estimated ? relief::estimateSurface(*loaded, diags)
                                                   : relief::planSurface(*loaded, diags);
    if (!surface) return std::nullopt;
    return std::pair{std::move(*loaded), std::move(*surface)};
}

int runInfo(const DataOptions& o) {
    relief::Diagnostics diags;
    const auto plan = planned(o, Planning::Estimated, diags);
    const auto info = plan ? relief::sceneInfo(plan->first, plan->second, diags) : nlohmann::ordered_json();
    printDiagnostics(diags, plan.has_value());
    if (!plan) return code(Exit::BadInput);
    std::cout << (o.json ? info.dump(2) + "\n" : terminalText(relief::sceneInfoText(info), 100000, true));
    return code(Exit::Ok);
}

int runInit(const DataOptions& o) {
    relief::Diagnostics diags;
    const std::filesystem::path out =
        o.output.empty() ? std::filesystem::path(std::filesystem::path(o.input).stem().string() + ".toml")
                         : std::filesystem::path(o.output);
    std::error_code ec;
    if (std::filesystem::exists(out, ec) && !o.force) {
        std::cerr << fmt::format("relief: error: {} exists: give another -o, or --force to replace it\n",
                                 terminalText(out.string(), 500));
        return code(Exit::BadInput);
    }
    // Before any work: a name TOML cannot hold is refused, not written with U+FFFD.
    const std::filesystem::path input(o.input);
    if (!relief::initCanNameData(input.has_filename() ? input : input.parent_path(), out, diags)) {
        printDiagnostics(diags, false);
        return code(Exit::BadInput);
    }
    const auto plan = planned(o, Planning::NetRead, diags);
    if (plan && plan->first.scene.madeForData.empty())
        diags.error({o.input, 0, 0},
                    "relief init makes a scene for elevation data (a raster or a CSV of samples); "
                    "this is a scene file already");
    if (!plan || diags.hasErrors() || !o.quiet) printDiagnostics(diags, false);
    if (!plan || diags.hasErrors()) return code(Exit::BadInput);
    try {
        createParentFolder(out);
        writeFileAtomically(out, relief::initSceneText(plan->first, plan->second, out));
    } catch (const std::exception& e) {
        std::cerr << "relief: error: " << terminalText(e.what(), 2000) << '\n';
        return code(Exit::BadInput);
    }
    if (!o.quiet)
        std::cerr << fmt::format("wrote {} (net {} x {}, depth {}): relief render {} makes the still\n",
                                 terminalText(out.string(), 500), plan->second.net.rows(), plan->second.net.cols(),
                                 plan->second.depth, terminalText(shellQuoted(out.string()), 500));
    return code(Exit::Ok);
}

}  // namespace

void addDataCommands(CLI::App& app, std::vector<Command>& out) {
    auto o = std::make_shared<DataOptions>();
    CLI::App* info = app.add_subcommand(
        "info",
        "what relief would do with a DEM or a scene and what it would cost (the data, frame, net, depth and "
        "why, geometry, estimated triangles, memory and .pov size against [limits]), before doing it");
    info->add_option("input", o->input, "a raster DEM, a CSV of lon,lat,elev samples, or a scene file")->required();
    info->add_flag("--json", o->json, "print JSON");
    info->add_option("--set", o->sets, "override a scene key: section.key=value (render.width=3840); repeatable");
    out.push_back({info, [o] { return runInfo(*o); }});

    CLI::App* init =
        app.add_subcommand("init",
                           "write the scene relief makes for a DEM as a TOML file: every choice with its value and why "
                           "(relief render of it makes the still relief render of the DEM does)");
    init->add_option("input", o->input, "a raster DEM or a CSV of lon,lat,elev samples")->required();
    init->add_option("-o,--output", o->output, "the scene file to write (default: <DEM name>.toml here)");
    init->add_option("--set", o->sets, "override a scene key first: section.key=value (render.width=3840); repeatable");
    init->add_flag("--force", o->force, "replace the scene file if it exists");
    init->add_flag("-q,--quiet", o->quiet, "print errors only");
    out.push_back({init, [o] { return runInit(*o); }});
}


}  // namespace relief::cli
