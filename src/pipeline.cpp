#include "pipeline.h"

#include <chrono>
#include <cmath>
#include <mutex>
#include <numbers>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "core/atomic_file.h"
#include "core/date_time.h"
#include "core/input_file.h"
#include "core/number_format.h"
#include "core/png_file.h"
#include "core/text_escape.h"
#include "emit/adaptive_mesh.h"
#include "emit/block_base.h"
#include "emit/surface_contours.h"
#include "emit/height_field.h"
#include "emit/mesh.h"
#include "geo/raster.h"
#include "geo/samples.h"
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


namespace {

const char* name(scene::Gridding g) {
    switch (g) {
        case scene::Gridding::Linear: return "linear";
        case scene::Gridding::InverseDistance: return "invdist";
        case scene::Gridding::Nearest: return "nearest";
    }
    return "?";
}

emit::ParameterList describe(const scene::SceneSpec& s, const geo::ControlNet& net,
                             const subdiv::ResolvedScheme& scheme, int depth,
                             const CompileResult& compiled) {
    const subdiv::OutputEstimate& est = compiled.estimate;
    const scene::SubdivisionSpec& sub = s.subdivision;
    const scene::LookSpec& look = s.look;
    const scene::CameraSpec& camera = look.camera;
    emit::ParameterList p;
    auto add = [&](std::string k, std::string v) { p.emplace_back(std::move(k), std::move(v)); };
    add("relief", kVersion);
    add("scene", s.sceneFile.string());
    add("scene_sha1", s.sceneSha1);
    for (const auto& [k, v] : s.overrides) add("override " + k, v);
    add("samples.path", s.samples.pathAsWritten);
    if (!s.samples.attribution.empty()) add("samples.attribution", s.samples.attribution);
    else if (!net.attribution.empty()) add("samples.attribution", net.attribution + " (from the raster's metadata)");
    add("samples.count", std::to_string(net.sampleCount));
    add("frame", net.frame.describe());
    add("net.size", fmt::format("{} rows x {} cols", net.grid.rows, net.grid.cols));
    add("net.spacing_m", fmt::format("{} x {}", formatShortest(net.dx), formatShortest(net.dy)));
    add("net.origin_m", fmt::format("{}, {}", formatShortest(net.x0), formatShortest(net.y0)));
    if (net.raster.empty()) add("net.gridding", name(s.net.gridding));
    else add("samples.raster", net.raster);
    if (net.filledNodata > 0) add("net.filled_nodata", std::to_string(net.filledNodata));
    else if (!net.masked.empty()) add("net.masked_nodata", std::to_string(net.maskedCount()));
    else add("net.filled_outside_hull", std::to_string(net.filledOutsideHull));
    add("vertical.exaggeration", formatShortest(look.exaggeration));
    std::string params;
    for (const auto& [k, v] : scheme.params)
        params += fmt::format("{}{} = {}", params.empty() ? "" : ", ", k, formatShortest(v));
    if (scheme.family == "mask")
        for (double v : sub.scheme.mask) params += fmt::format("{}{}", params.empty() ? "mask " : ", ", formatShortest(v));
    add("subdivision.scheme", scheme.family);
    if (!sub.scheme.preset.empty()) add("subdivision.preset", sub.scheme.preset);
    add("subdivision.params", params);
    add("subdivision.certified", subdiv::certifiedClass(scheme.report));
    add("subdivision.boundary", "point reflection");
    add("subdivision.depth", sub.depthAuto ? fmt::format("{} (auto, tolerance_m = {})", depth,
                                                         formatShortest(sub.toleranceM))
                                         : std::to_string(depth));
    add("refined.size", fmt::format("{} rows x {} cols", est.rows, est.cols));
    add("refined.vertices", fmt::format("{:.0f}", est.vertices));
    add("refined.triangles", fmt::format("{:.0f}", est.triangles));
    add("geometry", fmt::format("{} ({})", emit::geometryKindName(compiled.geometry.kind), compiled.geometry.reason));
    if (compiled.geometry.kind == scene::GeometryKind::HeightField)
        add("geometry.height_field", fmt::format("{}, 16-bit, one level = {:.3g} m", compiled.heightPng.filename().string(),
                                                 compiled.heightStepM));
    if (compiled.geometry.kind == scene::GeometryKind::Adaptive)
        add("geometry.adaptive", fmt::format("{} triangles of the full mesh2's {:.0f}, vertical error at most {:.3g} m "
                                             "({:.2g} px)",
                                             compiled.meshTriangles, est.triangles, compiled.adaptiveToleranceM,
                                             compiled.adaptiveTolerancePx));
    else if (compiled.maskedNodes > 0)
        add("mesh.with_data", fmt::format("{} vertices, {} triangles (masked nodata left out)",
                                          compiled.meshVertices, compiled.meshTriangles));
    if (s.overlay.contours && s.overlay.enabled != scene::OverlaySpec::Enabled::Off)
        add("overlay.contours", fmt::format("every {} m on the surface{}", formatShortest(s.overlay.contours->intervalM),
                                            s.overlay.contours->indexEvery > 0
                                                ? fmt::format(", every {}th heavier", s.overlay.contours->indexEvery)
                                                : std::string()));
    if (compiled.baseFloorM)
        add("base", fmt::format("a block: walls down to a floor at {:.2f} m, {:.2f} m below the lowest point",
                                *compiled.baseFloorM, compiled.zRangeM[0] - *compiled.baseFloorM));
    add("texture.ramp", look.ramp.cptPath.empty() ? look.ramp.preset : "cpt " + look.ramp.cptPath);
    using Colouring = scene::LookSpec::Colouring;
    if (look.colouring == Colouring::Image) add("texture.image", look.drapeImageText);
    if (look.colouring == Colouring::Slope || look.colouring == Colouring::Blend)
        add("texture.mode", fmt::format("{}: rock from {} to {} degrees of slope",
                                        look.colouring == Colouring::Slope ? "slope" : "blend",
                                        formatShortest(look.rockFromDeg), formatShortest(look.rockToDeg)));
    if (compiled.sun.fromDatetime)
        add("lighting.sun", fmt::format("azimuth {:.2f} deg (true), altitude {:.2f} deg, at {} over lon {:.4f} lat {:.4f}",
                                        compiled.sun.azimuthDeg, compiled.sun.altitudeDeg,
                                        oneLineText(compiled.sun.datetime), compiled.sun.lonDeg, compiled.sun.latDeg));
    else
        add("lighting.sun", fmt::format("azimuth {} deg, altitude {} deg", formatShortest(look.sunAzimuthDeg),
                                        formatShortest(look.sunAltitudeDeg)));
    const char* projection = camera.projection == scene::Projection::Perspective ? "perspective" : "orthographic";
    const auto lonLatH = [](const std::array<double, 3>& p) {
        return fmt::format("lon {} lat {} height {} m", formatShortest(p[0]), formatShortest(p[1]), formatShortest(p[2]));
    };
    if (camera.position)
        add("camera", fmt::format("{}, at {}, looking at {}, fov {} deg", projection, lonLatH(*camera.position),
                                  camera.lookAt ? lonLatH(*camera.lookAt) : std::string("the terrain's centre"),
                                  formatShortest(camera.fovDeg)));
    else
        add("camera", fmt::format("{}, azimuth {} deg, elevation {} deg, distance {}, fov {} deg", projection,
                                  formatShortest(camera.azimuthDeg), formatShortest(camera.elevationDeg),
                                  camera.distanceM > 0 ? formatShortest(camera.distanceM) + " m" : std::string("fit"),
                                  formatShortest(camera.fovDeg)));
    add("render", fmt::format("{} x {}, antialias {}", s.render.width, s.render.height,
                              s.render.antialias ? "on" : "off"));
    if (s.render.background == scene::Background::Transparent) add("render.background", "transparent");
    if (s.render.background == scene::Background::Colour) {
        const auto& c = s.render.backgroundColour;  // linear RGB, as POV-Ray gets it
        add("render.background", fmt::format("rgb {} {} {}", formatShortest(c.r), formatShortest(c.g), formatShortest(c.b)));
    }
    add("scene_unit_m", formatShortest(compiled.metresPerUnit));
    return p;
}

}  // namespace

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

