#include "pipeline/depth.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>
#include <omp.h>

#include "core/number_format.h"
#include "core/stopwatch.h"
#include "curves/hausdorff.h"
#include "emit/camera.h"
#include "pipeline/map_frame.h"
#include "subdiv/refine.h"

namespace relief {

namespace {

// A net row (along x) or column (along y) as a planar control polygon:
// (position along the line, elevation), packed into Vec3 for the refiner.
struct NetCurve {
    std::string name;
    bool isRow;
    int index;
    std::vector<Vec3> points;
};

std::vector<NetCurve> netCurves(const geo::GeoGrid& net) {
    std::vector<NetCurve> curves;
    for (int r = 0; r < net.grid.rows; ++r) {
        NetCurve c{fmt::format("row {}", r), true, r, {}};
        for (int k = 0; k < net.grid.cols; ++k) c.points.push_back({net.x0 + k * net.dx, net.grid.at(r, k).z, 0});
        curves.push_back(std::move(c));
    }
    for (int k = 0; k < net.grid.cols; ++k) {
        NetCurve c{fmt::format("column {}", k), false, k, {}};
        for (int r = 0; r < net.grid.rows; ++r) c.points.push_back({net.y0 + r * net.dy, net.grid.at(r, k).z, 0});
        curves.push_back(std::move(c));
    }
    return curves;
}

curves::PiecewiseBezier polyline(const std::vector<Vec3>& points) {
    curves::CurveFile line{"polyline", false, {}};
    for (const Vec3& p : points) line.points.push_back({p.x, p.y});
    return curves::toBezier(line);
}

}  // namespace

DepthChoice chooseDepth(const subdiv::Scheme& scheme, const geo::GeoGrid& net, double toleranceM,
                        int maxDepth, int threads) {
    DepthChoice choice;
    std::vector<NetCurve> curves = netCurves(net);
    const int n = static_cast<int>(curves.size());
    const int nThreads = threads > 0 ? threads : omp_get_max_threads();
    // Each step's distances need far less precision than the tolerance, but
    // the rates between levels are worth seeing well below it.
    const double hausdorffTolerance = 1e-4 * toleranceM;
    for (int level = 1; level <= maxDepth; ++level) {
        const auto t0 = Clock::now();
        std::vector<curves::OneSided> witness(curves.size());
        std::vector<double> distance(curves.size());
        std::vector<std::vector<Vec3>> finer(curves.size());
        std::vector<curves::PiecewiseBezier> coarseLine(curves.size()), fineLine(curves.size());
        // Only the largest distance matters: the vertex-only distances (exact
        // lower bounds, cheap) give every curve's exact search a floor to beat.
        std::vector<double> lowerBound(curves.size());
#pragma omp parallel for num_threads(nThreads) schedule(dynamic, 1)
        for (int i = 0; i < n; ++i) {
            finer[i] = subdiv::refineCurve(scheme, curves[i].points);
            coarseLine[i] = polyline(curves[i].points);
            fineLine[i] = polyline(finer[i]);
            lowerBound[i] = curves::vertexHausdorff({&coarseLine[i], 1}, {&fineLine[i], 1});
        }
        const double floor = *std::max_element(lowerBound.begin(), lowerBound.end());
#pragma omp parallel for num_threads(nThreads) schedule(dynamic, 1)
        for (int i = 0; i < n; ++i) {
            const auto h = curves::hausdorff(coarseLine[i], fineLine[i], {hausdorffTolerance, floor});
            // The witness on the finer curve: where the new level put a point
            // farthest from the old one (or the old point farthest from the new).
            witness[i] = h.ba.value >= h.ab.value ? h.ba : h.ab;
            if (h.ba.value < h.ab.value) witness[i].a = h.ab.foot.point;
            distance[i] = h.H;
        }
        for (int i = 0; i < n; ++i) curves[i].points = std::move(finer[i]);
        LevelChange change;
        change.level = level;
        size_t worst = 0;
        for (size_t i = 1; i < curves.size(); ++i)
            if (distance[i] > distance[worst]) worst = i;  // first of equals: independent of threads
        change.distanceM = distance[worst];
        change.curve = curves[worst].name;
        const curves::Point2 w = witness[worst].a;
        change.x = curves[worst].isRow ? w.x : net.x0 + curves[worst].index * net.dx;
        change.y = curves[worst].isRow ? net.y0 + curves[worst].index * net.dy : w.x;
        change.z = w.y;
        change.seconds = secondsSince(t0);
        choice.levels.push_back(change);
        choice.depth = level;
        if (change.distanceM <= toleranceM) {
            choice.reached = true;
            break;
        }
    }
    return choice;
}

double observedRate(const DepthChoice& choice, size_t index, int arity) {
    if (index == 0 || index >= choice.levels.size()) return std::numeric_limits<double>::quiet_NaN();
    const double prev = choice.levels[index - 1].distanceM, cur = choice.levels[index].distanceM;
    if (!(prev > 0 && cur > 0)) return std::numeric_limits<double>::quiet_NaN();
    return std::log(prev / cur) / std::log(arity);
}

std::string depthLabel(const scene::SubdivisionSpec& sub) {
    if (sub.depthAuto) return fmt::format("depth auto (tolerance_m = {})", formatShortest(sub.toleranceM));
    return sub.depthGiven ? fmt::format("depth {}", sub.depth) : std::string("depth for the still");
}

namespace {
std::string levelSeries(const DepthChoice& choice) {
    std::string steps;
    for (const auto& l : choice.levels)
        steps += fmt::format("{}{}: {:.3g} m", steps.empty() ? "" : ", ", l.level, l.distanceM);
    return steps;
}
}  // namespace

std::string autoDepthSummary(const DepthChoice& choice, double toleranceM) {
    const std::string steps = levelSeries(choice);
    return fmt::format("depth {} chosen: the largest change per level (Hausdorff, net rows and "
                       "columns) was {}; tolerance {} m",
                       choice.depth, steps, formatShortest(toleranceM));
}




namespace {

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

}  // namespace

std::optional<DepthCost> costAt(const LoadedScene& loaded, const geo::ControlNet& net, const NetSize& size, int depth,
                                Diagnostics& diags) {
    const scene::SceneSpec& spec = loaded.scene;
    const subdiv::Scheme& scheme = loaded.resolved.scheme;
    const auto mesh = subdiv::estimateOutput(scheme, size.rows, size.cols, depth);
    auto geometry = emit::chooseGeometry(spec.geometry, geometryFacts(loaded, net, depth, mesh.triangles), diags);
    if (!geometry) return std::nullopt;
    DepthCost c{*geometry, mesh};
    if (geometry->kind == scene::GeometryKind::HeightField)
        c.estimate = subdiv::estimateOutput(scheme, size.rows, size.cols, depth, subdiv::GeometryCost::HeightField);
    else if (geometry->kind == scene::GeometryKind::Adaptive)
        c.estimate = subdiv::estimateOutput(scheme, size.rows, size.cols, depth, subdiv::GeometryCost::Adaptive);
    // The colours held beside the grid: a height field's drape (16-bit RGBA, a
    // node each); an image drape's too on any kind, and the image on the grid (RGB and coverage).
    const bool heightField = geometry->kind == scene::GeometryKind::HeightField;
    const bool image = spec.look.texture.colouring == scene::TextureSpec::Colouring::Image;
    c.estimate.memoryBytes += c.estimate.vertices * ((heightField || image ? 8 : 0) + (image ? 4 : 0));
    return c;
}

namespace {

// The least height above the ground an eye's footprint is taken at (an eye on
// or under the surface would otherwise see a pixel nanometres wide).
constexpr double kLowestEyeM = 1.7;

// The depth whose refined spacing is nearest one pixel of the still where the
// terrain is nearest the camera (within a factor sqrt(arity) of it): no more
// detail than the picture can show, and none less.
int depthForStill(const LoadedScene& loaded, const geo::ControlNet& net, const NetSize& size, double& pixelM) {
    const scene::SceneSpec& spec = loaded.scene;
    Diagnostics quiet;  // a camera point that cannot be placed is reported once, with the view
    const auto points = emit::cameraPointsInFrame(spec.look.camera, net.frame, quiet);
    const emit::ScenePlacement where = emit::placeTerrain(net, spec.look);
    const emit::CameraView camera = emit::placeCamera(where, spec.look.camera, points.value_or(emit::CameraPoints{}),
                                                      spec.render, frameInsetOf(spec, mapFrameTicks(spec, net, quiet)));
    pixelM = emit::finestMetresPerPixel(camera, where, spec.render.width);
    // An eye among the terrain's heights is inside its bounding box, whose nearest point is then
    // the eye itself: the footprint of a pixel at its height above the ground under it instead.
    if (points && points->eyeM && camera.perspective)
        if (const auto ground = net.sample(points->eyeM->x, points->eyeM->y)) {
            const double aboveM = std::max(points->eyeM->z - *ground, kLowestEyeM);
            pixelM = std::max(pixelM, 2 * aboveM * camera.tanHalfFov / spec.render.width);
        }
    const double arity = loaded.resolved.scheme.arity, spacing = std::max(size.dx, size.dy);
    int depth = 0;
    while (depth < scene::kMaxDepth && spacing / std::pow(arity, depth) > pixelM * std::sqrt(arity)) ++depth;
    return depth;
}

// depth = "auto": the smallest depth whose last level moves the terrain by at
// most tolerance_m, searched up to the deepest the budget allows.
bool chooseAutoDepth(const LoadedScene& loaded, const geo::ControlNet& net, const NetSize& size, int threads,
                     SurfaceDepth& s, Diagnostics& diags) {
    const scene::SubdivisionSpec& sub = loaded.scene.subdivision;
    const subdiv::Scheme& scheme = loaded.resolved.scheme;
    // When not even level 1 fits, the budget check after says so.
    const int maxDepth =
        subdiv::deepestWithinBudget(scheme, size.rows, size.cols, loaded.budget, scene::kMaxDepth);
    s.depth = 1;
    if (maxDepth <= 0) return true;
    s.autoDepth = chooseDepth(scheme, net, sub.toleranceM, maxDepth, threads);
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
    s.reason = autoDepthSummary(*s.autoDepth, sub.toleranceM);
    return true;
}

// The refined nodes a still's pixels are worth: a pixel shows at most about
// this many. Where the nearest terrain asks for more (a camera at a place, a
// low view: the footprint there is far finer than over the rest), refining
// the whole terrain to it would cost the nodes the far ground shows as one
// pixel: the depth stops at this, the foreground as fine as it allows.
constexpr double kNodesPerPixel = 4;

// No depth in the scene: the still's (depthForStill), or the deepest below it
// that the pixels are worth and [limits] allow; a default never refuses a
// scene that fits at depth 0.
void chooseStillDepth(const LoadedScene& loaded, const geo::ControlNet& net, const NetSize& size, SurfaceDepth& s) {
    double pixelM = 0;
    const int wanted = depthForStill(loaded, net, size, pixelM);
    const double pixels = double(loaded.scene.render.width) * loaded.scene.render.height;
    const auto nodesAt = [&](int d) {
        const auto e = subdiv::estimateOutput(loaded.resolved.scheme, size.rows, size.cols, d);
        return double(e.rows) * double(e.cols);
    };
    int depth = wanted;
    while (depth > 0 && nodesAt(depth) > kNodesPerPixel * pixels) --depth;
    const int worth = depth;
    for (; depth > 0; --depth) {
        Diagnostics quiet;
        const auto cost = costAt(loaded, net, size, depth, quiet);
        if (cost && subdiv::withinBudget(cost->estimate, loaded.budget)) break;
    }
    s.depth = depth;
    const double netM = std::max(size.dx, size.dy), refinedM = netM / std::pow(loaded.resolved.scheme.arity, depth);
    const int width = loaded.scene.render.width;
    if (worth == wanted)
        s.reason = fmt::format("chosen for the still: the net's {:.3g} m refined to {:.3g} m, about the {:.3g} m one "
                               "pixel of the {} px wide still covers where the terrain is nearest the camera",
                               netM, refinedM, pixelM, width);
    else
        s.reason = fmt::format("chosen for the still: the net's {:.3g} m refined to {:.3g} m; the {:.3g} m one pixel "
                               "of the {} px wide still covers where the terrain is nearest the camera would take "
                               "depth {}, {:.3g} nodes, more than the still's {:.3g} pixels are worth ({} a pixel)",
                               netM, refinedM, pixelM, width, wanted, nodesAt(wanted), pixels,
                               formatShortest(kNodesPerPixel));
    if (depth < worth) s.reason += fmt::format(" (depth {} would be over [limits])", worth);
}

}  // namespace

std::optional<SurfaceDepth> chooseSurfaceDepth(const LoadedScene& loaded, const geo::ControlNet& net,
                                               const NetSize& size, int threads, Diagnostics& diags) {
    const scene::SubdivisionSpec& sub = loaded.scene.subdivision;
    SurfaceDepth s;
    if (sub.depthAuto) {
        if (!chooseAutoDepth(loaded, net, size, threads, s, diags)) return std::nullopt;
    } else if (sub.depthGiven) {
        s.depth = sub.depth;
        s.reason = "subdivision.depth";
    } else {
        chooseStillDepth(loaded, net, size, s);
    }
    return s;
}

}  // namespace relief
