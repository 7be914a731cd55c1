#include "pipeline.h"

#include <chrono>
#include <cmath>
#include <numbers>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "core/atomic_file.h"
#include "core/date_time.h"
#include "core/number_format.h"
#include "core/png_file.h"
#include "emit/adaptive_mesh.h"
#include "emit/block_base.h"
#include "emit/surface_contours.h"
#include "emit/height_field.h"
#include "emit/mesh.h"
#include "geo/control_net.h"
#include "geo/sun_position.h"
#include "measure/auto_depth.h"
#include "relief/version.h"
#include "scene/read_scene.h"
#include "subdiv/refine.h"

namespace relief {

namespace {

using Clock = std::chrono::steady_clock;
double secondsSince(Clock::time_point t0) {
    return std::chrono::duration<double>(Clock::now() - t0).count();
}

}  // namespace

std::string depthLabel(const scene::SubdivisionSpec& sub) {
    return sub.depthAuto ? fmt::format("depth auto (tolerance_m = {})", formatShortest(sub.toleranceM))
                         : fmt::format("depth {}", sub.depth);
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



OutputPaths outputPathsFor(const std::filesystem::path& png) {
    OutputPaths p;
    p.png = png;
    p.pov = png;
    p.pov.replace_extension(".pov");
    p.sidecar = png;
    p.sidecar.replace_extension(".json");
    return p;
}

std::optional<LoadedScene> loadScene(const std::filesystem::path& scenePath,
                                     Diagnostics& diags, const scene::SceneOverrides& overrides) {
    const auto t0 = Clock::now();
    auto spec = scene::readScene(scenePath, diags, overrides);
    if (!spec) return std::nullopt;
    // The scene's own errors do not stop the scheme's checks: every problem is reported at once.
    auto resolved = subdiv::resolveScheme(spec->subdivision.scheme, diags);
    if (diags.hasErrors() || !resolved) return std::nullopt;
    LoadedScene loaded{std::move(*spec), std::move(*resolved), 0};
    loaded.seconds = secondsSince(t0);
    return loaded;
}

namespace {

// What [limits] allow the control net, for geo.
geo::NetLimits netLimitsOf(const scene::LimitsSpec& limits) {
    geo::NetLimits l{netBudgetOf(limits), budgetOf(limits).maxMemoryMB, std::nullopt};
    if (limits.locs.has("limits.max_memory_mb")) l.memoryKey = limits.locs.at("limits.max_memory_mb");
    return l;
}

}  // namespace

std::optional<Surface> buildSurface(const LoadedScene& loaded, Diagnostics& diags, int threads,
                                    const ProgressFn& progress) {
    const scene::SceneSpec& spec = loaded.scene;
    const scene::SubdivisionSpec& sub = spec.subdivision;
    const subdiv::Scheme& scheme = loaded.resolved.scheme;
    auto t0 = Clock::now();
    geo::NetProgressFn netProgress;
    if (progress)
        netProgress = [&](const std::string& task, int percent) {
            progress({ProgressEvent::Stage::Compiling, task, percent});
        };
    auto net = geo::controlNet(spec.samples, spec.frame, spec.net, netLimitsOf(spec.limits), diags, netProgress);
    if (!net) return std::nullopt;
    Surface s;
    s.normalizeSeconds = secondsSince(t0);
    const subdiv::Budget budget = budgetOf(spec.limits);
    s.depth = sub.depth;
    t0 = Clock::now();
    if (sub.depthAuto) {
        // The deepest level the budget allows bounds the search; when not
        // even level 1 fits, the budget check below says so.
        const int maxDepth = subdiv::deepestWithinBudget(scheme, net->rows(), net->cols(), budget,
                                                         scene::kMaxDepth);
        s.depth = 1;
        if (maxDepth > 0) {
            s.autoDepth = measure::chooseDepth(scheme, *net, sub.toleranceM, maxDepth, threads);
            const auto& last = s.autoDepth->levels.back();
            if (!s.autoDepth->reached) {
                diags.error(sub.locs.at("subdivision.tolerance_m"),
                            fmt::format("subdivision.tolerance_m = {} m is not reached within the output "
                                        "budget: level {} (the deepest [limits] allow) still moves {} by "
                                        "{:.3g} m (per level: {}); raise tolerance_m or [limits], or set "
                                        "a fixed depth",
                                        formatShortest(sub.toleranceM), last.level, last.curve,
                                        last.distanceM, levelSeries(*s.autoDepth)));
                return std::nullopt;
            }
            s.depth = s.autoDepth->depth;
        }
    }
    s.estimate = subdiv::estimateOutput(scheme, net->rows(), net->cols(), s.depth);
    {
        emit::GeometryFacts facts;
        facts.triangles = s.estimate.triangles;
        facts.masked = !net->masked.empty();
        double zmin = 1e300, zmax = -1e300;
        for (const Vec3& p : net->grid.points) zmin = std::min(zmin, p.z), zmax = std::max(zmax, p.z);
        facts.zRangeM = zmax - zmin;
        facts.extentM = std::max(net->xMax() - net->x0, net->yMax() - net->y0);
        facts.exaggeration = spec.look.vertical.exaggeration;
        facts.widthPx = spec.render.width;
        facts.rough = s.depth > 0 && loaded.resolved.report.holder < 1;
        auto geometry = emit::chooseGeometry(spec.geometry, facts, diags);
        if (!geometry) return std::nullopt;
        s.geometry = *geometry;
    }
    if (s.geometry.kind == scene::GeometryKind::HeightField)
        s.estimate = subdiv::estimateOutput(scheme, net->rows(), net->cols(), s.depth,
                                            subdiv::GeometryCost::HeightField);
    else if (s.geometry.kind == scene::GeometryKind::Adaptive)
        s.estimate = subdiv::estimateOutput(scheme, net->rows(), net->cols(), s.depth,
                                            subdiv::GeometryCost::Adaptive);
    // The colours held beside the grid: a height field's drape (16-bit RGBA, a
    // node each); an image drape's too on any kind, and the image on the grid (RGB and coverage).
    const bool heightField = s.geometry.kind == scene::GeometryKind::HeightField;
    const bool image = spec.look.texture.colouring == scene::TextureSpec::Colouring::Image;
    s.estimate.memoryBytes += s.estimate.vertices * ((heightField || image ? 8 : 0) + (image ? 4 : 0));
    if (!subdiv::checkBudget(s.estimate, budget,
                             sub.locs.at(sub.depthAuto ? "subdivision.depth" : "subdivision.scheme"),
                             s.depth, diags))
        return std::nullopt;
    if (progress)
        progress({ProgressEvent::Stage::Compiling,
                  fmt::format("subdividing to depth {} ({} x {} nodes)", s.depth, s.estimate.rows, s.estimate.cols),
                  -1});
    s.refined = net->refined(subdiv::refineGrid(scheme, net->grid, s.depth, threads),
                             std::pow(scheme.arity, s.depth));
    s.subdivideSeconds = secondsSince(t0);
    s.net = std::move(*net);
    return s;
}

}  // namespace relief