std::optional<CompileResult> compileScene(const LoadedScene& loaded,
                                          const CompileOptions& options, Diagnostics& diags) {
    CompileResult result;
    const scene::SceneSpec& spec = loaded.scene;
    result.times.readScene = loaded.seconds;

    auto tmpl = emit::loadSceneTemplate(options.templatesDir, diags);
    if (!tmpl) return std::nullopt;
    auto surface = buildSurface(loaded, diags, options.threads, options.progress);
    if (!surface) return std::nullopt;
    result.estimate = surface->estimate;
    result.times.normalize = surface->normalizeSeconds;
    result.times.subdivide = surface->subdivideSeconds;
    const geo::ControlNet& net = surface->net;

    // A camera placed by geography: its eye and target in the frame's metres.
    scene::LookSpec look = spec.look;
    {
        scene::CameraSpec& camera = look.camera;
        const auto toFrame = [&](const std::array<double, 3>& lonLatH, const char* key) -> std::optional<Vec3> {
            Vec3 p;
            if (geo::geodeticToFrame(net.frame, lonLatH[1], lonLatH[0], lonLatH[2], p)) return p;
            diags.error(look.locs.at(key), fmt::format("{} = [{}, {}, {}] cannot be placed in the scene's frame ({}): "
                                                       "put it nearer the terrain, or use frame.kind = \"local\"",
                                                       key, formatShortest(lonLatH[0]), formatShortest(lonLatH[1]),
                                                       formatShortest(lonLatH[2]), net.frame.describe()));
            return std::nullopt;
        };
        if (camera.position && !(camera.positionFrameM = toFrame(*camera.position, "camera.position")))
            return std::nullopt;
        if (camera.lookAt && !(camera.lookAtFrameM = toFrame(*camera.lookAt, "camera.look_at"))) return std::nullopt;
        if (camera.positionFrameM && camera.lookAtFrameM && length(*camera.positionFrameM - *camera.lookAtFrameM) < 1e-3) {
            diags.error(look.locs.at("camera.look_at"), "camera.look_at is where camera.position is: a camera must "
                                                        "look at a point away from itself");
            return std::nullopt;
        }
    }

    // The sun: the scene's angles, or where it stood at [lighting] datetime
    // over the terrain's centre. The scene's axes are the frame's grid, whose
    // north is the meridian convergence away from true north.
    const double convergenceDeg =
        geo::gridConvergenceDeg(net.frame, (net.x0 + net.xMax()) / 2, (net.y0 + net.yMax()) / 2);
    result.sun = {look.sunAzimuthDeg, look.sunAltitudeDeg, false, {}, 0, 0};
    if (look.sunTime) {
        double lat = 0, lon = 0, h = 0;
        if (!geo::frameToGeodetic(net.frame, Vec3{(net.x0 + net.xMax()) / 2, (net.y0 + net.yMax()) / 2, 0}, lat, lon,
                                  h)) {
            diags.error(look.locs.at("lighting.datetime"), "lighting.datetime: the terrain's centre has no longitude "
                                                           "and latitude in its frame; give sun_azimuth_deg and "
                                                           "sun_altitude_deg instead");
            return std::nullopt;
        }
        const geo::SunPosition sun = geo::sunPosition(lon, lat, look.sunTime->utcSeconds);
        if (!(sun.altitudeDeg > 0)) {
            diags.error(look.locs.at("lighting.datetime"),
                        fmt::format("lighting.datetime = \"{}\"{}: the sun is {:.1f} degrees below the horizon at "
                                    "the terrain's centre (lon {:.4f}, lat {:.4f}); choose a time in daylight, or give "
                                    "sun_azimuth_deg and sun_altitude_deg",
                                    printableExcerpt(look.sunTimeText),
                                    look.sunTime->offsetMinutes != 0 ? " (" + formatUtc(look.sunTime->utcSeconds) + ")"
                                                                     : std::string(),
                                    -sun.altitudeDeg, lon, lat));
            return std::nullopt;
        }
        result.sun = {sun.azimuthDeg, sun.altitudeDeg, true, look.sunTimeText, lon, lat};
        look.sunAzimuthDeg = std::fmod(sun.azimuthDeg - convergenceDeg + 360, 360);
        look.sunAltitudeDeg = sun.altitudeDeg;
    }

    const auto t0 = Clock::now();
    const geo::GeoGrid& refined = surface->refined;
    const bool heightField = surface->geometry.kind == scene::GeometryKind::HeightField;
    // One of the two geometries: the mesh (a view of the refined grid) or the
    // height field's 16-bit levels.
    std::optional<emit::Mesh> mesh;
    std::optional<emit::HeightField> field;
    emit::ScenePlacement where;
    if (heightField) {
        where = emit::placeTerrain(refined, look);
        field = emit::quantizeHeights(refined, where);
        result.heightPng = options.povPath.parent_path() / emit::siblingPngName(options.povPath, "height");
        result.drapePng = options.povPath.parent_path() / emit::siblingPngName(options.povPath, "drape");
        options.outputs->add(result.heightPng, "the height field's PNG");
        options.outputs->add(result.drapePng, "the height field's drape PNG");
        result.heightStepM = field->stepM();
        result.meshVertices = static_cast<long long>(refined.grid.points.size());
        result.meshTriangles = gridMeshSize(refined.rows(), refined.cols()).triangles;
    } else {
        if (surface->geometry.kind == scene::GeometryKind::Adaptive) {
            // The tolerance in metres: given, or half a pixel (by default) where the terrain is
            // nearest the camera, in true (not exaggerated) metres.
            const scene::GeometrySpec& g = spec.geometry;
            const emit::ScenePlacement placed = emit::placeTerrain(refined, look);
            const double pixelM = emit::finestMetresPerPixel(emit::placeCamera(placed, look, spec.render), placed,
                                                             spec.render.width);
            result.adaptiveToleranceM = g.toleranceM > 0 ? g.toleranceM : g.tolerancePx * pixelM / look.exaggeration;
            result.adaptiveTolerancePx = result.adaptiveToleranceM * look.exaggeration / pixelM;
            mesh = emit::buildAdaptiveMesh(refined, look, result.adaptiveToleranceM);
            const scene::SubdivisionSpec& sub = spec.subdivision;
            if (!subdiv::checkBudget(subdiv::withBuiltMesh(surface->estimate, double(mesh->vertices),
                                                           double(mesh->triangles)),
                                     budgetOf(spec.limits),
                                     sub.locs.at(sub.depthAuto ? "subdivision.depth" : "subdivision.scheme"),
                                     surface->depth, diags, true))
                return std::nullopt;
        } else {
            mesh = emit::buildMesh(refined, look);
        }
        where = *mesh;
        result.meshVertices = static_cast<long long>(mesh->vertices);
        result.meshTriangles = mesh->triangles;
    }
    result.geometry = surface->geometry;
    result.schemeFamily = loaded.resolved.family;
    result.certified = subdiv::certifiedClass(loaded.resolved.report);
    result.arity = loaded.resolved.scheme.arity;
    result.holder = loaded.resolved.report.holder;
    result.metresPerUnit = where.metresPerUnit;
    result.baseFloorM = where.baseElevationM;
    result.zRangeM = {where.zMinM, where.zMaxM};
    {
        annotate::OverlayFacts& f = result.overlayFacts;
        // Whose data: the scene's credit line, else the one the raster's metadata carries.
        result.dataAttribution = !spec.samples.attribution.empty() ? spec.samples.attribution : net.attribution;
        f.credits = spec.overlay.credits ? *spec.overlay.credits : result.dataAttribution;
        // The legend: the ramp over elevation (a blend's first layer, without rock),
        // or the slope palette over degrees.
        f.palette.assign(where.paletteColors.begin(),
                         where.paletteColors.begin() + std::min<size_t>(emit::kPaletteSize, where.paletteColors.size()));
        f.zMinM = where.zMinM;
        f.zMaxM = where.zMaxM;
        using Colouring = scene::LookSpec::Colouring;
        if (look.colouring == Colouring::Image) {
            f.palette.clear();  // an image's colours are its own: no elevation legend
        } else if (look.colouring == Colouring::Slope) {
            f.legendTitle = "Slope (\u00b0)";
            f.zMinM = 0;
            f.zMaxM = emit::kSlopePaletteMaxDeg;
        } else if (look.colouring == Colouring::Blend) {
            f.legendNote = fmt::format("rock on slopes over {}\u00b0", formatShortest(look.rockFromDeg));
        }
        f.exaggeration = where.exaggeration;
        const emit::CameraView view = emit::placeCamera(where, look, spec.render);
        // The eye and the target back in metres (heights unexaggerated), then degrees.
        const auto toFrame = [&](const Vec3& p) {
            return Vec3{p.x * where.metresPerUnit + where.originM.x, p.z * where.metresPerUnit + where.originM.y,
                        p.y * where.metresPerUnit / where.exaggeration};
        };
        const Vec3 eye = toFrame(view.eye), target = toFrame(view.target);
        for (auto [p, out] : {std::pair{eye, &result.cameraEyeLonLatH}, std::pair{target, &result.cameraTargetLonLatH}}) {
            double lat = 0, lon = 0, h = 0;
            if (geo::frameToGeodetic(net.frame, p, lat, lon, h)) *out = {lon, lat, h};
        }
        const Vec3 d = eye - target;
        result.cameraDistanceM = length(d);
        result.cameraAzimuthDeg = std::fmod(std::atan2(d.x, d.y) * 180 / std::numbers::pi + 360, 360);
        result.cameraElevationDeg = std::asin(std::clamp(d.z / std::max(result.cameraDistanceM, 1e-300), -1.0, 1.0)) *
                                    180 / std::numbers::pi;
        f.perspective = view.perspective;
        f.metresPerPixel = annotate::metresPerPixelAtTarget(view, where.metresPerUnit, spec.render.width);
        f.northDeg = annotate::northOnImageDeg(view, geo::gridConvergenceDeg(net.frame, where.originM.x, where.originM.y),
                                               spec.render.width, spec.render.height);
        // Where the terrain lies on the still (points in front of the eye only).
        std::vector<std::array<double, 2>> onImage;
        const Vec3 forward = view.target - view.eye;
        for (const Vec3& p : where.outline)
            if (!view.perspective || dot(p - view.eye, forward) > 0)
                onImage.push_back(emit::projectToImage(view, p, spec.render.width, spec.render.height));
        f.terrain = annotate::TerrainOnImage::fromPoints(onImage, spec.render.width);
    }
    result.depth = surface->depth;
    result.autoDepth = surface->autoDepth;
    result.maskedNodes = refined.maskedCount();
    result.parameters = describe(spec, net, loaded.resolved, surface->depth, result);

    if (!options.dumpNetPath.empty()) {
        const bool asc = options.dumpNetPath.extension() == ".asc";
        if (asc && std::abs(net.dx - net.dy) > 1e-9 * net.dx) {
            diags.error({options.dumpNetPath.string(), 0, 0},
                        fmt::format("an ESRI ASCII grid needs square cells, but the net's "
                                    "spacing is {} x {} m; set net.spacing_m or dump to .csv",
                                    formatShortest(net.dx), formatShortest(net.dy)));
            return std::nullopt;
        }
    }
    if (spec.overlay.contours) {
        constexpr int kMaxContourLevels = 1000;
        if (const int n = emit::contourLevelCount(where, *spec.overlay.contours); n > kMaxContourLevels) {
            diags.error(spec.overlay.locs.at("overlay.contours"),
                        fmt::format("overlay.contours: interval_m = {} m gives {} lines over the surface's {:.0f} m "
                                    "of relief, more than {} a still can show: choose a wider interval",
                                    formatShortest(spec.overlay.contours->intervalM), n, where.zMaxM - where.zMinM,
                                    kMaxContourLevels));
            return std::nullopt;
        }
    }
    // [texture] image: the image resampled onto the refined grid, drawn as a drape PNG.
    std::optional<geo::ImageOnGrid> image;
    if (look.colouring == scene::LookSpec::Colouring::Image) {
        image = geo::imageOnGrid(look.drapeImage, look.drapeImageText, refined, diags);
        if (!image) return std::nullopt;
        result.drapeImageCoverage = double(image->coveredCount) / double(image->covered.size());
        // The image's credit joins the data's (a map's or a photo's licence asks for it too).
        result.imageAttribution = !look.drapeImageAttribution.empty() ? look.drapeImageAttribution : image->attribution;
        if (!spec.overlay.credits && !result.imageAttribution.empty())
            result.overlayFacts.credits += (result.overlayFacts.credits.empty() ? "" : " ") + result.imageAttribution;
        if (!result.imageAttribution.empty())
            result.parameters.emplace_back("texture.image_attribution", result.imageAttribution);
        if (!heightField) {
            result.drapePng = options.povPath.parent_path() / emit::siblingPngName(options.povPath, "drape");
            const std::filesystem::path staged = options.outputs->add(result.drapePng, "the drape PNG");
            if (const std::string pngError = emit::writeDrapePng(emit::imageDrape(refined, where, *image), staged);
                !pngError.empty()) {
                diags.error({}, pngError);
                return std::nullopt;
            }
        }
    }
    emit::GeometryWriter geometry;
    if (heightField) {
        std::string pngError = emit::writeHeightFieldPng(*field, options.outputs->staged(result.heightPng));
        if (pngError.empty())
            pngError = emit::writeDrapePng(image ? emit::imageDrape(refined, where, *image)
                                                 : emit::elevationDrape(refined, where),
                                           options.outputs->staged(result.drapePng));
        if (!pngError.empty()) {
            diags.error({}, pngError);
            return std::nullopt;
        }
        geometry = [&](std::FILE* out) {
            emit::writeHeightFieldSdl(out, *field, refined, where, result.heightPng.filename().string(),
                                      result.drapePng.filename().string());
        };
    } else {
        emit::WriteProgressFn writing;
        if (options.progress)
            writing = [&](double fraction) {
                options.progress({ProgressEvent::Stage::Compiling,
                                  fmt::format("writing {} ({} triangles)", options.povPath.filename().string(),
                                              mesh->triangles),
                                  static_cast<int>(100 * fraction)});
            };
        geometry = [&, writing](std::FILE* out) {
            emit::writeMesh2(*mesh, out, writing);
            if (image) {
                const std::string texture = emit::drapeTextureSdl(refined, where, result.drapePng.filename().string());
                std::fwrite(texture.data(), 1, texture.size(), out);
            }
        };
    }
    emit::GeometryWriter base;
    if (where.baseElevationM) base = [&](std::FILE* out) { emit::writeBlockBase(out, refined, where); };
    // [overlay] contours: built before anything is written, so that lines over
    // the output limits are refused with nothing left behind.
    emit::GeometryWriter contours;
    emit::ContourRibbons ribbons;
    if (spec.overlay.contours && spec.overlay.enabled != scene::OverlaySpec::Enabled::Off) {
        // A line a pixel and a fifth wide at the centre of the view (index lines twice that).
        const double widthM = 1.2 * result.overlayFacts.metresPerPixel;
        std::string contourError;
        ribbons = emit::buildSurfaceContours(refined, where, *spec.overlay.contours, widthM, contourError);
        const SourceLoc at = spec.overlay.locs.at("overlay.contours");
        if (!contourError.empty()) {
            diags.error(at, "overlay.contours: GDAL: " + contourError);
            return std::nullopt;
        }
        const scene::LimitsSpec& limits = spec.limits;
        const double triangles = double(ribbons.faces.size()), mb = ribbons.sdlBytes() / 1e6;
        if (triangles + double(result.meshTriangles) > limits.maxTriangles || mb > limits.maxSdlMB) {
            diags.error(at, fmt::format("overlay.contours: interval_m = {} m draws {} lines of {:.3g} triangles "
                                        "({:.3g} MB of SDL), past limits.max_triangles ({:.3g} with the surface's "
                                        "{:.3g}) or limits.max_sdl_mb ({}): choose a wider interval",
                                        formatShortest(spec.overlay.contours->intervalM), ribbons.made.lines,
                                        triangles, mb, limits.maxTriangles, double(result.meshTriangles),
                                        formatShortest(limits.maxSdlMB)));
            return std::nullopt;
        }
        result.contours = ribbons.made;
        contours = [&](std::FILE* out) { emit::writeSurfaceContours(out, ribbons, *spec.overlay.contours); };
    }
    const std::filesystem::path stagedPov = options.outputs->staged(options.povPath);
    if (!emit::writeScene(stagedPov, *tmpl, where, geometry, base, contours, look, spec.render,
                          result.parameters, diags))
        return std::nullopt;
    if (!options.dumpNetPath.empty())
        writeFileAtomically(options.outputs->staged(options.dumpNetPath), options.dumpNetPath.extension() == ".asc"
                                                                            ? geo::netToAsciiGrid(net)
                                                                            : geo::netToCsv(net));
    result.times.emit = secondsSince(t0);
    std::error_code ec;
    result.povBytes = std::filesystem::file_size(stagedPov, ec);
    result.scene = spec;
    result.scene.look = look;
    result.net = std::move(surface->net);
    return result;
}

