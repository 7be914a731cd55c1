// Stages 2 and 3 composed: the control net for the loaded scene, the depth
// (depth.h), the fit to the scheme where the scene asks, the refined surface.
#include "pipeline/surface.h"

#include <cmath>
#include <limits>
#include <numbers>

#include <fmt/format.h>

#include "core/number_format.h"
#include "core/stopwatch.h"
#include "emit/unsupported_fade.h"
#include "geo/geo.h"
#include "subdiv/refine.h"

namespace relief {

namespace {

// The most nodes the control net may have: the job's memory at geo's bytes a node.
geo::NetBudget netBudgetOf(const LoadedScene& loaded) {
    const double mb = loaded.budget.maxMemoryMB;
    geo::NetBudget b;
    b.maxNodes = std::min(1e9, mb * 1e6 / geo::kNetBytesPerNode);
    b.why = loaded.scene.limits.maxMemoryMB > 0
                ? fmt::format("limits.max_memory_mb = {} ({} bytes a node)", formatShortest(mb), geo::kNetBytesPerNode)
                : fmt::format("the memory relief may use ({:.0f} MB, three quarters of this machine's; "
                              "limits.max_memory_mb) at {} bytes a node",
                              mb, geo::kNetBytesPerNode);
    return b;
}

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

// The data on a coarse net over `net`'s extent, for what its heights tell (the
// ground under a path, relief info's stand-in), not for a surface: about
// `across` nodes across, laid as a still's default net is (a raster's block
// means: a fraction of a second), or, for samples (which have no spacing of
// their own), `across` columns and `rows` rows.
std::optional<geo::ControlNet> coarseNet(const LoadedScene& loaded, scene::NetSpec net, int across, int rows,
                                         Diagnostics& diags) {
    net.spacingM = 0;
    for (const char* key : {"net.spacing_m", "net.rows", "net.cols"}) net.locs.keys.erase(key);
    net.cols = across;
    net.rows = rows;
    geo::NetLimits read{netBudgetOf(loaded), loaded.budget.maxMemoryMB, std::nullopt};
    read.nodes.stillWidthPx = across;
    return geo::controlNet(loaded.scene.samples, loaded.scene.frame, net, read, diags);
}

// A flyover through waypoints with heights above the sea: the eye's least
// height above the ground along its path (straight between the waypoints, 64
// points a leg, 1.7 m at least), the ground read on a coarse net 400 nodes
// across; none where the ground cannot be read there.
std::optional<double> lowestEyeAboveGround(const LoadedScene& loaded) {
    const scene::SceneSpec& spec = loaded.scene;
    const auto& fly = spec.animation.flyover;
    if (!fly.waypointHeights || fly.waypoints.size() < 2) return std::nullopt;
    Diagnostics quiet;  // the net itself says what is wrong with the data
    const auto ground = coarseNet(loaded, spec.net, 400, 400, quiet);
    if (!ground) return std::nullopt;
    double lowest = std::numeric_limits<double>::infinity();
    for (size_t i = 0; i + 1 < fly.waypoints.size(); ++i) {
        const auto a = geo::forward(ground->frame, fly.waypoints[i]), b = geo::forward(ground->frame, fly.waypoints[i + 1]);
        if (!a || !b) continue;
        for (int k = 0; k <= 64; ++k) {
            const Vec3 p = *a + (k / 64.0) * (*b - *a);
            if (const auto z = ground->sample(p.x, p.y)) lowest = std::min(lowest, p.z - *z);
        }
    }
    if (!std::isfinite(lowest)) return std::nullopt;
    return std::max(lowest, 1.7);
}

// What [limits] and the still allow the control net, for geo: its nodes, a
// default net no finer than the still, and a net whose refinement (at the
// scene's depth, else at depth 0 in the cheapest geometry) is over [limits]
// refused before a height is read.
geo::NetLimits netLimitsOf(const LoadedScene& loaded) {
    const scene::SceneSpec& spec = loaded.scene;
    geo::NetLimits l{netBudgetOf(loaded), loaded.budget.maxMemoryMB, std::nullopt};
    if (spec.limits.locs.has("limits.max_memory_mb")) l.memoryKey = spec.limits.locs.at("limits.max_memory_mb");
    l.nodes.stillWidthPx = spec.render.width;
    // A flyover's eye comes down to its height above the ground (the scene's, its waypoints'
    // least over the ground, else a twentieth of the terrain's diagonal): the net from a pixel's
    // footprint there, not from the whole terrain across the still, which would average away
    // what it flies over.
    if (spec.animation.path == scene::CameraPath::Flyover) {
        // The height the scene gives above the ground, else its waypoints' least over it.
        const auto heightM = spec.animation.flyover.heightAboveTerrainM
                                 ? spec.animation.flyover.heightAboveTerrainM
                                 : lowestEyeAboveGround(loaded);
        // The angle a pixel spans at the middle of the still: a pinhole's, a panorama's, a sphere's.
        using scene::Projection;
        const scene::CameraSpec& camera = spec.look.camera;
        const double across = camera.projection == Projection::Spherical ? 2 * std::numbers::pi
                              : camera.projection == Projection::Panoramic
                                  ? camera.fovDeg * std::numbers::pi / 180
                                  : 2 * std::tan(camera.fovDeg * std::numbers::pi / 360);
        const double perPixel = across / spec.render.width;
        l.nodes.nearestPixelM = [heightM, perPixel](double extentM) {
            const double eyeM = heightM ? *heightM : extentM * std::numbers::sqrt2 / 20;  // the diagonal's 20th
            return eyeM * perPixel;
        };
    }
    l.nodes.fits = [&loaded](const geo::GeoGrid& laidOut, Diagnostics& diags) {
        const scene::SceneSpec& spec = loaded.scene;
        const int depth = spec.subdivision.depthGiven ? spec.subdivision.depth : 0;
        const auto est = subdiv::estimateOutput(loaded.resolved.scheme, laidOut.rows(), laidOut.cols(), depth,
                                                cheapestCost(spec.geometry.kind));
        return subdiv::checkBudget(est, loaded.budget, budgetKey(spec), depth, diags);
    };
    return l;
}

// The share of a fitted net no sample reaches that is warned of: a tenth (lines, clusters and holes
// leave 15-80 %; the corners of a raster's footprint turned into UTM, a few per cent).
constexpr double kUnsupportedWarnShare = 0.1;

// A fit's nodes no sample reaches: left out as nodata is (net.unsupported =
// "mask"), faded (compile's, on the refined surface's colours) or shown,
// with a warning when they are a share of the net a reader would see and the
// scene has not said what to do with them.
void markUnsupported(const scene::NetSpec& spec, fit::FitReport& fit, geo::ControlNet& net, Diagnostics& diags) {
    fit.unsupportedAs = spec.unsupported;
    if (spec.unsupported == scene::Unsupported::Mask && fit.unsupportedShare > 0) {
        net.masked.resize(net.grid.points.size(), 0);
        for (size_t i = 0; i < net.masked.size(); ++i) net.masked[i] |= fit.unsupported(i);
    }
    if (fit.unsupportedShare < kUnsupportedWarnShare || spec.locs.has("net.unsupported")) return;
    diags.warning(spec.locs.at("net.gridding"),
                  fmt::format("net.gridding = \"fit\": {:.0f} % of the net is farther than {:.3g} m (twice the "
                              "samples' mean spacing) from any sample: the surface there is the fit's, not the "
                              "data's; net.unsupported = \"fade\" washes its colour out, \"mask\" leaves it out, "
                              "\"show\" keeps it without this warning",
                              100 * fit.unsupportedShare, fit.unsupportedBeyondM));
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
        markUnsupported(spec, *s.fit, net, diags);
        if (progress)
            progress({ProgressEvent::Stage::Compiling,
                      fmt::format("fitted {} samples: RMSE {:.3g} m, largest residual {:.3g} m, smoothing {:.3g} ({}), "
                                  "tension {:.3g}, {:.1f} s; {:.1f} % of the net farther than {:.3g} m from any sample{}",
                                  s.fit->samples, s.fit->rmseM, s.fit->maxResidualM, s.fit->smoothing,
                                  s.fit->chosenBy, s.fit->tension, s.fit->seconds, 100 * s.fit->unsupportedShare,
                                  s.fit->unsupportedBeyondM,
                                  s.fit->unsupportedShare > 0 && s.fit->unsupportedAs != scene::Unsupported::Show
                                      ? fmt::format(" ({})", s.fit->unsupportedAs == scene::Unsupported::Mask ? "masked" : "faded")
                                      : ""),
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

namespace {

// The net laid out and read as the scene says, and what geo hears of it.
geo::NetProgressFn netProgressOf(const ProgressFn& progress) {
    if (!progress) return {};
    return [progress](const std::string& task, int percent) {
        progress({ProgressEvent::Stage::Compiling, task, percent});
    };
}
scene::NetSpec netSpecOf(const scene::SceneSpec& spec) {
    scene::NetSpec net = spec.net;
    net.linearBeforeFit = spec.subdivision.depthAuto;
    return net;
}

// The depth, the fit and the cost of a surface on `net`'s heights at `size`,
// checked against [limits]. `standInAtM`: 0, or the spacing of the coarser
// net `net` is (relief info's estimate), which is not fitted (its fit would
// not be the net's) and whose automatic depth is measured on it, and said so.
std::optional<Surface> planOnNet(const LoadedScene& loaded, geo::ControlNet net, const NetSize& size,
                                 double standInAtM, Diagnostics& diags, int threads, const ProgressFn& progress) {
    const auto t0 = Clock::now();
    Surface s;
    s.size = size;
    s.heightsReadAtM = standInAtM;
    auto depth = chooseSurfaceDepth(loaded, net, size, threads, diags);
    if (!depth) return std::nullopt;
    s.depth = depth->depth;
    s.depthReason = std::move(depth->reason);
    s.autoDepth = std::move(depth->autoDepth);
    if (s.autoDepth && standInAtM > 0)
        s.depthReason += fmt::format(" (measured on the net's heights read at {:.3g} m: relief info's estimate)",
                                     standInAtM);
    s.dataPeak = net.highestSample.value_or(measure::highestNode(net));
    if (standInAtM == 0 && !fitToScheme(loaded, s.depth, net, s, diags, progress)) return std::nullopt;
    auto cost = costAt(loaded, net, size, s.depth, diags);
    if (!cost) return std::nullopt;
    s.geometry = cost->geometry;
    s.estimate = cost->estimate;
    if (!subdiv::checkBudget(s.estimate, loaded.budget, budgetKey(loaded.scene), s.depth, diags)) return std::nullopt;
    s.subdivideSeconds = secondsSince(t0);
    s.net = std::move(net);
    return s;
}

// relief info's stand-in heights: a still's default net about this many nodes
// across (block means of whole cells where the data allow), 0.4 s on a
// 53 M-cell raster.
constexpr int kEstimateReadWidthPx = 1000;

}  // namespace

std::optional<Surface> planSurface(const LoadedScene& loaded, Diagnostics& diags, int threads,
                                   const ProgressFn& progress) {
    const scene::SceneSpec& spec = loaded.scene;
    const auto t0 = Clock::now();
    auto net = geo::controlNet(spec.samples, spec.frame, netSpecOf(spec), netLimitsOf(loaded), diags,
                               netProgressOf(progress));
    if (!net) return std::nullopt;
    const double normalizeSeconds = secondsSince(t0);
    const NetSize size = NetSize::of(*net);
    auto s = planOnNet(loaded, std::move(*net), size, 0, diags, threads, progress);
    if (s) s->normalizeSeconds = normalizeSeconds;
    return s;
}

std::optional<Surface> estimateSurface(const LoadedScene& loaded, Diagnostics& diags) {
    const scene::SceneSpec& spec = loaded.scene;
    geo::NetLimits limits = netLimitsOf(loaded);
    std::optional<geo::ControlNet> tooLarge;  // laid out and described, not read
    limits.nodes.beforeReading = [&tooLarge](const geo::ControlNet& laidOut) {
        if (double(laidOut.rows()) * laidOut.cols() <= kEstimateReadNodes) return true;
        tooLarge = laidOut;
        return false;
    };
    auto net = geo::controlNet(spec.samples, spec.frame, netSpecOf(spec), limits, diags);
    if (!tooLarge) {
        if (!net) return std::nullopt;
        const NetSize size = NetSize::of(*net);
        return planOnNet(loaded, std::move(*net), size, 0, diags, 0, {});
    }
    // The stand-in: a net about kEstimateReadWidthPx nodes across over the same extent, laid as a
    // still's default net is (a raster's block means), or, for samples (which have no spacing of
    // their own), as rows and columns in the net's proportions. Its warnings are the net's, said.
    const int across = std::min(tooLarge->cols(), kEstimateReadWidthPx);
    const int rows = std::max(4, int(std::lround(double(tooLarge->rows()) * across / tooLarge->cols())));
    Diagnostics again;
    auto standIn = coarseNet(loaded, netSpecOf(spec), across, rows, again);
    for (const Diagnostic& d : again.all())
        if (d.severity == Severity::Error) diags.error(d.loc, d.message);
    if (!standIn) return std::nullopt;
    const double readAtM = std::max(standIn->dx, standIn->dy);
    // What the net is and why, as laid out; its heights the stand-in's.
    standIn->spacingReason = tooLarge->spacingReason;
    standIn->raster = tooLarge->raster;
    return planOnNet(loaded, std::move(*standIn), NetSize::of(*tooLarge), readAtM, diags, 0, {});
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

std::shared_ptr<const std::vector<std::uint8_t>> unsupportedFadeOf(const Surface& surface) {
    const auto& fit = surface.fit;
    if (!fit || fit->unsupportedAs != scene::Unsupported::Fade || fit->unsupportedShare == 0) return nullptr;
    return std::make_shared<const std::vector<std::uint8_t>>(
        emit::unsupportedFade(surface.net, fit->reachM, fit->unsupportedBeyondM, surface.refined));
}

}  // namespace relief
