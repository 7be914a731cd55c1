#include "cli/cli_common.h"

// relief export: the terrain as the still renders it, as a 3-D model
// (pipeline/export.h).
#include <iostream>
#include <memory>

#include <fmt/format.h>

#include "core/text_escape.h"
#include "pipeline/export.h"

namespace relief::cli {

namespace {

struct ExportOptions {
    CommonOptions common;
    double scaleMM = 0;
    long long maxTriangles = relief::kDefaultModelTriangles;
    bool solid = false;
};

void printExported(const relief::ExportOutcome& o) {
    const std::string surface =
        o.toleranceM > 0 ? fmt::format("an adaptive mesh within {:.3g} m of the refined surface", o.toleranceM)
                         : "every node a vertex";
    std::cerr << fmt::format("wrote {} ({}: {} vertices, {} triangles of the surface ({} x {} nodes, depth {}: {}){}; "
                             "{}, {:.1f} MB, {:.2f} s)\n",
                             terminalText(o.output.string(), 500), o.format, o.vertices, o.surfaceTriangles, o.rows,
                             o.cols, o.depth, surface,
                             o.floorElevationM ? fmt::format(", {} of walls and {} of floor at {:.4g} m",
                                                             o.wallTriangles, o.floorTriangles, *o.floorElevationM)
                                               : std::string(),
                             o.unitsPerMetre == 1 ? "metres" : fmt::format("millimetres, {:.4g} a metre", o.unitsPerMetre),
                             o.bytes / 1e6, o.seconds);
}

int runExport(const ExportOptions& o) {
    relief::Diagnostics diags;
    Progress progress(o.common.quiet);
    relief::ExportJob job;
    job.scenePath = o.common.scene;
    if (!parseOverrides(o.common.sets, job.overrides)) return code(Exit::BadInput);
    job.output = o.common.output;
    if (o.scaleMM > 0) job.acrossMM = o.scaleMM;
    job.maxTriangles = o.maxTriangles;
    job.solid = o.solid;
    job.threads = o.common.threads;
    const auto outcome = relief::exportTerrain(job, diags, showing(progress));
    progress.done();
    printDiagnostics(diags, outcome.has_value());
    if (!outcome) return code(Exit::BadInput);
    if (!o.common.quiet) printExported(*outcome);
    return code(Exit::Ok);
}

}  // namespace

void addExportCommands(CLI::App& app, std::vector<Command>& out) {
    auto o = std::make_shared<ExportOptions>();
    CLI::App* cmd = app.add_subcommand(
        "export", "write the terrain as the still renders it (its depth, exaggeration, colours; nodes without data left "
                  "out) as a 3-D model: .glb or .gltf (glTF 2.0), .stl (a closed solid, for printing), .obj or .ply");
    cmd->add_option("scene", o->common.scene,
                    "scene file (TOML), or a DEM alone: a raster GDAL opens or a CSV of lon,lat,elev")
        ->required();
    cmd->add_option("-o,--output", o->common.output,
                    "the model to write, its format by its extension (default: out/<scene name>.glb)");
    cmd->add_option("--scale", o->scaleMM,
                    "millimetres across: the model scaled so that its wider side is this long (for printing; "
                    "default: metres)")
        ->check(CLI::Range(0.001, 1e9));
    cmd->add_option("--max-triangles", o->maxTriangles,
                    fmt::format("at most this many triangles: above it, an adaptive mesh within the least tolerance "
                                "that fits, said in the output (default {})",
                                relief::kDefaultModelTriangles))
        ->check(CLI::Range(100LL, 100'000'000LL));
    cmd->add_flag("--solid", o->solid,
                  "close the surface into a solid (walls and a floor, as [base] draws them) whatever the format; "
                  ".stl always is one, and any format is when the scene has [base]");
    cmd->add_option("--threads", o->common.threads, "refiner threads (0: all cores)")->check(CLI::Range(0, 256));
    cmd->add_flag("-q,--quiet", o->common.quiet, "print errors only");
    cmd->add_option("--set", o->common.sets,
                    "override a scene key: section.key=value, the value as TOML writes it (vertical.exaggeration=2, "
                    "subdivision.depth=2); repeatable");
    out.push_back({cmd, [o] { return runExport(*o); }});
}

}  // namespace relief::cli
