#include "pipeline/preview.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <fmt/format.h>

#include "annotate/overlay.h"
#include "core/atomic_file.h"
#include "core/input_file.h"
#include "core/png_file.h"
#include "core/number_format.h"
#include "emit/camera.h"
#include "geo/normalize.h"
#include "model/terrain_model.h"
#include "pipeline/export.h"
#include "pipeline/compile.h"
#include "pipeline/load.h"
#include "pipeline/map_frame.h"
#include "pipeline/record.h"
#include "pipeline/surface.h"
#include "pipeline/view.h"
#include "relief/version.h"
#include "scene/edit_scene.h"
#include "scene/read_scene.h"

namespace relief {

namespace fs = std::filesystem;

namespace {

constexpr double kRadiansPerDegree = std::numbers::pi / 180.0;

// A scene point (POV-Ray's east, up, north, scene units) in the model's axes (glTF's east, up,
// south, metres): what the page's three.js scene holds.
nlohmann::json modelAxes(const emit::ScenePlacement& where, const SceneVec3& p) {
    const double m = where.metresPerUnit;
    return {p.x * m, p.y * m, -p.z * m};
}

// The page's facts: the still's frame and camera (as the still places it), the sun, the water.
nlohmann::json pageFacts(const LoadedScene& loaded, const View& view, const SceneModel& model) {
    const scene::LookSpec& look = loaded.scene.look;
    const emit::CameraView& cam = view.camera;
    nlohmann::json page;
    page["scene"] = loaded.scene.sceneFile.filename().string();
    page["still"] = {{"width", loaded.scene.render.width}, {"height", loaded.scene.render.height}};
    page["camera"] = {{"eye", modelAxes(model.where, cam.eye)},
                      {"target", modelAxes(model.where, cam.target)},
                      {"fovDeg", 2 * std::atan(cam.tanHalfFov) / kRadiansPerDegree},
                      {"perspective", cam.perspective && !cam.wide}};
    const SceneVec3 sun = emit::sceneDirection(view.sun.azimuthDeg, view.sun.altitudeDeg);
    page["sun"] = {{"direction", {sun.x, sun.y, -sun.z}},
                   {"azimuthDeg", view.sun.azimuthDeg},
                   {"altitudeDeg", view.sun.altitudeDeg}};
    page["water"] = nullptr;
    if (look.water.levelM) {
        const double y = model.where.scenePoint({model.where.originM.x, model.where.originM.y, *look.water.levelM}).y;
        const auto& c = look.water.colour;
        page["water"] = {{"y", y * model.where.metresPerUnit},
                         {"colour", {c.r, c.g, c.b}},
                         {"transparency", look.water.transparency}};
    }
    const SceneVec3 lo = model.where.boundsMin, hi = model.where.boundsMax;
    page["bounds"] = {modelAxes(model.where, {lo.x, lo.y, hi.z}), modelAxes(model.where, {hi.x, hi.y, lo.z})};
    page["model"] = {{"vertices", model.model.positions.size()},
                     {"triangles", model.model.triangles()},
                     {"toleranceM", model.toleranceM}};
    return page;
}

// Where the still's furniture (title, legend, scale bar, north arrow, credits, a map frame's
// annotations) goes from the scene's camera, in the still's pixels: drawn on a blank still of its
// size, the drawing being the placement's one implementation, and each item's box kept.
nlohmann::json furnitureBoxes(const LoadedScene& loaded, const Surface& surface, const View& view) {
    const scene::SceneSpec& spec = loaded.scene;
    nlohmann::json boxes = nlohmann::json::array();
    if (!annotate::overlaysWanted(spec.overlay, spec.render.width)) return boxes;
    annotate::OverlayFacts facts =
        annotate::overlayFacts(spec.look, view.where, view.camera, spec.render,
                               geo::gridConvergenceDeg(surface.net.frame, view.where.originM.x, view.where.originM.y));
    facts.credits = spec.overlay.credits ? *spec.overlay.credits : dataCredit(spec.samples, surface.net).text;
    if (view.frameTicks)
        facts.mapFrame = mapFrameOnImage(*view.frameTicks, view.where, view.camera, spec.render.width, spec.render.height);
    PngImage8 blank{spec.render.width, spec.render.height, 4, {}};
    blank.pixels.assign(static_cast<size_t>(blank.width) * static_cast<size_t>(blank.height) * 4, 0);
    Diagnostics unused;  // what was left out is the still's to say
    annotate::OverlayRecord record;
    if (!annotate::drawOverlays(blank, spec.overlay, facts, {}, unused, &record)) return boxes;
    for (const auto& [item, b] : record.boxes) {
        const nlohmann::json box = {b.x0, b.y0, b.x1, b.y1};
        // Items drawn as one block (the title and its subtitle) are one outline named for both.
        auto same = std::find_if(boxes.begin(), boxes.end(), [&](const nlohmann::json& o) { return o["box"] == box; });
        if (same != boxes.end()) (*same)["item"] = (*same)["item"].get<std::string>() + ", " + item;
        else boxes.push_back({{"item", item}, {"box", box}});
    }
    return boxes;
}

std::string lonLatHeight(const GeoPoint& g) {
    return fmt::format("[{}, {}, {}]", formatShortest(g.lonDeg), formatShortest(g.latDeg), formatShortest(g.heightM));
}

}  // namespace

std::optional<PreviewScene> previewScene(const PreviewJob& job, Diagnostics& diags, const ProgressFn& progress) {
    if (progress) progress({ProgressEvent::Stage::Reading, "reading " + job.scenePath.string(), -1});
    const auto loaded = loadScene(job.scenePath, diags, job.overrides);
    if (!loaded) return std::nullopt;
    auto surface = buildSurface(*loaded, diags, job.threads, progress);
    if (!surface) return std::nullopt;
    const auto view = resolveView(loaded->scene, surface->net, surface->refined, diags);
    if (!view) return std::nullopt;
    auto model = sceneModel(*loaded, *surface, job.maxTriangles, diags, progress);
    if (!model) return std::nullopt;
    if (progress) progress({ProgressEvent::Stage::Finishing, "serving the model", -1});
    PreviewScene out;
    const model::ModelFormatRow* glb = model::modelFormatOf("preview.glb");
    try {
        out.glb = model::modelBytes(model->model, *glb, fmt::format("relief {}", kVersion));
    } catch (const std::runtime_error& e) {
        diags.error({job.scenePath.string(), 0, 0}, fmt::format("the preview's model cannot be made: {}", e.what()));
        return std::nullopt;
    }
    out.page = pageFacts(*loaded, *view, *model);
    out.page["furniture"] = furnitureBoxes(*loaded, *surface, *view);
    out.where = model->where;
    out.frame = surface->net.frame;
    if (!loaded->scene.madeForData.empty()) {
        out.newScenePath = fs::path(job.scenePath.stem().string() + ".toml");
        out.newSceneText = initSceneText(*loaded, *surface, out.newScenePath);
    }
    return out;
}

std::vector<std::pair<std::string, std::string>> CameraKeys::toml() const {
    return {{"position", lonLatHeight(position)}, {"look_at", lonLatHeight(lookAt)}, {"fov_deg", formatShortest(fovDeg)}};
}

std::optional<CameraKeys> cameraKeysOf(const PreviewScene& preview, const PageView& view, Diagnostics& diags) {
    const emit::ScenePlacement& where = preview.where;
    // The inverse of ScenePlacement::scenePoint after modelAxes: the frame point drawn there.
    const auto framePoint = [&](const Vec3& m) {
        const double x = m.x + where.originM.x, y = -m.z + where.originM.y;
        const double drawn = m.y / where.exaggeration, fall = where.fallAt({x, y, 0});
        return Vec3{x, y, drawn + fall - fall / where.exaggeration};
    };
    const auto geographic = [&](const Vec3& m, const char* what) -> std::optional<GeoPoint> {
        const auto g = geo::reverse(preview.frame, framePoint(m));
        if (g && std::isfinite(g->lonDeg) && std::isfinite(g->latDeg) && std::isfinite(g->heightM)) return g;
        diags.error({"camera", 0, 0}, fmt::format("the view's {} has no longitude and latitude in the scene's frame "
                                                  "({}): bring it nearer the terrain",
                                                  what, preview.frame.describe()));
        return std::nullopt;
    };
    if (!(view.fovDeg >= 1 && view.fovDeg <= 170)) {
        diags.error({"camera", 0, 0}, fmt::format("the view's field of view ({} degrees across) is outside what a "
                                                  "perspective camera takes (1 to 170)",
                                                  formatShortest(view.fovDeg)));
        return std::nullopt;
    }
    const auto eye = geographic(view.eye, "eye");
    const auto target = eye ? geographic(view.target, "target") : std::nullopt;
    if (!target) return std::nullopt;
    return CameraKeys{*eye, *target, view.fovDeg};
}

std::optional<std::vector<std::pair<std::string, std::string>>> flyoverKeysOf(const PreviewScene& preview,
                                                                              std::span<const PageView> keyframes,
                                                                              Diagnostics& diags) {
    if (keyframes.size() < 2) {
        diags.error({"animation", 0, 0}, fmt::format("a flyover needs two keyframes or more, and there {}: add "
                                                     "views with K",
                                                     keyframes.size() == 1 ? "is one" : "are none"));
        return std::nullopt;
    }
    std::vector<CameraKeys> keys;
    for (const PageView& view : keyframes) {
        auto k = cameraKeysOf(preview, view, diags);
        if (!k) return std::nullopt;
        keys.push_back(*k);
    }
    std::string waypoints = "[";
    bool oneTarget = true;
    for (size_t i = 0; i < keys.size(); ++i) {
        if (i > 0 && length(keyframes[i].eye - keyframes[i - 1].eye) < 1e-3) {
            diags.error({"animation", 0, 0}, fmt::format("keyframes {} and {} are one place: a flyover moves between "
                                                         "its keyframes (orbit or fly between them)",
                                                         i, i + 1));
            return std::nullopt;
        }
        oneTarget = oneTarget && length(keyframes[i].target - keyframes[0].target) < 1e-3;
        waypoints += (i ? ", " : "") + lonLatHeight(keys[i].position);
    }
    std::vector<std::pair<std::string, std::string>> out{{"path", "\"flyover\""}, {"waypoints", waypoints + "]"}};
    if (oneTarget) out.push_back({"look_at", lonLatHeight(keys[0].lookAt)});
    return out;
}

std::vector<std::pair<std::string, std::string>> flyoverDefaultsOf(size_t keyframes) {
    return {{"frames", std::to_string(kFlyoverFramesPerLeg * std::max<size_t>(keyframes, 2) - kFlyoverFramesPerLeg)}};
}

std::optional<fs::path> writeSceneKeys(const PreviewScene& preview, const fs::path& scenePath, const std::string& table,
                                       const std::vector<std::pair<std::string, std::string>>& keys,
                                       std::span<const char* const> retired, Diagnostics& diags,
                                       const std::vector<std::pair<std::string, std::string>>& defaults) {
    const fs::path target = preview.newScenePath.empty() ? scenePath : preview.newScenePath;
    std::error_code ec;
    const bool exists = fs::exists(fs::symlink_status(target, ec));
    std::string before = preview.newSceneText;
    if (exists) {
        std::string problem;
        auto text = readInputFile(target, kMaxSceneBytes, problem);
        if (!text) {
            diags.error({target.string(), 0, 0}, fmt::format("{}: the view is not written", problem));
            return std::nullopt;
        }
        before = std::move(*text);
    }
    const std::vector<std::string> retiredKeys(retired.begin(), retired.end());
    const auto after = scene::withTableKeys(before, target.string(), table, keys, retiredKeys, diags, defaults);
    if (!after) return std::nullopt;
    // The scene as it would be, read as relief reads it: one that would not load is not written
    // (camera.position with a map frame or an orbit film), and the reason is the reader's.
    Diagnostics check;
    if (!scene::readSceneText(*after, target, check) || check.hasErrors()) {
        for (const auto& d : check.all())
            if (d.severity == Severity::Error) diags.error(d.loc, d.message + " (so the view is not written)");
        return std::nullopt;
    }
    try {
        const auto perms = exists ? fs::status(target).permissions() : fs::perms::unknown;
        if (exists) writeFileAtomically(fs::path(target.string() + ".bak"), before);
        writeFileAtomically(target, *after);
        // The scene keeps its permissions (a private scene stays private), its backup too.
        if (exists) {
            fs::permissions(target, perms);
            fs::permissions(fs::path(target.string() + ".bak"), perms);
        }
    } catch (const std::exception& e) {
        diags.error({target.string(), 0, 0}, fmt::format("the scene cannot be written: {}", e.what()));
        return std::nullopt;
    }
    return target;
}

}  // namespace relief
