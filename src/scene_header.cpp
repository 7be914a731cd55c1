// The .pov's header (and the sidecar's "parameters"): every input and choice
// that made the scene, as key and value, one line each.
#include "scene_header.h"

#include <fmt/format.h>

#include "core/number_format.h"
#include "core/text_escape.h"
#include "emit/geometry_kind.h"
#include "scene/enum_names.h"
#include "relief/version.h"

namespace relief {

emit::ParameterList sceneHeader(const scene::SceneSpec& s, const geo::ControlNet& net,
                                const subdiv::ResolvedScheme& scheme, int depth, const CompileResult& compiled) {
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
    if (net.spacingReason.starts_with("about")) add("net.spacing_reason", net.spacingReason);
    add("net.origin_m", fmt::format("{}, {}", formatShortest(net.x0), formatShortest(net.y0)));
    if (net.raster.empty()) add("net.gridding", scene::nameOf(s.net.gridding));
    else add("samples.raster", net.raster);
    if (net.filledNodata > 0) add("net.filled_nodata", std::to_string(net.filledNodata));
    else if (!net.masked.empty()) add("net.masked_nodata", std::to_string(net.maskedCount()));
    else add("net.filled_outside_hull", std::to_string(net.filledOutsideHull));
    add("vertical.exaggeration", formatShortest(look.vertical.exaggeration));
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
    add("subdivision.depth", sub.depthAuto
                                 ? fmt::format("{} (auto, tolerance_m = {})", depth, formatShortest(sub.toleranceM))
                             : sub.depthGiven ? std::to_string(depth)
                                              : fmt::format("{} ({})", depth, compiled.depthReason));
    add("refined.size", fmt::format("{} rows x {} cols", est.rows, est.cols));
    add("refined.vertices", fmt::format("{:.0f}", est.vertices));
    add("refined.triangles", fmt::format("{:.0f}", est.triangles));
    add("geometry", fmt::format("{} ({})", scene::nameOf(compiled.geometry.kind), compiled.geometry.reason));
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
    add("texture.ramp",
        look.texture.ramp.cptPath.empty() ? look.texture.ramp.preset : "cpt " + look.texture.ramp.cptPath);
    using Colouring = scene::TextureSpec::Colouring;
    if (look.texture.colouring == Colouring::Image) add("texture.image", look.texture.drapeImageText);
    if (look.texture.colouring == Colouring::Slope || look.texture.colouring == Colouring::Blend)
        add("texture.mode",
            fmt::format("{}: rock from {} to {} degrees of slope", scene::nameOf(look.texture.colouring),
                        formatShortest(look.texture.rockFromDeg), formatShortest(look.texture.rockToDeg)));
    if (compiled.sun.fromDatetime)
        add("lighting.sun", fmt::format("azimuth {:.2f} deg (true), altitude {:.2f} deg, at {} over lon {:.4f} lat {:.4f}",
                                        compiled.sun.azimuthDeg, compiled.sun.altitudeDeg,
                                        oneLineText(compiled.sun.datetime), compiled.sun.lonDeg, compiled.sun.latDeg));
    else
        add("lighting.sun", fmt::format("azimuth {} deg, altitude {} deg", formatShortest(look.lighting.sunAzimuthDeg),
                                        formatShortest(look.lighting.sunAltitudeDeg)));
    const char* projection = scene::nameOf(camera.projection);
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

}  // namespace relief
