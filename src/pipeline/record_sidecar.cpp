// The JSON sidecar: what made the still, what it cost, what it shows.
#include "pipeline/record.h"

#include <map>

#include "core/text_escape.h"
#include "core/utf8_record.h"

#include <fmt/format.h>

#include "emit/geometry_kind.h"
#include "scene/enum_names.h"
#include "pipeline/depth.h"
#include "relief/version.h"

namespace relief {

using nlohmann::ordered_json;

namespace {

// The net's fit (or prefilter) and the peak loss.
void addFitToSidecar(ordered_json& j, const SurfaceSummary& c) {
    const auto point = [](const Vec3& p) { return ordered_json::array({p.x, p.y, p.z}); };
    j["peak_loss"] = {{"loss_m", c.peakLoss.lossM},
                      {"data_peak_m", point(c.peakLoss.peak)},
                      {"surface_highest_m", point(c.peakLoss.surfaceHighest)},
                      {"within_m", std::max(c.net.dx, c.net.dy)}};
    if (c.prefilter)
        j["net"]["fit"] = {{"kind", "prefilter"},
                           {"depth", c.prefilter->depth},
                           {"largest_change_m", c.prefilter->largestChangeM},
                           {"gain", c.prefilter->gain}};
    if (!c.fit) return;
    const fit::FitReport& f = *c.fit;
    ordered_json gcv = ordered_json::array();
    for (const auto& t : f.gcv) gcv.push_back({{"smoothing", t.smoothing}, {"tension", t.tension}, {"score", t.score}, {"trace_h", t.traceH}, {"strays", t.strays}});
    j["net"]["fit"] = {{"kind", "least squares of the scheme's surface"},
                       {"depth", f.depth},
                       {"samples", f.samples},
                       {"samples_outside_the_net", f.samplesOutside},
                       {"rmse_m", f.rmseM},
                       {"max_residual_m", f.maxResidualM},
                       {"max_residual_at_m", point(f.worstSample)},
                       {"smoothing", f.smoothing},
                       {"smoothing_chosen_by", f.chosenBy},
                       {"tension", f.tension},
                       {"tension_chosen_by", f.tensionChosenBy},
                       {"gcv", gcv},
                       {"trace_method", f.traceMethod},
                       {"nodes", f.nodes},
                       {"nodes_constrained", f.nodesConstrained},
                       {"data_reach_m", f.dataReachM},
                       {"mean_data_reach_m", f.meanReachM},
                       {"unsupported_share", f.unsupportedShare},
                       {"unsupported_beyond_m", f.unsupportedBeyondM},
                       {"unsupported", scene::nameOf(f.unsupportedAs)},
                       {"stray_from_data", f.strayFromData},
                       {"refinement_steps", f.refinementSteps},
                       {"relative_residual", f.relativeResidual},
                       {"seconds", f.seconds}};
}

// What the run read: the scene, its samples and their credit, the parameters the header records.
void addInputs(ordered_json& j, const scene::SceneSpec& scene, const CompileResult& compiled) {
    j["relief_version"] = kVersion;
    j["inputs"] = {{"scene", scene.sceneFile.string()},
                   {"scene_sha1", scene.sceneSha1},
                   {"samples", scene.samples.path.string()},
                   {"sample_count", compiled.surface.net.sampleCount}};
    if (!scene.madeForData.empty()) j["inputs"]["scene_made_for_the_data"] = scene.madeForData;
    if (!compiled.credits.data.empty()) j["inputs"]["attribution"] = compiled.credits.data;
    ordered_json params = ordered_json::object();
    for (const auto& [k, value] : compiled.parameters) params[k] = value;
    j["parameters"] = params;
}

// depth = "auto": the change each level made, and its observed rate beside the scheme's Hölder exponent.
ordered_json autoDepthJson(const scene::SceneSpec& scene, const SurfaceSummary& c) {
    ordered_json levels = ordered_json::array();
    for (size_t i = 0; i < c.autoDepth->levels.size(); ++i) {
        const auto& l = c.autoDepth->levels[i];
        ordered_json level = {{"level", l.level},
                              {"hausdorff_m", l.distanceM},
                              {"curve", l.curve},
                              {"where_m", {l.x, l.y, l.z}},
                              {"seconds", l.seconds}};
        const double rate = observedRate(*c.autoDepth, i, c.arity);
        if (std::isfinite(rate)) level["rate"] = rate;
        levels.push_back(level);
    }
    return {{"tolerance_m", scene.subdivision.toleranceM},
            {"depth", c.depth},
            {"holder_estimate", c.holder},
            {"levels", levels}};
}

// The net, the refined surface and what lies on it, the fit.
void addSurface(ordered_json& j, const scene::SceneSpec& scene, const CompileResult& compiled) {
    const SurfaceSummary& c = compiled.surface;
    const TerrainSummary& t = compiled.terrain;
    j["net"] = {{"rows", c.net.rows},
                {"cols", c.net.cols},
                {"dx_m", c.net.dx},
                {"dy_m", c.net.dy},
                {"frame", c.net.frame},
                {"spacing_reason", c.net.spacingReason},
                {"filled_outside_hull", c.net.filledOutsideHull},
                {"filled_nodata", c.net.filledNodata},
                {"masked_nodata", c.net.maskedNodes}};
    j["refined"] = {{"depth", c.depth},
                    {"depth_reason", c.depthReason},
                    {"rows", c.estimate.rows},
                    {"cols", c.estimate.cols},
                    {"masked_nodata", c.maskedNodes},
                    {"vertices", t.meshVertices},
                    {"triangles", t.meshTriangles},
                    {"pov_bytes", compiled.povBytes},
                    {"memory_estimate_mb", c.estimate.memoryBytes / 1e6}};
    if (c.autoDepth) j["auto_depth"] = autoDepthJson(scene, c);
    if (t.contours.levels > 0)
        j["contours"] = {{"interval_m", scene.overlay.contours->intervalM},
                         {"levels", t.contours.levels},
                         {"lines", t.contours.lines}};
    if (!t.layers.empty()) j["layers"] = t.layers;
    addFitToSidecar(j, c);
}

// The block, the sun and the camera.
void addView(ordered_json& j, const scene::SceneSpec& scene, const ViewSummary& v) {
    if (v.baseFloorM)
        j["base"] = {{"floor_elevation_m", *v.baseFloorM}, {"thickness_m", v.zRangeM[0] - *v.baseFloorM}};
    j["sun"] = {{"azimuth_deg", v.sun.azimuthDeg},
                {"altitude_deg", v.sun.altitudeDeg},
                {"from", v.sun.fromDatetime ? "datetime" : "scene"}};
    j["sun"]["azimuth_is"] = v.sun.fromDatetime ? "true bearing" : "bearing on the frame's grid, as given";
    if (v.sun.fromDatetime) {
        j["sun"]["datetime"] = v.sun.datetime;
        j["sun"]["at_lonlat"] = {v.sun.lonDeg, v.sun.latDeg};
    }
    const auto lonLatH = [](const GeoPoint& p) { return std::array{p.lonDeg, p.latDeg, p.heightM}; };
    j["camera"] = {
        {"eye_lonlat_h", lonLatH(v.cameraEye)}, {"look_at_lonlat_h", lonLatH(v.cameraTarget)},
        {"azimuth_deg", v.cameraAzimuthDeg},    {"elevation_deg", v.cameraElevationDeg},
        {"distance_m", v.cameraDistanceM},      {"placed_by", scene.look.camera.position ? "position" : "orbit"}};
}

// The geometry written and the files made, the still keyed by what it is: "png", "pdf" or "svg".
void addOutputs(ordered_json& j, const scene::SceneSpec& scene, const CompileResult& compiled,
                const OutputPaths& paths) {
    const SurfaceSummary& c = compiled.surface;
    const TerrainSummary& t = compiled.terrain;
    j["geometry"] = {{"kind", scene::nameOf(c.geometry.kind)}, {"reason", c.geometry.reason}};
    if (!t.heightPng.empty()) j["geometry"]["height_step_m"] = t.heightStepM;
    if (c.geometry.kind == scene::GeometryKind::Adaptive) {
        j["geometry"]["tolerance_m"] = t.adaptiveToleranceM;
        j["geometry"]["tolerance_px"] = t.adaptiveTolerancePx;
    }
    j["geometry"]["triangles"] = t.meshTriangles;
    j["outputs"] = {{"pov", paths.pov.string()}};
    if (!t.heightPng.empty()) j["outputs"]["height_png"] = t.heightPng.string();
    if (!t.drapePng.empty()) j["outputs"]["drape_png"] = t.drapePng.string();
    if (t.drapeImageCoverage)
        j["texture"] = {{"image", scene.look.texture.drapeImageText},
                        {"image_covers", *t.drapeImageCoverage},
                        {"image_attribution", compiled.credits.image}};
    if (!paths.still.empty()) {
        const std::string extension = asciiLower(paths.still.extension().string());
        j["outputs"][extension.size() > 1 ? extension.substr(1) : "still"] = paths.still.string();
    }
}

// The sidecar as compiling made it, its strings as they came (a name may not be UTF-8).
ordered_json sidecarFacts(const scene::SceneSpec& scene, const CompileResult& compiled, const OutputPaths& paths) {
    ordered_json j;
    addInputs(j, scene, compiled);
    addSurface(j, scene, compiled);
    addView(j, scene, compiled.view);
    j["seconds"] = {{"read_scene", compiled.seconds.readScene},
                    {"normalize", compiled.seconds.normalize},
                    {"subdivide", compiled.seconds.subdivide},
                    {"emit", compiled.seconds.emit}};
    addOutputs(j, scene, compiled, paths);
    return j;
}

}  // namespace

ordered_json sidecarJson(const scene::SceneSpec& scene, const CompileResult& c, const OutputPaths& paths) {
    ordered_json j = sidecarFacts(scene, c, paths);
    replaceNotUtf8(j);  // compileView has warned
    return j;
}

void warnIfSidecarNotUtf8(const scene::SceneSpec& scene, const CompileResult& c, const std::filesystem::path& pov,
                          Diagnostics& diags) {
    ordered_json j = sidecarFacts(scene, c, {{}, pov, {}});
    if (const std::string bad = replaceNotUtf8(j); !bad.empty())
        warnNotUtf8(diags, {scene.sceneFile.string(), 0, 0}, "the sidecar's " + bad);
}

namespace {

// Pixels to a tenth: the sidecar's boxes and points.
double tenth(double v) { return std::round(v * 10) / 10; }
ordered_json tenthsOf(const PixelBox& b) { return {tenth(b.x0), tenth(b.y0), tenth(b.x1), tenth(b.y1)}; }
ordered_json tenthsOf(const PixelPoint& p) { return {tenth(p.x), tenth(p.y)}; }

void addRenderFacts(ordered_json& j, const RenderFacts& r) {
    double parse = 0, trace = 0;
    ordered_json tiles = ordered_json::array();
    std::map<std::string, int> tilesOn;  // a node's name: its tiles
    for (const auto& t : r.tiles) {
        parse += t.parseSeconds;
        trace += t.traceSeconds;
        tiles.push_back(plan::tileRecordJson(t));
        ++tilesOn[t.node.empty() ? plan::nodeName() : t.node];
    }
    // Every tile parses the whole scene: the parse is paid once a tile, and summed here.
    j["seconds"]["povray_parse"] = parse;
    j["seconds"]["povray_trace"] = trace;
    j["seconds"]["povray_wall"] = r.wallSeconds;
    j["seconds"]["finish"] = r.finishSeconds;
    if (!r.tiles.empty()) j["povray_command"] = r.tiles.front().povrayCommand;
    j["tiles"] = tiles;
    j["nodes"] = tilesOn;
    if (!r.overlays) return;
    const annotate::OverlayRecord& o = *r.overlays;
    j["overlay"] = {{"drawn", o.drawn}};
    if (o.scaleBar.pixels > 0)
        j["overlay"]["scale_bar"] = {{"metres", o.scaleBar.metres},
                                     {"pixels", o.scaleBar.pixels},
                                     {"valid", r.perspective ? "at the centre of the view" : "everywhere"}};
    j["overlay"]["north_deg_clockwise_from_up"] = o.northDeg;
    if (o.northCentre) j["overlay"]["north_arrow_centre_px"] = tenthsOf(*o.northCentre);
    j["overlay"]["placement"] = o.placement;
    for (const auto& [name, box] : o.boxes) j["overlay"]["boxes_px"][name] = tenthsOf(box);
    j["overlay"]["on_terrain"] = o.onTerrain;
    if (!o.leftOut.empty()) {
        ordered_json leftOut = ordered_json::object();
        for (const auto& l : o.leftOut) leftOut[l.item] = "in the way: " + l.inTheWay;
        j["overlay"]["left_out"] = leftOut;
    }
    ordered_json texts = ordered_json::array();
    for (const annotate::DrawnText& t : o.texts)
        texts.push_back({{"text", t.text}, {"box_px", tenthsOf({t.x, t.y, t.x + t.w, t.y + t.h})}});
    j["overlay"]["texts"] = texts;
    if (o.frame) {
        ordered_json ticks = ordered_json::array(), annotations = ordered_json::array();
        for (const auto& t : o.frame->ticks)
            ticks.push_back({{"side", annotate::MapFrame::nameOf(t.side)}, {"px", tenth(t.px)}, {"label", t.label}});
        for (const auto& a : o.frameAnnotations)
            annotations.push_back({{"text", a.text},
                                   {"side", annotate::MapFrame::nameOf(a.side)},
                                   {"tick_px", tenth(a.tickPx)},
                                   {"box_px", tenthsOf(a.box)}});
        j["overlay"]["frame"] = {{"map_px", tenthsOf(o.frame->map)}, {"ticks", ticks}, {"annotations", annotations}};
    }
    if (o.labels.empty()) return;
    ordered_json labels = ordered_json::array();
    for (const auto& l : o.labels) {
        ordered_json label = {{"text", l.text}, {"layer", l.layer}};
        label["anchor_px"] = tenthsOf(l.anchor);
        if (l.placed) {
            label["box_px"] = tenthsOf(l.box);
            label["leader"] = l.leader;
            if (l.leader) label["leader_end_px"] = tenthsOf(l.leaderEnd);
        } else {
            label["left_out"] = l.layer == 0 ? "no free place on its line" : "no free place beside its marker";
        }
        labels.push_back(label);
    }
    j["overlay"]["labels"] = labels;
}

}  // namespace

void addRenderToSidecar(ordered_json& j, const RenderFacts& r) {
    addRenderFacts(j, r);
    replaceNotUtf8(j);  // the labels are drawn text already (drawnText); the tiles' records are the plan's
}

std::string sidecarText(const ordered_json& sidecar) {
    return sidecar.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n";
}

}  // namespace relief
