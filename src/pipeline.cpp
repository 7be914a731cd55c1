#include "pipeline.h"

#include <cmath>
#include <numbers>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "core/atomic_file.h"
#include "core/date_time.h"
#include "core/number_format.h"
#include "core/png_file.h"
#include "core/stopwatch.h"
#include "core/utf8_record.h"
#include "emit/adaptive_mesh.h"
#include "emit/block_base.h"
#include "emit/camera.h"
#include "emit/surface_contours.h"
#include "emit/height_field.h"
#include "emit/mesh.h"
#include "geo/control_net.h"
#include "geo/sun_position.h"
#include "measure/auto_depth.h"
#include "relief/version.h"
#include "scene/read_scene.h"
#include "scene_for_data.h"
#include "subdiv/refine.h"

namespace relief {

std::string depthLabel(const scene::SubdivisionSpec& sub) {
    if (sub.depthAuto) return fmt::format("depth auto (tolerance_m = {})", formatShortest(sub.toleranceM));
    return sub.depthGiven ? fmt::format("depth {}", sub.depth) : std::string("depth for the still");
}

subdiv::Budget budgetOf(const scene::LimitsSpec& limits) {
    return {limits.maxTriangles, limits.maxSdlMB, limits.maxParseS,
            limits.maxMemoryMB > 0 ? limits.maxMemoryMB : subdiv::defaultMemoryBudgetMB()};
}

geo::NetBudget netBudgetOf(const scene::LimitsSpec& limits) {
    const double mb = budgetOf(limits).maxMemoryMB;
    geo::NetBudget b;
    b.maxNodes = std::min(1e9, mb * 1e6 / geo::kNetBytesPerNode);
    b.why = limits.maxMemoryMB > 0
                ? fmt::format("limits.max_memory_mb = {} ({} bytes a node)", formatShortest(mb), geo::kNetBytesPerNode)
                : fmt::format("the memory relief may use ({:.0f} MB, three quarters of this machine's; "
                              "limits.max_memory_mb) at {} bytes a node",
                              mb, geo::kNetBytesPerNode);
    return b;
}

namespace {
std::string levelSeries(const measure::DepthChoice& choice) {
    std::string steps;
    for (const auto& l : choice.levels)
        steps += fmt::format("{}{}: {:.3g} m", steps.empty() ? "" : ", ", l.level, l.distanceM);
    return steps;
}
}  // namespace

std::string autoDepthSummary(const measure::DepthChoice& choice, double toleranceM) {
    const std::string steps = levelSeries(choice);
    return fmt::format("depth {} chosen: the largest change per level (Hausdorff, net rows and "
                       "columns) was {}; tolerance {} m",
                       choice.depth, steps, formatShortest(toleranceM));
}



OutputPaths outputPathsFor(const std::filesystem::path& still) {
    OutputPaths p;
    p.still = still;
    p.pov = still;
    p.pov.replace_extension(".pov");
    p.sidecar = still;
    p.sidecar.replace_extension(".json");
    return p;
}

std::optional<LoadedScene> loadScene(const std::filesystem::path& named, Diagnostics& diags,
                                     const scene::SceneOverrides& overrides) {
    const auto t0 = Clock::now();
    // "tiles/" is the folder "tiles", beside which its scene lies.
    const std::filesystem::path scenePath = named.has_filename() ? named : named.parent_path();
    std::string why;
    const InputKind kind = inputKindOf(scenePath, why);
    if (kind == InputKind::Neither) {
        diags.error(
            {scenePath.string(), 0, 0},
            fmt::format(
                "relief reads a scene file (TOML), a raster DEM GDAL opens (GeoTIFF, SRTM .hgt, ESRI "
                "ASCII grid, VRT, ...), a folder of such tiles or a CSV of lon,lat,elev samples, and this is none of "
                "them ({})",
                why));
        return std::nullopt;
    }
    checkUtf8(diags, {scenePath.string(), 0, 0}, scenePath.string(), "the file's name");
    for (const auto& [key, value] : overrides)
        checkUtf8(diags, {"--set " + key, 0, 0}, value, "the value");
    auto spec = kind == InputKind::Scene ? scene::readScene(scenePath, diags, overrides)
                                         : readSceneForData(scenePath, diags, overrides);
    if (!spec) return std::nullopt;
    // The scene's own errors do not stop the scheme's checks: every problem is reported at once.
    auto resolved = subdiv::resolveScheme(spec->subdivision.scheme, diags);
    if (diags.hasErrors() || !resolved) return std::nullopt;
    LoadedScene loaded{std::move(*spec), std::move(*resolved), 0};
    loaded.seconds = secondsSince(t0);
    return loaded;
}

namespace {

// The cheapest geometry the scene allows, whose cost bounds the job's from below.
subdiv::GeometryCost cheapestCost(scene::GeometryKind kind) {
    switch (kind) {
        case scene::GeometryKind::Mesh2:
            return subdiv::GeometryCost::Mesh2;
        case scene::GeometryKind::Adaptive:
            return subdiv::GeometryCost::Adaptive;
        default:
            return subdiv::GeometryCost::HeightField;
    }
}

}  // namespace

SourceLoc budgetKey(const scene::SceneSpec& spec) {
    const scene::SubdivisionSpec& sub = spec.subdivision;
    if (sub.depthAuto) return sub.locs.at("subdivision.depth");
    if (sub.depthGiven) return sub.locs.at("subdivision.scheme");
    if (spec.net.locs.has("net.spacing_m")) return spec.net.locs.at("net.spacing_m");
    return spec.net.locs.has("net.rows") ? spec.net.locs.at("net.rows") : SourceLoc{spec.samples.pathAsWritten, 0, 0};
}

namespace {

// What [limits] and the still allow the control net, for geo: its nodes, a
// default net no finer than the still, and a net whose refinement (at the
// scene's depth, else at depth 0 in the cheapest geometry) is over [limits]
// refused before a height is read.
geo::NetLimits netLimitsOf(const LoadedScene& loaded) {
    const scene::SceneSpec& spec = loaded.scene;
    geo::NetLimits l{netBudgetOf(spec.limits), budgetOf(spec.limits).maxMemoryMB, std::nullopt};
    if (spec.limits.locs.has("limits.max_memory_mb")) l.memoryKey = spec.limits.locs.at("limits.max_memory_mb");
    l.nodes.stillWidthPx = spec.render.width;
    l.nodes.fits = [&loaded](int rows, int cols, Diagnostics& diags) {
        const scene::SceneSpec& spec = loaded.scene;
        const int depth = spec.subdivision.depthGiven ? spec.subdivision.depth : 0;
        const auto est =
            subdiv::estimateOutput(loaded.resolved.scheme, rows, cols, depth, cheapestCost(spec.geometry.kind));
        return subdiv::checkBudget(est, budgetOf(spec.limits), budgetKey(spec), depth, diags);
    };
    return l;
}

// What chooseGeometry weighs for the net refined to `triangles`.
emit::GeometryFacts geometryFacts(const LoadedScene& loaded, const geo::ControlNet& net, int depth, double triangles) {
    const scene::SceneSpec& spec = loaded.scene;
    emit::GeometryFacts facts;
    facts.triangles = triangles;
    facts.masked = !net.masked.empty();
    const auto [zmin, zmax] = net.grid.zRange();
    facts.zRangeM = zmax - zmin;
    facts.extentM = std::max(net.xMax() - net.x0, net.yMax() - net.y0);
    facts.exaggeration = spec.look.vertical.exaggeration;
    facts.widthPx = spec.render.width;
    facts.rough = depth > 0 && loaded.resolved.report.holder < 1;
    return facts;
}

// The geometry the net refined `depth` times becomes, and what it costs.
struct DepthCost {
    emit::GeometryChoice geometry;
    subdiv::OutputEstimate estimate;
};
std::optional<DepthCost> costAt(const LoadedScene& loaded, const geo::ControlNet& net, int depth, Diagnostics& diags) {
    const scene::SceneSpec& spec = loaded.scene;
    const subdiv::Scheme& scheme = loaded.resolved.scheme;
    const auto mesh = subdiv::estimateOutput(scheme, net.rows(), net.cols(), depth);
    auto geometry = emit::chooseGeometry(spec.geometry, geometryFacts(loaded, net, depth, mesh.triangles), diags);
    if (!geometry) return std::nullopt;
    DepthCost c{*geometry, mesh};
    if (geometry->kind == scene::GeometryKind::HeightField)
        c.estimate = subdiv::estimateOutput(scheme, net.rows(), net.cols(), depth, subdiv::GeometryCost::HeightField);
    else if (geometry->kind == scene::GeometryKind::Adaptive)
        c.estimate = subdiv::estimateOutput(scheme, net.rows(), net.cols(), depth, subdiv::GeometryCost::Adaptive);
    // The colours held beside the grid: a height field's drape (16-bit RGBA, a
    // node each); an image drape's too on any kind, and the image on the grid (RGB and coverage).
    const bool heightField = geometry->kind == scene::GeometryKind::HeightField;
    const bool image = spec.look.texture.colouring == scene::TextureSpec::Colouring::Image;
    c.estimate.memoryBytes += c.estimate.vertices * ((heightField || image ? 8 : 0) + (image ? 4 : 0));
    return c;
}

// The depth whose refined spacing is nearest one pixel of the still where the
// terrain is nearest the camera (within a factor sqrt(arity) of it): no more
// detail than the picture can show, and none less.
int depthForStill(const LoadedScene& loaded, const geo::ControlNet& net, double& pixelM) {
    const scene::SceneSpec& spec = loaded.scene;
    Diagnostics quiet;  // a camera point that cannot be placed is reported once, with the view
    const auto points = emit::cameraPointsInFrame(spec.look.camera, net.frame, quiet);
    const emit::ScenePlacement where = emit::placeTerrain(net, spec.look);
    const emit::CameraView camera =
        emit::placeCamera(where, spec.look.camera, points.value_or(emit::CameraPoints{}), spec.render);
    pixelM = emit::finestMetresPerPixel(camera, where, spec.render.width);
    const double arity = loaded.resolved.scheme.arity, spacing = std::max(net.dx, net.dy);
    int depth = 0;
    while (depth < scene::kMaxDepth && spacing / std::pow(arity, depth) > pixelM * std::sqrt(arity)) ++depth;
    return depth;
}

// depth = "auto": the smallest depth whose last level moves the terrain by at
// most tolerance_m, searched up to the deepest the budget allows.
bool chooseAutoDepth(const LoadedScene& loaded, const geo::ControlNet& net, int threads, Surface& s,
                     Diagnostics& diags) {
    const scene::SubdivisionSpec& sub = loaded.scene.subdivision;
    const subdiv::Scheme& scheme = loaded.resolved.scheme;
    // When not even level 1 fits, the budget check after says so.
    const int maxDepth =
        subdiv::deepestWithinBudget(scheme, net.rows(), net.cols(), budgetOf(loaded.scene.limits), scene::kMaxDepth);
    s.depth = 1;
    if (maxDepth <= 0) return true;
    s.autoDepth = measure::chooseDepth(scheme, net, sub.toleranceM, maxDepth, threads);
    const auto& last = s.autoDepth->levels.back();
    if (!s.autoDepth->reached) {
        diags.error(sub.locs.at("subdivision.tolerance_m"),
                    fmt::format("subdivision.tolerance_m = {} m is not reached within the output "
                                "budget: level {} (the deepest [limits] allow) still moves {} by "
                                "{:.3g} m (per level: {}); raise tolerance_m or [limits], or set "
                                "a fixed depth",
                                formatShortest(sub.toleranceM), last.level, last.curve, last.distanceM,
                                levelSeries(*s.autoDepth)));
        return false;
    }
    s.depth = s.autoDepth->depth;
    s.depthReason = autoDepthSummary(*s.autoDepth, sub.toleranceM);
    return true;
}

// No depth in the scene: the still's (depthForStill), or the deepest below it
// that [limits] allow; a default never refuses a scene that fits at depth 0.
void chooseStillDepth(const LoadedScene& loaded, const geo::ControlNet& net, Surface& s) {
    double pixelM = 0;
    const int wanted = depthForStill(loaded, net, pixelM);
    int depth = wanted;
    for (; depth > 0; --depth) {
        Diagnostics quiet;
        const auto cost = costAt(loaded, net, depth, quiet);
        if (cost && subdiv::withinBudget(cost->estimate, budgetOf(loaded.scene.limits))) break;
    }
    s.depth = depth;
    const double refinedM = std::max(net.dx, net.dy) / std::pow(loaded.resolved.scheme.arity, depth);
    s.depthReason = fmt::format(
        "chosen for the still: the net's {:.3g} m refined to {:.3g} m, about the {:.3g} m "
        "one pixel of the {} px wide still covers where the terrain is nearest the camera",
        std::max(net.dx, net.dy), refinedM, pixelM, loaded.scene.render.width);
    if (depth < wanted) s.depthReason += fmt::format(" (depth {} would be over [limits])", wanted);
}

// net.gridding = "fit" and net.fit = true: the net made for the scheme's
// surface at the depth rendered (chosen on the gridded net before).
bool fitToScheme(const LoadedScene& loaded, int depth, geo::ControlNet& net, Surface& s, Diagnostics& diags,
                 const ProgressFn& progress) {
    const scene::NetSpec& spec = loaded.scene.net;
    const subdiv::Scheme& scheme = loaded.resolved.scheme;
    if (net.fitSamples) {
        const geo::NetLimits limits = netLimitsOf(loaded);
        const double neededMB = static_cast<double>(net.grid.points.size()) * fit::kFitBytesPerNode / 1e6;
        const double budgetMB = limits.memoryMB;
        if (neededMB > budgetMB) {
            diags.error(limits.memoryKey.value_or(spec.locs.at("net.gridding")),
                        fmt::format("net.gridding = \"fit\" on a net of {} nodes needs about {:.0f} MB ({:.0f} kB "
                                    "a node), more than the {:.0f} MB relief may use (limits.max_memory_mb): a "
                                    "coarser net (net.spacing_m), or raise the limit",
                                    net.grid.points.size(), neededMB, fit::kFitBytesPerNode / 1e3, budgetMB));
            return false;
        }
        const auto told = [&](const std::string& task) {
            if (progress) progress({ProgressEvent::Stage::Compiling, task, -1});
        };
        s.fit = fit::fitNet(scheme, depth, *net.fitSamples, spec, net, diags, told);
        if (!s.fit) return false;
        if (progress)
            progress({ProgressEvent::Stage::Compiling,
                      fmt::format("fitted {} samples: RMSE {:.3g} m, largest residual {:.3g} m, smoothing {:.3g} ({}), "
                                  "tension {:.3g}, {:.1f} s",
                                  s.fit->samples, s.fit->rmseM, s.fit->maxResidualM, s.fit->smoothing,
                                  s.fit->chosenBy, s.fit->tension, s.fit->seconds),
                      -1});
        return true;
    }
    if (spec.gridding == scene::Gridding::Fit)
        diags.warning(spec.locs.at("net.gridding"),
                      "net.gridding = \"fit\" is not used: the samples are a raster or a lattice, whose nodes are "
                      "the net as they stand; net.fit = true makes an approximating scheme pass through them");
    if (!spec.fit) return true;
    s.prefilter = fit::prefilterNet(scheme, depth, spec, net, diags);
    return s.prefilter.has_value();
}

}  // namespace

std::optional<Surface> planSurface(const LoadedScene& loaded, Diagnostics& diags, int threads,
                                   const ProgressFn& progress) {
    const scene::SceneSpec& spec = loaded.scene;
    const scene::SubdivisionSpec& sub = spec.subdivision;
    auto t0 = Clock::now();
    geo::NetProgressFn netProgress;
    if (progress)
        netProgress = [&](const std::string& task, int percent) {
            progress({ProgressEvent::Stage::Compiling, task, percent});
        };
    scene::NetSpec netSpec = spec.net;
    netSpec.linearBeforeFit = sub.depthAuto;
    auto net = geo::controlNet(spec.samples, spec.frame, netSpec, netLimitsOf(loaded), diags, netProgress);
    if (!net) return std::nullopt;
    Surface s;
    s.normalizeSeconds = secondsSince(t0);
    t0 = Clock::now();
    if (sub.depthAuto) {
        if (!chooseAutoDepth(loaded, *net, threads, s, diags)) return std::nullopt;
    } else if (sub.depthGiven) {
        s.depth = sub.depth;
        s.depthReason = "subdivision.depth";
    } else {
        chooseStillDepth(loaded, *net, s);
    }
    s.dataPeak = net->highestSample.value_or(measure::highestNode(*net));
    if (!fitToScheme(loaded, s.depth, *net, s, diags, progress)) return std::nullopt;
    auto cost = costAt(loaded, *net, s.depth, diags);
    if (!cost) return std::nullopt;
    s.geometry = cost->geometry;
    s.estimate = cost->estimate;
    if (!subdiv::checkBudget(s.estimate, budgetOf(spec.limits), budgetKey(spec), s.depth, diags)) return std::nullopt;
    s.subdivideSeconds = secondsSince(t0);
    s.net = std::move(*net);
    return s;
}

std::optional<Surface> buildSurface(const LoadedScene& loaded, Diagnostics& diags, int threads,
                                    const ProgressFn& progress) {
    auto s = planSurface(loaded, diags, threads, progress);
    if (!s) return std::nullopt;
    const auto t0 = Clock::now();
    if (progress)
        progress({ProgressEvent::Stage::Compiling,
                  fmt::format("subdividing to depth {} ({} x {} nodes{})", s->depth, s->estimate.rows, s->estimate.cols,
                              loaded.scene.subdivision.depthGiven ? std::string() : "; " + s->depthReason),
                  -1});
    const subdiv::Scheme& scheme = loaded.resolved.scheme;
    s->refined =
        s->net.refined(subdiv::refineGrid(scheme, s->net.grid, s->depth, threads), std::pow(scheme.arity, s->depth));
    s->subdivideSeconds += secondsSince(t0);
    s->peakLoss = measure::peakLoss(s->dataPeak, s->refined, std::max(s->net.dx, s->net.dy));
    if (progress)
        progress({ProgressEvent::Stage::Compiling,
                  fmt::format("peak loss {:.3g} m: the data's highest point {:.2f} m, the surface's near it {:.2f} m",
                              s->peakLoss.lossM, s->peakLoss.peak.z, s->peakLoss.surfaceHighest.z),
                  -1});
    return s;
}

}  // namespace relief