namespace {

// Scattered samples gridded onto the net, telling each percent of the gridding
// (what takes long on real data).
std::optional<geo::ControlNet> griddedSamples(const scene::SceneSpec& spec, Diagnostics& diags,
                                              const ProgressFn& progress) {
    // The samples held in memory take several times the file's bytes: a file
    // over a quarter of the memory budget is refused before it is read.
    const double budgetMB = budgetOf(spec.limits).maxMemoryMB;
    const auto maxBytes = static_cast<std::uintmax_t>(budgetMB * 1e6 / 4);
    std::error_code ec;
    if (const auto bytes = std::filesystem::file_size(spec.samples.path, ec); !ec && bytes > maxBytes) {
        diags.error(spec.limits.locs.has("limits.max_memory_mb") ? spec.limits.locs.at("limits.max_memory_mb")
                                                                 : SourceLoc{spec.samples.pathAsWritten, 0, 0},
                    fmt::format("the samples file is {}, more than a quarter of limits.max_memory_mb = {:.0f} "
                                "(the samples in memory take several times the file): thin the samples, give them "
                                "as a raster, or raise the limit",
                                byteSize(bytes), budgetMB));
        return std::nullopt;
    }
    const auto samples = geo::readSamples(spec.samples, diags, maxBytes);
    if (diags.hasErrors()) return std::nullopt;
    // A DEM exported as lon,lat,elev is a lattice in its own CRS: resampled as
    // the raster it is. Tried: the scene's samples.crs, else degrees, Web
    // Mercator and the UTM zone of the samples' first point.
    std::vector<std::string> candidates{spec.samples.crs};
    if (spec.samples.crs.empty()) {
        const auto& s0 = samples.front();
        const int zone = std::clamp(static_cast<int>(std::floor((s0.lonDeg + 180) / 6)) + 1, 1, 60);
        candidates = {"EPSG:4326", "EPSG:3857", fmt::format("EPSG:{}", (s0.latDeg >= 0 ? 32600 : 32700) + zone)};
    }
    for (const auto& crs : candidates) {
        const auto lattice = geo::findLattice(samples, crs);
        if (!lattice) continue;
        const std::string task = fmt::format("resampling the {} x {} lattice of samples in {}", lattice->cols,
                                             lattice->rows, crs);
        return geo::latticeNet(
            *lattice, spec.samples, spec.frame, spec.net, diags,
            [&](double fraction) {
                if (progress) progress({ProgressEvent::Stage::Compiling, task, static_cast<int>(100 * fraction)});
            },
            netBudgetOf(spec.limits));
    }
    if (!spec.samples.crs.empty())
        diags.warning(spec.samples.locs.at("samples.crs"),
                      fmt::format("the {} samples are not one per node of a regular lattice in {}: gridded as "
                                  "scattered samples",
                                  samples.size(), spec.samples.crs));
    const double griddingMB = samples.size() * subdiv::kGriddingBytesPerSample / 1e6;
    if (griddingMB > budgetMB) {
        diags.error(spec.limits.locs.has("limits.max_memory_mb") ? spec.limits.locs.at("limits.max_memory_mb")
                                                                 : SourceLoc{spec.samples.pathAsWritten, 0, 0},
                    fmt::format("gridding {} samples needs about {:.0f} MB of memory (2.2 kB each), more than "
                                "limits.max_memory_mb = {:.0f}: thin the samples, or give them as a raster",
                                samples.size(), griddingMB, budgetMB));
        return std::nullopt;
    }
    geo::GridProgressFn gridding;
    int lastPercent = -1;
    std::mutex reporting;  // GDAL reports from its main thread; a guard costs nothing if not
    const std::string task = fmt::format("gridding {} samples", samples.size());
    if (progress) {
        progress({ProgressEvent::Stage::Compiling, task, -1});  // before GDAL's triangulation, which tells nothing
        gridding = [&](double fraction) {
            const int percent = static_cast<int>(100 * fraction);
            const std::lock_guard<std::mutex> lock(reporting);
            if (percent == lastPercent) return;
            lastPercent = percent;
            progress({ProgressEvent::Stage::Compiling, task, percent});
        };
    }
    return geo::normalize(spec.frame, spec.net, spec.samples.pathAsWritten, samples, diags, gridding,
                          netBudgetOf(spec.limits));
}

}  // namespace

