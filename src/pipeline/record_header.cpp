// The .pov's header (and the sidecar's "parameters"): every input and choice
// that made the scene, as key and value, one line each.
#include "pipeline/record.h"

#include <fmt/format.h>

#include "core/number_format.h"
#include "core/text_escape.h"
#include "emit/geometry_kind.h"
#include "scene/enum_names.h"
#include "relief/version.h"

namespace relief {

namespace {

// A header being written: a key and its value a line.
struct Header {
    emit::ParameterList lines;
    void add(std::string key, std::string value) { lines.emplace_back(std::move(key), std::move(value)); }
};

// Where the scene came from, and the samples, frame and net it read.
void addData(Header& h, const scene::SceneSpec& s, const geo::ControlNet& net) {
    h.add("relief", kVersion);
    h.add("scene", s.sceneFile.string());
    h.add("scene_sha1", s.sceneSha1);
    for (const auto& [k, v] : s.overrides) h.add("override " + k, v);
    h.add("samples.path", s.samples.pathAsWritten);
    if (const DataCredit credit = dataCredit(s.samples, net); !credit.text.empty())
        h.add("samples.attribution", credit.text + (credit.fromMetadata ? " (from the raster's metadata)" : ""));
    h.add("samples.count", std::to_string(net.sampleCount));
    h.add("frame", net.frame.describe());
    h.add("net.size", fmt::format("{} rows x {} cols", net.grid.rows, net.grid.cols));
    h.add("net.spacing_m", fmt::format("{} x {}", formatShortest(net.dx), formatShortest(net.dy)));
    if (net.spacingReason.starts_with("about")) h.add("net.spacing_reason", net.spacingReason);
    h.add("net.origin_m", fmt::format("{}, {}", formatShortest(net.x0), formatShortest(net.y0)));
    if (net.raster.empty())
        h.add("net.gridding", scene::nameOf(s.net.gridding));
    else
        h.add("samples.raster", net.raster);
    if (net.filledNodata > 0)
        h.add("net.filled_nodata", std::to_string(net.filledNodata));
    else if (!net.masked.empty())
        h.add("net.masked_nodata", std::to_string(net.maskedCount()));
    else
        h.add("net.filled_outside_hull", std::to_string(net.filledOutsideHull));
    h.add("vertical.exaggeration", formatShortest(s.look.vertical.exaggeration));
}

// What made the net fit the scheme's surface, and how much of the data's peak the surface keeps.
void addFit(Header& h, const SurfaceSummary& c) {
    if (c.fit)
        h.add("net.fit", fmt::format("{} samples fitted at depth {}: RMSE {:.3g} m, largest residual {:.3g} m, "
                                     "smoothing {:.3g} ({}), tension {:.3g} ({}), {} of {} nodes constrained, data "
                                     "within {:.3g} m of every node, {:.1f} % of the net farther than {:.3g} m from any "
                                     "sample (net.unsupported = {})",
                                     c.fit->samples, c.fit->depth, c.fit->rmseM, c.fit->maxResidualM,
                                     c.fit->smoothing, c.fit->chosenBy, c.fit->tension, c.fit->tensionChosenBy,
                                     c.fit->nodesConstrained, c.fit->nodes,
                                     c.fit->dataReachM, 100 * c.fit->unsupportedShare, c.fit->unsupportedBeyondM,
                                     scene::nameOf(c.fit->unsupportedAs)));
    if (c.prefilter)
        h.add("net.fit", fmt::format("prefiltered at depth {}: the surface through the net's values, the largest "
                                     "change {:.3g} m, gain {:.3g}",
                                     c.prefilter->depth, c.prefilter->largestChangeM, c.prefilter->gain));
    h.add("peak_loss_m", fmt::format("{:.3f} (the data's highest point {:.2f} m, the surface's near it {:.2f} m)",
                                     c.peakLoss.lossM, c.peakLoss.peak.z, c.peakLoss.surfaceHighest.z));
}

// The scheme, its certificate and the depth, and the refined grid.
void addSubdivision(Header& h, const scene::SubdivisionSpec& sub, const subdiv::ResolvedScheme& scheme,
                    const SurfaceSummary& surface) {
    const int depth = surface.depth;
    std::string params;
    for (const auto& [k, v] : scheme.params)
        params += fmt::format("{}{} = {}", params.empty() ? "" : ", ", k, formatShortest(v));
    if (scheme.family == "mask")
        for (double v : sub.scheme.mask) params += fmt::format("{}{}", params.empty() ? "mask " : ", ", formatShortest(v));
    h.add("subdivision.scheme", scheme.family);
    if (!sub.scheme.preset.empty()) h.add("subdivision.preset", sub.scheme.preset);
    h.add("subdivision.params", params);
    h.add("subdivision.certified", subdiv::certifiedClass(scheme.report));
    h.add("subdivision.boundary", "point reflection");
    h.add("subdivision.depth", sub.depthAuto
                                   ? fmt::format("{} (auto, tolerance_m = {})", depth, formatShortest(sub.toleranceM))
                               : sub.depthGiven ? std::to_string(depth)
                                                : fmt::format("{} ({})", depth, surface.depthReason));
    const subdiv::OutputEstimate& est = surface.estimate;
    h.add("refined.size", fmt::format("{} rows x {} cols", est.rows, est.cols));
    h.add("refined.vertices", fmt::format("{:.0f}", est.vertices));
    h.add("refined.triangles", fmt::format("{:.0f}", est.triangles));
    addFit(h, surface);
}

// The geometry written, and what is drawn on it or under it.
void addGeometry(Header& h, const scene::SceneSpec& s, const CompileResult& compiled) {
    const SurfaceSummary& surface = compiled.surface;
    const TerrainSummary& t = compiled.terrain;
    const subdiv::OutputEstimate& est = surface.estimate;
    h.add("geometry", fmt::format("{} ({})", scene::nameOf(surface.geometry.kind), surface.geometry.reason));
    if (surface.geometry.kind == scene::GeometryKind::HeightField)
        h.add("geometry.height_field", fmt::format("{}, 16-bit, one level = {:.3g} m",
                                                   t.heightPng.filename().string(), t.heightStepM));
    if (surface.geometry.kind == scene::GeometryKind::Adaptive)
        h.add("geometry.adaptive", fmt::format("{} triangles of the full mesh2's {:.0f}, vertical error at most {:.3g} "
                                               "m ({:.2g} px)",
                                               t.meshTriangles, est.triangles, t.adaptiveToleranceM,
                                               t.adaptiveTolerancePx));
    else if (surface.maskedNodes > 0)
        h.add("mesh.with_data", fmt::format("{} vertices, {} triangles (masked nodata left out)", t.meshVertices,
                                            t.meshTriangles));
    if (s.overlay.contours && s.overlay.enabled != scene::OverlaySpec::Enabled::Off)
        h.add("overlay.contours",
              fmt::format("every {} m on the surface{}", formatShortest(s.overlay.contours->intervalM),
                          s.overlay.contours->indexEvery > 0
                              ? fmt::format(", every {}th heavier", s.overlay.contours->indexEvery)
                              : std::string()));
    if (compiled.view.baseFloorM)
        h.add("base", fmt::format("a block: walls down to a floor at {:.2f} m, {:.2f} m below the lowest point",
                                  *compiled.view.baseFloorM, compiled.view.zRangeM[0] - *compiled.view.baseFloorM));
}

// The colours and the sun.
void addTextureAndSun(Header& h, const scene::LookSpec& look, const SunFacts& sun) {
    h.add("texture.ramp",
          look.texture.ramp.cptPath.empty() ? look.texture.ramp.preset : "cpt " + look.texture.ramp.cptPath);
    using Colouring = scene::TextureSpec::Colouring;
    if (look.texture.colouring == Colouring::Image) h.add("texture.image", look.texture.drapeImageText);
    if (look.texture.colouring == Colouring::Slope || look.texture.colouring == Colouring::Blend)
        h.add("texture.mode",
              fmt::format("{}: rock from {} to {} degrees of slope", scene::nameOf(look.texture.colouring),
                          formatShortest(look.texture.rockFromDeg), formatShortest(look.texture.rockToDeg)));
    if (sun.fromDatetime)
        h.add("lighting.sun",
              fmt::format("azimuth {:.2f} deg (true), altitude {:.2f} deg, at {} over lon {:.4f} lat {:.4f}",
                          sun.azimuthDeg, sun.altitudeDeg, oneLineText(sun.datetime), sun.lonDeg, sun.latDeg));
    else
        h.add("lighting.sun",
              fmt::format("azimuth {} deg, altitude {} deg", formatShortest(look.lighting.sunAzimuthDeg),
                          formatShortest(look.lighting.sunAltitudeDeg)));
}

// The camera and the still.
// What render.quality adds to the still's light, when it is not the report's.
void addQuality(Header& h, const scene::RenderSpec& render, const scene::LightingSpec& lighting) {
    const scene::QualityLevel& level = scene::qualityLevel(render.quality);
    if (render.quality == scene::Quality::Draft) h.add("render.quality", "draft: no antialiasing");
    if (render.quality == scene::Quality::High)
        h.add("render.quality", fmt::format("high: the sun a disc {} deg wide, sky light by sky-view factor, "
                                            "antialias threshold {} depth {}",
                                            formatShortest(lighting.sunDiameterDeg),
                                            formatShortest(level.antialiasThreshold), level.antialiasDepth));
}

void addCameraAndRender(Header& h, const scene::CameraSpec& camera, const scene::RenderSpec& render,
                        double metresPerUnit) {
    const char* projection = scene::nameOf(camera.projection);
    const auto lonLatH = [](const GeoPoint& p) {
        return fmt::format("lon {} lat {} height {} m", formatShortest(p.lonDeg), formatShortest(p.latDeg),
                           formatShortest(p.heightM));
    };
    if (camera.position)
        h.add("camera", fmt::format("{}, at {}, looking at {}, fov {} deg", projection, lonLatH(*camera.position),
                                    camera.lookAt ? lonLatH(*camera.lookAt) : std::string("the terrain's centre"),
                                    formatShortest(camera.fovDeg)));
    else
        h.add("camera", fmt::format("{}, azimuth {} deg, elevation {} deg, distance {}, fov {} deg", projection,
                                    formatShortest(camera.azimuthDeg), formatShortest(camera.elevationDeg),
                                    camera.distanceM > 0 ? formatShortest(camera.distanceM) + " m" : std::string("fit"),
                                    formatShortest(camera.fovDeg)));
    h.add("render", fmt::format("{} x {}, antialias {}", render.width, render.height, render.antialias ? "on" : "off"));
    if (render.background == scene::Background::Transparent) h.add("render.background", "transparent");
    if (render.background == scene::Background::Colour) {
        const auto& c = render.backgroundColour;  // linear RGB, as POV-Ray gets it
        h.add("render.background",
              fmt::format("rgb {} {} {}", formatShortest(c.r), formatShortest(c.g), formatShortest(c.b)));
    }
    h.add("scene_unit_m", formatShortest(metresPerUnit));
}

}  // namespace

emit::ParameterList sceneHeader(const scene::SceneSpec& s, const geo::ControlNet& net,
                                const subdiv::ResolvedScheme& scheme, const CompileResult& compiled) {
    Header h;
    addData(h, s, net);
    addSubdivision(h, s.subdivision, scheme, compiled.surface);
    addGeometry(h, s, compiled);
    addTextureAndSun(h, s.look, compiled.view.sun);
    addCameraAndRender(h, s.look.camera, s.render, compiled.view.metresPerUnit);
    addQuality(h, s.render, s.look.lighting);
    return std::move(h.lines);
}

}  // namespace relief
