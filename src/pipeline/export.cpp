#include "pipeline/export.h"

#include <algorithm>
#include <cmath>
#include <new>
#include <span>
#include <vector>

#include <fmt/format.h>

#include "core/output_set.h"
#include "core/stopwatch.h"
#include "emit/adaptive_mesh.h"
#include "emit/height_field.h"
#include "geo/raster.h"
#include "model/terrain_model.h"
#include "pipeline/load.h"
#include "pipeline/surface.h"
#include "relief/version.h"

namespace relief {

namespace fs = std::filesystem;

namespace {

// The model of the surface within `maxTriangles`: every node a vertex when that fits (a floor
// doubles the surface's triangles: counted before the model is made), else the adaptive mesh at
// about the least tolerance that fits: raised (by how far over the last try was, its triangles
// going as one over the tolerance on a smooth surface) until one fits, then narrowed
// geometrically between the last over and the first within, kNarrowings times. Nullopt when
// raising the tolerance kStalledTries times in a row lowers the count no more (the walls of many
// holes) and none fits.
using Fitted = SceneModel;
constexpr int kNarrowings = 4;
constexpr int kStalledTries = 3;  // raisings in a row that lower nothing: no tolerance will
std::optional<Fitted> modelWithin(const Surface& surface, const emit::ScenePlacement& where,
                                  std::span<const LinearRgb> colours, long long maxTriangles, const ProgressFn& progress) {
    const std::optional<double> floor = where.baseElevationM;
    const auto within = [&](const Fitted& m) { return static_cast<long long>(m.model.triangles()) <= maxTriangles; };
    {
        const emit::Mesh mesh = emit::buildMesh(surface.refined, where);
        if (mesh.triangles * (floor ? 2 : 1) <= maxTriangles) {
            Fitted f{model::terrainModel(mesh, floor, colours), 0, {}};
            if (within(f)) return f;
        }
    }
    const auto adaptive = [&](double tolerance) {
        if (progress)
            progress({ProgressEvent::Stage::Compiling,
                      fmt::format("over --max-triangles {}: an adaptive mesh within {:.3g} m", maxTriangles, tolerance),
                      -1});
        return Fitted{model::terrainModel(emit::buildAdaptiveMesh(surface.refined, where, tolerance), floor, colours),
                      tolerance, {}};
    };
    double over = 0, tolerance = 1e-4 * std::max(where.zMaxM - where.zMinM, 1e-3);
    Fitted f = adaptive(tolerance);
    for (int stalled = 0; !within(f);) {
        const double ratio = static_cast<double>(f.model.triangles()) / static_cast<double>(maxTriangles);
        over = tolerance;
        tolerance *= std::clamp(ratio, 1.25, 8.0);
        const size_t before = f.model.triangles();
        f = adaptive(tolerance);
        stalled = f.model.triangles() < before ? 0 : stalled + 1;
        if (!within(f) && stalled == kStalledTries) return std::nullopt;
    }
    for (int k = 0; over > 0 && k < kNarrowings; ++k) {
        Fitted mid = adaptive(std::sqrt(over * f.toleranceM));
        if (within(mid)) f = std::move(mid);
        else over = mid.toleranceM;
    }
    return f;
}

// [texture] image: each refined node's colour as the drape PNG the still renders has it.
std::optional<std::vector<LinearRgb>> drapedColours(const scene::SceneSpec& spec, const geo::GeoGrid& refined,
                                                    const emit::ScenePlacement& where, Diagnostics& diags) {
    const auto image = geo::imageOnGrid(spec.look.texture.drapeImage, spec.look.texture.drapeImageText, refined, diags);
    if (!image) return std::nullopt;
    const emit::Drape drape = emit::imageDrape(refined, where, *image);
    std::vector<LinearRgb> colours(refined.grid.points.size());
    const auto channels = static_cast<size_t>(drape.channels), cols = static_cast<size_t>(drape.cols);
    for (size_t r = 0; r < static_cast<size_t>(drape.rows); ++r)
        for (size_t c = 0; c < cols; ++c) {
            const std::uint16_t* px = drape.pixels.data() + ((drape.rows - 1 - r) * cols + c) * channels;  // north first
            colours[r * cols + c] = {px[0] / 65535.0, px[1] / 65535.0, px[2] / 65535.0};
        }
    return colours;
}

}  // namespace

std::optional<SceneModel> sceneModel(const LoadedScene& loaded, const Surface& surface, long long maxTriangles,
                                     Diagnostics& diags, const ProgressFn& progress) {
    emit::ScenePlacement where = emit::placeTerrain(surface.refined, loaded.scene.look);
    where.fade = unsupportedFadeOf(surface);
    std::vector<LinearRgb> colours;
    if (loaded.scene.look.texture.colouring == scene::TextureSpec::Colouring::Image) {
        auto draped = drapedColours(loaded.scene, surface.refined, where, diags);
        if (!draped) return std::nullopt;
        colours = std::move(*draped);
    }
    auto fitted = modelWithin(surface, where, colours, maxTriangles, progress);
    if (!fitted) {
        diags.error(budgetKey(loaded.scene),
                    fmt::format("no mesh of the surface fits within --max-triangles {}: raise it", maxTriangles));
        return std::nullopt;
    }
    if (fitted->model.triangles() == 0) {
        diags.error(budgetKey(loaded.scene), "no triangle of the surface has data at its three corners: there is "
                                             "no model to write (a finer net, or data over more of it)");
        return std::nullopt;
    }
    fitted->where = std::move(where);
    return fitted;
}

std::optional<ExportOutcome> exportTerrain(const ExportJob& job, Diagnostics& diags, const ProgressFn& progress) {
    const auto t0 = Clock::now();
    const fs::path output = job.output.empty() ? fs::path("out") / (job.scenePath.stem().string() + ".glb") : job.output;
    const model::ModelFormatRow* format = model::modelFormatOf(output);
    if (!format) {
        diags.error({output.string(), 0, 0}, fmt::format("relief export writes {}, chosen by the extension: give -o "
                                                         "one of them",
                                                         model::modelExtensionsListed()));
        return std::nullopt;
    }
    try {
        if (progress) progress({ProgressEvent::Stage::Reading, "reading " + job.scenePath.string(), -1});
        auto loaded = loadScene(job.scenePath, diags, job.overrides);
        if (!loaded) return std::nullopt;
        if (format->solid || job.solid) loaded->scene.look.base.enabled = true;
        OutputSet outputs;
        outputs.addInput(job.scenePath, "the scene");
        const fs::path staged = outputs.add(output, "-o");
        auto surface = buildSurface(*loaded, diags, job.threads, progress);
        if (!surface) return std::nullopt;
        auto fitted = sceneModel(*loaded, *surface, job.maxTriangles, diags, progress);
        if (!fitted) return std::nullopt;
        if (job.acrossMM) model::scaleAcross(fitted->model, *job.acrossMM);
        if (progress) progress({ProgressEvent::Stage::Finishing, "writing " + output.string(), -1});
        model::writeModel(fitted->model, *format, staged, fmt::format("relief {}", kVersion));
        ExportOutcome out;
        out.bytes = fs::file_size(staged);
        outputs.commit();
        const model::TerrainModel& m = fitted->model;
        const auto partSize = [&](const char* name) { return m.part(name) ? m.part(name)->faces.size() : size_t{0}; };
        out.output = output;
        out.format = format->name;
        out.vertices = m.positions.size();
        out.surfaceTriangles = partSize("surface"), out.wallTriangles = partSize("walls"), out.floorTriangles = partSize("floor");
        out.rows = surface->refined.rows(), out.cols = surface->refined.cols(), out.depth = surface->depth;
        out.toleranceM = fitted->toleranceM;
        out.unitsPerMetre = m.unitsPerMetre;
        out.floorElevationM = fitted->where.baseElevationM;
        out.seconds = secondsSince(t0);
        return out;
    } catch (const OutputError& e) {
        diags.error(e.at(), e.problem());
    } catch (const std::bad_alloc&) {
        diags.error({output.string(), 0, 0}, "the model does not fit in memory: a lower --max-triangles");
    } catch (const std::runtime_error& e) {
        diags.error({output.string(), 0, 0}, fmt::format("the model cannot be written: {}", e.what()));
    }
    return std::nullopt;
}

}  // namespace relief