std::optional<Surface> buildSurface(const LoadedScene& loaded, Diagnostics& diags, int threads,
                                    const ProgressFn& progress) {
    const scene::SceneSpec& spec = loaded.scene;
    const scene::SubdivisionSpec& sub = spec.subdivision;
    const subdiv::Scheme& scheme = loaded.resolved.scheme;
    auto t0 = Clock::now();
    std::optional<geo::ControlNet> net;
    if (geo::isRasterDem(spec.samples.path)) {
        net = geo::rasterNet(
            spec.samples, spec.frame, spec.net, diags,
            [&](double fraction) {
                if (progress)
                    progress({ProgressEvent::Stage::Compiling, "resampling the raster", static_cast<int>(100 * fraction)});
            },
            netBudgetOf(spec.limits));
        if (!net) return std::nullopt;
    } else {
        for (const char* key : {"samples.band", "samples.resample", "samples.nodata", "samples.vertical_unit"})
            if (spec.samples.locs.has(key))
                diags.error(spec.samples.locs.at(key),
                            fmt::format("{} is only used with a raster DEM, and GDAL does not read {} as a "
                                        "raster (relief takes it for a CSV of samples): remove it",
                                        key, printableExcerpt(spec.samples.pathAsWritten, 200)));
        if (diags.hasErrors()) return std::nullopt;
        net = griddedSamples(spec, diags, progress);
        if (!net) return std::nullopt;
    }
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
        facts.exaggeration = spec.look.exaggeration;
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
    const bool image = spec.look.colouring == scene::LookSpec::Colouring::Image;
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

namespace {

// The scene's [render] output, else out/<scene stem> with the extension.
std::filesystem::path defaultOutput(const std::filesystem::path& scenePath,
                                    const std::string& sceneOutput, const char* extension) {
    if (!sceneOutput.empty()) return sceneOutput;
    return std::filesystem::path("out") / (scenePath.stem().string() + extension);
}

}  // namespace

namespace {

// The job's outputs, declared before any work is done, so that two of them
// with one name, or an output over an input, are refused at once: the still,
// the .pov, the net dump, the sidecar last (the seal of the set).
void declareOutputs(const SceneJob& job, const LoadedScene& loaded, const OutputPaths& paths, OutputSet& outputs) {
    const bool render = job.until == SceneJob::Until::Png;
    const char* given = job.output.empty() ? nullptr : "-o";
    if (render) outputs.add(paths.png, given ? given : "the still");
    outputs.add(paths.pov, !render && given ? given : "the .pov");
    if (!job.dumpNetPath.empty()) outputs.add(job.dumpNetPath, "--dump-net");
    outputs.add(paths.sidecar, "the sidecar", true);
    const scene::SceneSpec& s = loaded.scene;
    outputs.addInput(job.scenePath, "the scene file");
    outputs.addInput(s.samples.path, "samples.path");
    if (!s.look.drapeImage.empty()) outputs.addInput(s.look.drapeImage, "texture.image");
    if (!s.look.ramp.cptPath.empty()) outputs.addInput(job.scenePath.parent_path() / s.look.ramp.cptPath, "texture.cpt");
}

// POV-Ray renders the staged .pov into the staged still; the overlays are
// drawn on it. False with the reason in `diags` (BadInput) or in
// `outcome.render` (ToolFailed).
bool renderStill(const SceneJob& job, const LoadedScene& loaded, const OutputSet& outputs, JobOutcome& outcome,
                 Diagnostics& diags, const ProgressFn& progress) {
    const CompileResult& compiled = *outcome.compiled;
    const scene::RenderSpec& still = loaded.scene.render;
    const std::filesystem::path png = outputs.staged(outcome.paths.png);
    render::RenderRequest req;
    req.pov = outputs.staged(outcome.paths.pov);
    req.png = png;
    req.width = still.width;
    req.height = still.height;
    req.antialias = still.antialias;
    req.alpha = still.background == scene::Background::Transparent;
    req.templatesDir = job.templatesDir;
    for (const auto& f : {compiled.heightPng, compiled.drapePng})
        if (!f.empty()) req.inputFiles.push_back(outputs.staged(f));
    req.threads = job.threads;
    req.sandbox = job.sandbox;
    req.timeoutSeconds = still.timeoutS;
    outcome.render = render::renderPov(req, [&](const render::RenderProgress& p) {
        if (progress) progress({ProgressEvent::Stage::Rendering, p.text, p.percent});
    });
    if (outcome.render.cannotWriteOutput) {  // not POV-Ray's failure: a full disk, say
        diags.error({}, outcome.render.error);
        return false;
    }
    if (!outcome.render.ok) {
        outcome.status = JobStatus::ToolFailed;
        return false;
    }
    if (!annotate::overlaysWanted(loaded.scene.overlay, still.width)) return true;
    PngImage8 image;
    std::string error = readPng8(png, image);
    annotate::OverlayRecord record;
    if (error.empty()) error = annotate::drawOverlays(image, loaded.scene.overlay, compiled.overlayFacts, &record);
    if (error.empty())
        error = writePngAtomically(png, {image.width, image.height, image.channels, false, image.pixels.data()});
    if (!error.empty()) {
        diags.error({}, "the overlays: " + error);
        return false;
    }
    outcome.overlays = record;
    return true;
}

// The job's outputs, named from the scene and the job.
OutputPaths jobPaths(const SceneJob& job, const LoadedScene& loaded) {
    if (job.until == SceneJob::Until::Png)
        return outputPathsFor(job.output.empty() ? defaultOutput(job.scenePath, loaded.scene.render.output, ".png")
                                                 : job.output);
    // Only compiling: the .pov is the output, and the scene's PNG name does not apply.
    OutputPaths paths;
    paths.pov = job.output.empty() ? defaultOutput(job.scenePath, "", ".pov") : job.output;
    paths.sidecar = paths.pov;
    paths.sidecar.replace_extension(".json");
    return paths;
}

JobOutcome runStagedJob(const SceneJob& job, Diagnostics& diags, const ProgressFn& progress, OutputSet& outputs) {
    JobOutcome outcome;
    if (progress) progress({ProgressEvent::Stage::Reading, "reading " + job.scenePath.string(), -1});
    auto loaded = loadScene(job.scenePath, diags, job.overrides);
    if (!loaded) return outcome;
    outcome.paths = jobPaths(job, *loaded);
    // The scene's own output name stays in the current folder, links resolved too.
    if (job.output.empty() && !loaded->scene.render.output.empty() && job.until == SceneJob::Until::Png &&
        !pathInside(loaded->scene.render.output, ".")) {
        diags.error(loaded->scene.render.locs.at("render.output"),
                    fmt::format("render.output = \"{}\" leads out of the current folder through a link; give -o "
                                "to write there",
                                printableExcerpt(loaded->scene.render.output, 200)));
        return outcome;
    }
    declareOutputs(job, *loaded, outcome.paths, outputs);
    CompileOptions copts;
    copts.povPath = outcome.paths.pov;
    copts.outputs = &outputs;
    copts.templatesDir = job.templatesDir;
    copts.dumpNetPath = job.dumpNetPath;
    copts.threads = job.threads;
    copts.progress = progress;
    if (progress)
        progress({ProgressEvent::Stage::Compiling,
                  fmt::format("compiling {} ({}, {})", job.scenePath.string(), loaded->resolved.family,
                              depthLabel(loaded->scene.subdivision)),
                  -1});
    outcome.compiled = compileScene(*loaded, copts, diags);
    if (!outcome.compiled) return outcome;
    const bool render = job.until == SceneJob::Until::Png;
    if (render && !renderStill(job, *loaded, outputs, outcome, diags, progress)) return outcome;
    writeFileAtomically(outputs.staged(outcome.paths.sidecar),
                        sidecarJson(*outcome.compiled, outcome.paths, render ? &outcome.render : nullptr,
                                    outcome.overlays));
    if (job.stillOnly)
        for (const auto& f : {outcome.paths.pov, outcome.paths.sidecar, outcome.compiled->heightPng,
                              outcome.compiled->drapePng, job.dumpNetPath})
            if (!f.empty()) outputs.drop(f);
    outcome.status = JobStatus::Ok;
    return outcome;
}

}  // namespace

JobOutcome runSceneJob(const SceneJob& job, Diagnostics& diags, const ProgressFn& progress) {
    // An output that cannot be made or written (a full disk, a name given
    // twice) is bad input like any other, with nothing left behind.
    try {
        OutputSet own;
        OutputSet& outputs = job.outputs ? *job.outputs : own;
        JobOutcome outcome = runStagedJob(job, diags, progress, outputs);
        if (outcome.status == JobStatus::Ok && !job.outputs) own.commit();
        return outcome;
    } catch (const std::runtime_error& e) {
        diags.error({}, e.what());
        return JobOutcome{};
    }
}

std::string sidecarJson(const CompileResult& c, const OutputPaths& paths,
                        const render::RenderResult* render,
                        const std::optional<annotate::OverlayRecord>& overlays) {
    using nlohmann::ordered_json;
    ordered_json j;
    j["relief_version"] = kVersion;
    j["inputs"] = {{"scene", c.scene.sceneFile.string()},
                   {"scene_sha1", c.scene.sceneSha1},
                   {"samples", c.scene.samples.path.string()},
                   {"sample_count", c.net.sampleCount}};
    if (!c.dataAttribution.empty()) j["inputs"]["attribution"] = c.dataAttribution;
    ordered_json params = ordered_json::object();
    for (const auto& [k, v] : c.parameters) params[k] = v;
    j["parameters"] = params;
    j["net"] = {{"rows", c.net.grid.rows},
                {"cols", c.net.grid.cols},
                {"dx_m", c.net.dx},
                {"dy_m", c.net.dy},
                {"frame", c.net.frame.describe()},
                {"filled_outside_hull", c.net.filledOutsideHull},
                {"filled_nodata", c.net.filledNodata},
                {"masked_nodata", c.net.maskedCount()}};
    j["refined"] = {{"rows", c.estimate.rows},
                    {"cols", c.estimate.cols},
                    {"masked_nodata", c.maskedNodes},
                    {"vertices", c.meshVertices},
                    {"triangles", c.meshTriangles},
                    {"pov_bytes", c.povBytes},
                    {"memory_estimate_mb", c.estimate.memoryBytes / 1e6}};
    ordered_json times = {{"read_scene", c.times.readScene},
                          {"normalize", c.times.normalize},
                          {"subdivide", c.times.subdivide},
                          {"emit", c.times.emit}};
    if (render) {
        times["povray_parse"] = render->parseSeconds;
        times["povray_trace"] = render->traceSeconds;
        times["povray_wall"] = render->wallSeconds;
        j["povray_command"] = render->command;
    }
    if (c.autoDepth) {
        ordered_json levels = ordered_json::array();
        const int arity = c.arity;
        for (size_t i = 0; i < c.autoDepth->levels.size(); ++i) {
            const auto& l = c.autoDepth->levels[i];
            ordered_json level = {{"level", l.level},
                                  {"hausdorff_m", l.distanceM},
                                  {"curve", l.curve},
                                  {"where_m", {l.x, l.y, l.z}},
                                  {"seconds", l.seconds}};
            const double rate = measure::observedRate(*c.autoDepth, i, arity);
            if (std::isfinite(rate)) level["rate"] = rate;
            levels.push_back(level);
        }
        j["auto_depth"] = {{"tolerance_m", c.scene.subdivision.toleranceM},
                           {"depth", c.depth},
                           {"holder_estimate", c.holder},
                           {"levels", levels}};
    }
    if (c.contours.levels > 0)
        j["contours"] = {{"interval_m", c.scene.overlay.contours->intervalM},
                         {"levels", c.contours.levels},
                         {"lines", c.contours.lines}};
    if (c.baseFloorM)
        j["base"] = {{"floor_elevation_m", *c.baseFloorM}, {"thickness_m", c.zRangeM[0] - *c.baseFloorM}};
    j["sun"] = {{"azimuth_deg", c.sun.azimuthDeg},
                {"altitude_deg", c.sun.altitudeDeg},
                {"from", c.sun.fromDatetime ? "datetime" : "scene"}};
    j["sun"]["azimuth_is"] = c.sun.fromDatetime ? "true bearing" : "bearing on the frame's grid, as given";
    if (c.sun.fromDatetime) {
        j["sun"]["datetime"] = c.sun.datetime;
        j["sun"]["at_lonlat"] = {c.sun.lonDeg, c.sun.latDeg};
    }
    j["camera"] = {{"eye_lonlat_h", c.cameraEyeLonLatH},
                   {"look_at_lonlat_h", c.cameraTargetLonLatH},
                   {"azimuth_deg", c.cameraAzimuthDeg},
                   {"elevation_deg", c.cameraElevationDeg},
                   {"distance_m", c.cameraDistanceM},
                   {"placed_by", c.scene.look.camera.position ? "position" : "orbit"}};
    j["seconds"] = times;
    j["geometry"] = {{"kind", emit::geometryKindName(c.geometry.kind)}, {"reason", c.geometry.reason}};
    if (!c.heightPng.empty()) j["geometry"]["height_step_m"] = c.heightStepM;
    if (c.geometry.kind == scene::GeometryKind::Adaptive) {
        j["geometry"]["tolerance_m"] = c.adaptiveToleranceM;
        j["geometry"]["tolerance_px"] = c.adaptiveTolerancePx;
    }
    j["geometry"]["triangles"] = c.meshTriangles;
    j["outputs"] = {{"pov", paths.pov.string()}};
    if (!c.heightPng.empty()) j["outputs"]["height_png"] = c.heightPng.string();
    if (!c.drapePng.empty()) j["outputs"]["drape_png"] = c.drapePng.string();
    if (c.drapeImageCoverage)
        j["texture"] = {{"image", c.scene.look.drapeImageText},
                        {"image_covers", *c.drapeImageCoverage},
                        {"image_attribution", c.imageAttribution}};
    if (render) j["outputs"]["png"] = paths.png.string();
    if (overlays) {
        j["overlay"] = {{"drawn", overlays->drawn}};
        if (overlays->scaleBar.pixels > 0)
            j["overlay"]["scale_bar"] = {{"metres", overlays->scaleBar.metres},
                                         {"pixels", overlays->scaleBar.pixels},
                                         {"valid", c.overlayFacts.perspective ? "at the centre of the view" : "everywhere"}};
        j["overlay"]["north_deg_clockwise_from_up"] = overlays->northDeg;
        j["overlay"]["placement"] = overlays->placement;
        j["overlay"]["on_terrain"] = overlays->onTerrain;
    }
    return j.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n";
}

}  // namespace relief
