// compileScene: the stages from the surface to the .pov, each called once
// and each handing the next a value: the view (placement, camera, sun), the
// terrain's geometry, the contours, the overlays' facts, the .pov.
#include <cmath>
#include <numbers>

#include <fmt/format.h>

#include "core/atomic_file.h"
#include "core/date_time.h"
#include "core/number_format.h"
#include "core/stopwatch.h"
#include "core/text_escape.h"
#include "emit/adaptive_mesh.h"
#include "emit/sky_light.h"
#include "emit/block_base.h"
#include "emit/height_field.h"
#include "emit/mesh.h"
#include "emit/surface_contours.h"
#include "geo/raster.h"
#include "geo/sun_position.h"
#include "pipeline/compile.h"
#include "pipeline/marks.h"
#include "pipeline/record.h"
#include "pipeline/surface.h"
#include "pipeline/view.h"

namespace relief {

namespace {

// The terrain's geometry: a mesh (a view of the refined grid), the adaptive
// mesh, or a height field's 16-bit levels, and the image draped on it.
struct Terrain {
    std::optional<emit::Mesh> mesh;
    std::optional<emit::HeightField> field;
    std::optional<geo::ImageOnGrid> image;
    std::filesystem::path heightPng, drapePng;  ///< final names ("" when none)
    long long vertices = 0, triangles = 0;
    double heightStepM = 0, adaptiveToleranceM = 0, adaptiveTolerancePx = 0;
};

bool buildMeshes(const LoadedScene& loaded, const Surface& surface, const View& view, Terrain& t, Diagnostics& diags) {
    const scene::SceneSpec& spec = loaded.scene;
    const geo::GeoGrid& refined = surface.refined;
    if (surface.geometry.kind == scene::GeometryKind::HeightField) {
        t.field = emit::quantizeHeights(refined, view.where);
        t.heightStepM = t.field->stepM();
        t.vertices = static_cast<long long>(refined.grid.points.size());
        t.triangles = gridMeshSize(refined.rows(), refined.cols()).triangles;
        return true;
    }
    if (surface.geometry.kind != scene::GeometryKind::Adaptive) {
        t.mesh = emit::buildMesh(refined, view.where);
    } else {
        // The tolerance in metres: given, or a tenth of a pixel (by default) in true (not exaggerated)
        // metres, where the terrain is nearest the camera and, in a perspective view, as many
        // times more as a pixel's footprint is wider elsewhere (emit::PixelTolerance).
        const scene::GeometrySpec& g = spec.geometry;
        const double pixelM = emit::finestMetresPerPixel(view.camera, view.where, spec.render.width);
        const double exaggeration = spec.look.vertical.exaggeration;
        t.adaptiveToleranceM = g.toleranceM > 0 ? g.toleranceM : g.tolerancePx * pixelM / exaggeration;
        t.adaptiveTolerancePx = t.adaptiveToleranceM * exaggeration / pixelM;
        const emit::PixelTolerance perPixel{&view.camera, spec.render.width, spec.render.height};
        t.mesh = emit::buildAdaptiveMesh(refined, view.where, t.adaptiveToleranceM, g.toleranceM > 0 ? nullptr : &perPixel);
        if (!subdiv::checkBudget(
                subdiv::withBuiltMesh(surface.estimate, double(t.mesh->vertices), double(t.mesh->triangles)),
                loaded.budget, budgetKey(spec), surface.depth, diags, true))
            return false;
    }
    emit::nodeTextures(*t.mesh);
    t.vertices = static_cast<long long>(t.mesh->vertices);
    t.triangles = t.mesh->triangles;
    return true;
}

// The PNGs the .pov reads: a height field's levels and drape, an image drape.
bool writeTerrainPngs(const scene::SceneSpec& spec, const Surface& surface, const View& view,
                      const CompileOptions& options, Terrain& t, Diagnostics& diags) {
    const geo::GeoGrid& refined = surface.refined;
    const std::filesystem::path& pov = options.povPath;
    if (spec.look.texture.colouring == scene::TextureSpec::Colouring::Image) {
        t.image = geo::imageOnGrid(spec.look.texture.drapeImage, spec.look.texture.drapeImageText, refined, diags);
        if (!t.image) return false;
    }
    try {
        if (t.field) {
            t.heightPng = pov.parent_path() / emit::siblingPngName(pov, "height");
            emit::writeHeightFieldPng(*t.field, options.writeAt(t.heightPng, "the height field's PNG"));
        }
        if (t.field || t.image) {
            t.drapePng = pov.parent_path() / emit::siblingPngName(pov, "drape");
            const auto at = options.writeAt(t.drapePng, t.field ? "the height field's drape PNG" : "the drape PNG");
            emit::writeDrapePng(
                t.image ? emit::imageDrape(refined, view.where, *t.image) : emit::elevationDrape(refined, view.where),
                at);
        }
    } catch (const OutputError& e) {
        diags.error(e.at(), e.problem());
        return false;
    }
    return true;
}

// [overlay] contours, built before anything is written, so that lines over
// the output limits are refused with nothing left behind.
std::optional<emit::ContourRibbons> buildContours(const scene::SceneSpec& spec, const subdiv::Budget& budget,
                                                  const Surface& surface, const View& view, double metresPerPixel,
                                                  long long meshTriangles, Diagnostics& diags) {
    if (!spec.overlay.contours) return emit::ContourRibbons{};
    const SourceLoc at = spec.overlay.locs.at("overlay.contours");
    constexpr int kMaxContourLevels = 1000;
    if (const int n = emit::contourLevelCount(view.where, *spec.overlay.contours); n > kMaxContourLevels) {
        diags.error(at, fmt::format("overlay.contours: interval_m = {} m gives {} lines over the surface's {:.0f} m "
                                    "of relief, more than {} a still can show: choose a wider interval",
                                    formatShortest(spec.overlay.contours->intervalM), n,
                                    view.where.zMaxM - view.where.zMinM, kMaxContourLevels));
        return std::nullopt;
    }
    if (spec.overlay.enabled == scene::OverlaySpec::Enabled::Off) return emit::ContourRibbons{};
    // A line a pixel and a fifth wide at the centre of the view (index lines twice that).
    auto built =
        emit::buildSurfaceContours(surface.refined, view.where, *spec.overlay.contours, 1.2 * metresPerPixel, at, diags);
    if (!built) return std::nullopt;
    emit::ContourRibbons ribbons = std::move(*built);
    // The lines' triangles join the surface's in POV-Ray's parse; their SDL is the .pov's beside the surface's.
    const auto withLines =
        subdiv::linesOnSurface(double(ribbons.ribbons.faces.size()), ribbons.ribbons.sdlBytes(), meshTriangles);
    if (const std::string over = subdiv::overBudget(withLines, budget); !over.empty()) {
        const std::string beside = meshTriangles > 0 ? fmt::format(" beside the surface's {}", meshTriangles) : "";
        diags.error(at, fmt::format("overlay.contours: interval_m = {} m draws {} lines of {} triangles{}: {}; choose "
                                    "a wider interval, or raise [limits]",
                                    formatShortest(spec.overlay.contours->intervalM), ribbons.made.lines,
                                    ribbons.ribbons.faces.size(), beside, over));
        return std::nullopt;
    }
    return ribbons;
}

// What the overlays say, the camera both ways and where the terrain sits, from the view.
ViewSummary describeView(const scene::SceneSpec& spec, const geo::ControlNet& net, const View& view,
                         const std::string& credits) {
    const emit::ScenePlacement& where = view.where;
    const emit::CameraView& camera = view.camera;
    ViewSummary v;
    v.sun = view.sunRecord;
    v.metresPerUnit = where.metresPerUnit;
    v.baseFloorM = where.baseElevationM;
    v.zRangeM = {where.zMinM, where.zMaxM};
    v.overlayFacts = annotate::overlayFacts(spec.look, where, camera, spec.render,
                                            geo::gridConvergenceDeg(net.frame, where.originM.x, where.originM.y));
    v.overlayFacts.credits = spec.overlay.credits ? *spec.overlay.credits : credits;
    if (view.frameTicks)
        v.overlayFacts.mapFrame =
            mapFrameOnImage(*view.frameTicks, where, camera, spec.render.width, spec.render.height);
    v.widthPx = spec.render.width;
    v.heightPx = spec.render.height;
    // The eye and the target back in metres (heights unexaggerated), then degrees.
    const Vec3 eye = where.unexaggerated(camera.eye), target = where.unexaggerated(camera.target);
    for (auto [p, out] : {std::pair{eye, &v.cameraEye}, std::pair{target, &v.cameraTarget}})
        if (auto g = geo::reverse(net.frame, p)) *out = *g;
    const Vec3 d = eye - target;
    v.cameraDistanceM = length(d);
    v.cameraAzimuthDeg = std::fmod(std::atan2(d.x, d.y) * 180 / std::numbers::pi + 360, 360);
    v.cameraElevationDeg =
        std::asin(std::clamp(d.z / std::max(v.cameraDistanceM, 1e-300), -1.0, 1.0)) * 180 / std::numbers::pi;
    return v;
}

// The image's credit joins the data's (a map's or a photo's licence asks for it too).
void creditImage(const scene::SceneSpec& spec, const Terrain& t, CompileResult& r) {
    if (!t.image) return;
    r.terrain.drapeImageCoverage = double(t.image->coveredCount) / double(t.image->covered.size());
    r.credits.image = !spec.look.texture.drapeImageAttribution.empty() ? spec.look.texture.drapeImageAttribution
                                                                       : t.image->attribution;
    annotate::OverlayFacts& f = r.view.overlayFacts;
    if (!spec.overlay.credits && !r.credits.image.empty())
        f.credits += (f.credits.empty() ? "" : " ") + r.credits.image;
    if (!r.credits.image.empty()) r.parameters.emplace_back("texture.image_attribution", r.credits.image);
}

// The writers the template's placeholders call: terrain, block model, what lies on the surface.
emit::GeometryWriters writersOf(const Surface& surface, const View& view, const Terrain& t,
                                const emit::ContourRibbons& ribbons, const SurfaceMarks& marks,
                                const scene::SceneSpec& spec, const CompileOptions& options) {
    const geo::GeoGrid& refined = surface.refined;
    emit::GeometryWriters w;
    if (t.field) {
        w.terrain = [&](std::FILE* out) {
            emit::writeHeightFieldSdl(out, *t.field, refined, view.where, t.heightPng.filename().string(),
                                      t.drapePng.filename().string());
        };
    } else {
        emit::WriteProgressFn writing;
        if (options.progress)
            writing = [&](double fraction) {
                options.progress({ProgressEvent::Stage::Compiling,
                                  fmt::format("writing {} ({} triangles)", options.povPath.filename().string(),
                                              t.mesh->triangles),
                                  static_cast<int>(100 * fraction)});
            };
        w.terrain = [&, writing](std::FILE* out) {
            emit::writeMesh2(*t.mesh, out, writing);
            if (!t.image) return;
            const std::string texture = emit::drapeTextureSdl(refined, view.where, t.drapePng.filename().string());
            std::fwrite(texture.data(), 1, texture.size(), out);
        };
    }
    if (view.where.baseElevationM) w.base = [&](std::FILE* out) { emit::writeBlockBase(out, refined, view.where); };
    if (!ribbons.ribbons.faces.empty() || !marks.empty())
        w.onSurface = [&](std::FILE* out) {
            if (!ribbons.ribbons.faces.empty()) emit::writeSurfaceContours(out, ribbons, *spec.overlay.contours);
            writeSurfaceMarks(out, marks, spec, view.where, view.camera);
        };
    return w;
}

bool dumpNetFits(const CompileOptions& options, const geo::ControlNet& net, Diagnostics& diags) {
    const bool asc = options.dumpNetPath.extension() == ".asc" || options.dumpSurfacePath.extension() == ".asc";
    if (!asc) return true;
    if (std::abs(net.dx - net.dy) <= 1e-9 * net.dx) return true;
    diags.error({(options.dumpNetPath.extension() == ".asc" ? options.dumpNetPath : options.dumpSurfacePath).string(), 0, 0},
                fmt::format("an ESRI ASCII grid needs square cells, but the net's spacing is {} x {} m; set "
                            "net.spacing_m or dump to .csv",
                            formatShortest(net.dx), formatShortest(net.dy)));
    return false;
}

// The net as the record describes it.
NetSummary summaryOf(const geo::ControlNet& net) {
    return {net.grid.rows,      net.grid.cols,      net.dx,           net.dy,          net.frame.describe(),
            net.spacingReason,  net.sampleCount,    net.filledOutsideHull, net.filledNodata, net.maskedCount()};
}

// What the surface was, for the header and the sidecar.
SurfaceSummary summaryOf(const LoadedScene& loaded, const Surface& surface) {
    SurfaceSummary s;
    s.net = summaryOf(surface.net);
    s.schemeFamily = loaded.resolved.family;
    s.certified = subdiv::certifiedClass(loaded.resolved.report);
    s.arity = loaded.resolved.scheme.arity;
    s.holder = loaded.resolved.report.holder;
    s.depth = surface.depth;
    s.depthReason = surface.depthReason;
    s.autoDepth = surface.autoDepth;
    s.estimate = surface.estimate;
    s.geometry = surface.geometry;
    s.maskedNodes = surface.refined.maskedCount();
    s.fit = surface.fit;
    s.prefilter = surface.prefilter;
    s.peakLoss = surface.peakLoss;
    return s;
}

// What the geometry became.
TerrainSummary summaryOf(const Terrain& t, const emit::SurfaceContours& contours) {
    TerrainSummary s;
    s.heightPng = t.heightPng;
    s.drapePng = t.drapePng;
    s.heightStepM = t.heightStepM;
    s.adaptiveToleranceM = t.adaptiveToleranceM;
    s.adaptiveTolerancePx = t.adaptiveTolerancePx;
    s.meshVertices = t.vertices;
    s.meshTriangles = t.triangles;
    s.contours = contours;
    return s;
}

// The SDL files a film's frames include in place of the geometry: written
// once by the writers a still's .pov calls, each frame's .pov naming them.
struct SdlFiles {
    std::filesystem::path terrain, base, onSurface;  ///< final names ("" when none)
};

SdlFiles writeSdlFiles(const emit::GeometryWriters& writers, const CompileOptions& options) {
    SdlFiles files;
    const std::filesystem::path& pov = options.povPath;
    const auto write = [&](const emit::GeometryWriter& writer, const char* name, std::string_view role) {
        if (!writer) return std::filesystem::path();
        const std::filesystem::path final = pov.parent_path() / name;
        AtomicFile file(options.writeAt(final, role));
        writer(file.stream());
        file.commit();
        return final;
    };
    files.terrain = write(writers.terrain, "terrain.inc", "the terrain's SDL");
    files.base = write(writers.base, "base.inc", "the block's SDL");
    files.onSurface = write(writers.onSurface, "on_surface.inc", "the SDL of the lines on the surface");
    return files;
}

emit::GeometryWriters includesOf(const SdlFiles& files) {
    const auto include = [](const std::filesystem::path& file) -> emit::GeometryWriter {
        if (file.empty()) return {};
        return
            [name = file.filename().string()](std::FILE* out) { std::fprintf(out, "#include \"%s\"\n", name.c_str()); };
    };
    return {include(files.terrain), include(files.base), include(files.onSurface)};
}

}  // namespace

DataCredit dataCredit(const scene::SamplesSpec& samples, const geo::ControlNet& net) {
    if (!samples.attribution.empty()) return {samples.attribution, false};
    return {net.attribution, !net.attribution.empty()};
}

// Everything compiled but the view: the surface, the view it was fitted to
// (the adaptive mesh's tolerance, the contours' width), the geometry and the
// files it needs. Built in place: the meshes and writers refer into it.
struct SharedTerrain::State {
    LoadedScene loaded;
    emit::Template tmpl;
    Surface surface;
    View view;
    Terrain terrain;
    emit::ContourRibbons ribbons;
    SurfaceMarks marks;
    bool inFiles = false;  ///< the geometry is in SDL files the frames include
    SdlFiles sdl;
    double seconds = 0;  ///< emitting the terrain
};

SharedTerrain::SharedTerrain(std::unique_ptr<State> state) : state_(std::move(state)) {}
SharedTerrain::SharedTerrain(SharedTerrain&&) noexcept = default;
SharedTerrain::~SharedTerrain() = default;
const geo::ControlNet& SharedTerrain::net() const {
    return state_->surface.net;
}
const geo::GeoGrid& SharedTerrain::refined() const {
    return state_->surface.refined;
}
int SharedTerrain::depth() const {
    return state_->surface.depth;
}
const emit::ScenePlacement& SharedTerrain::placement() const {
    return state_->view.where;
}

namespace {

std::unique_ptr<SharedTerrain::State> compileTerrain(const LoadedScene& loaded, const CompileOptions& options,
                                                     bool inFiles, Diagnostics& diags) {
    const scene::SceneSpec& spec = loaded.scene;
    auto st = std::make_unique<SharedTerrain::State>();
    st->loaded = loaded;
    st->inFiles = inFiles;
    auto tmpl = emit::loadSceneTemplate(options.templatesDir, diags);
    if (!tmpl) return nullptr;
    st->tmpl = std::move(*tmpl);
    auto surface = buildSurface(loaded, diags, options.threads, options.progress);
    if (!surface) return nullptr;
    st->surface = std::move(*surface);
    auto view = resolveView(spec, st->surface.net, st->surface.refined, diags);
    if (!view) return nullptr;
    st->view = std::move(*view);
    const auto t0 = Clock::now();
    if (scene::qualityLevel(spec.render.quality).skyLight)
        emit::addSkyLight(st->view.where, st->surface.refined, {.threads = options.threads});
    const double metresPerPixel = st->view.metresPerPixel;  // the width of the contour lines and the layers' lines
    auto marks = buildSurfaceMarks(spec, st->surface.refined, st->view.where, metresPerPixel, diags);
    if (!marks) return nullptr;
    st->marks = std::move(*marks);
    st->view.where.fills = st->marks.layers.fills;  // the polygons' tints, in every geometry's colours
    st->view.where.fade = unsupportedFadeOf(st->surface);
    if (!buildMeshes(st->loaded, st->surface, st->view, st->terrain, diags)) return nullptr;
    const long long parsedTriangles =
        st->terrain.field ? 0 : st->terrain.triangles;  // a height field's are POV-Ray's own
    auto ribbons = buildContours(spec, loaded.budget, st->surface, st->view, metresPerPixel, parsedTriangles, diags);
    if (!ribbons ||
        !surfaceMarksWithinLimits(st->marks, spec, loaded.budget,
                                  parsedTriangles + static_cast<long long>(ribbons->ribbons.faces.size()), diags) ||
        !dumpNetFits(options, st->surface.net, diags) ||
        !writeTerrainPngs(spec, st->surface, st->view, options, st->terrain, diags))
        return nullptr;
    st->ribbons = std::move(*ribbons);
    if (inFiles)
        st->sdl = writeSdlFiles(
            writersOf(st->surface, st->view, st->terrain, st->ribbons, st->marks, spec, options), options);
    st->seconds = secondsSince(t0);
    return st;
}

}  // namespace

std::optional<CompileResult> compileView(const LoadedScene& frame, const SharedTerrain& shared,
                                         const CompileOptions& options, Diagnostics& diags) {
    const SharedTerrain::State& st = *shared.state_;
    const scene::SceneSpec& spec = frame.scene;
    std::optional<View> own;  // a frame's own camera and sun; a still's are the terrain's
    if (st.inFiles && !(own = resolveView(spec, st.surface.net, st.surface.refined, diags))) return std::nullopt;
    const View& view = own ? *own : st.view;
    const auto t0 = Clock::now();
    CompileResult r;
    r.seconds = {frame.seconds, st.surface.normalizeSeconds, st.surface.subdivideSeconds, 0};
    r.credits.data = dataCredit(spec.samples, st.surface.net).text;
    r.view = describeView(spec, st.surface.net, view, r.credits.data);
    r.surface = summaryOf(st.loaded, st.surface);
    r.terrain = summaryOf(st.terrain, st.ribbons.made);
    r.terrain.layers =
        describeSurfaceMarks(st.marks, spec, st.surface.refined, view.where, view.camera, r.view.overlayFacts);
    r.parameters = sceneHeader(spec, st.surface.net, st.loaded.resolved, r);
    creditImage(spec, st.terrain, r);

    const std::filesystem::path pov = options.writeAt(options.povPath, "the .pov");
    const emit::GeometryWriters writers =
        st.inFiles ? includesOf(st.sdl) : writersOf(st.surface, view, st.terrain, st.ribbons, st.marks, spec, options);
    if (!emit::writeScene(pov, st.tmpl, view.where, view.camera, view.sun, writers, spec.look, spec.render,
                          r.parameters, diags))
        return std::nullopt;
    r.seconds.emit = st.seconds + secondsSince(t0);
    std::error_code ec;
    r.povBytes = std::filesystem::file_size(pov, ec);
    warnIfSidecarNotUtf8(spec, r, options.povPath, diags);
    return r;
}

std::optional<SharedTerrain> compileSharedTerrain(const LoadedScene& loaded, const CompileOptions& options,
                                                  Diagnostics& diags) {
    try {
        auto st = compileTerrain(loaded, options, true, diags);
        if (!st) return std::nullopt;
        return SharedTerrain(std::move(st));
    } catch (const OutputError& e) {
        diags.error(e.at(), e.problem());
        return std::nullopt;
    }
}

std::optional<CompileResult> compileScene(const LoadedScene& loaded, const CompileOptions& options,
                                          Diagnostics& diags) {
    auto st = compileTerrain(loaded, options, false, diags);
    if (!st) return std::nullopt;
    const SharedTerrain shared(std::move(st));
    auto r = compileView(loaded, shared, options, diags);
    if (!r) return std::nullopt;
    const auto dump = [&](const std::filesystem::path& path, const geo::GeoGrid& grid, std::string_view role) {
        if (path.empty()) return;
        writeFileAtomically(options.writeAt(path, role),
                            path.extension() == ".asc" ? geo::netToAsciiGrid(grid) : geo::netToCsv(grid));
    };
    dump(options.dumpNetPath, shared.net(), "--dump-net");
    dump(options.dumpSurfacePath, shared.refined(), "--dump-surface");
    return r;
}

}  // namespace relief
