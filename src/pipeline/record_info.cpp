// `relief info`: the plan of a scene (estimateSurface) as facts, JSON or text.
#include "pipeline/record.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "core/number_format.h"
#include "core/utf8_record.h"
#include "scene/enum_names.h"

namespace relief {

using nlohmann::ordered_json;

namespace {

// The net's corners in WGS84 degrees: lon_min, lat_min, lon_max, lat_max.
ordered_json lonLatBox(const geo::ControlNet& net) {
    double lonMin = 1e9, lonMax = -1e9, latMin = 1e9, latMax = -1e9;
    for (double x : {net.x0, net.xMax()})
        for (double y : {net.y0, net.yMax()}) {
            const auto g = geo::reverse(net.frame, Vec3{x, y, 0});
            if (!g) continue;
            lonMin = std::min(lonMin, g->lonDeg), lonMax = std::max(lonMax, g->lonDeg);
            latMin = std::min(latMin, g->latDeg), latMax = std::max(latMax, g->latDeg);
        }
    return ordered_json::array({lonMin, latMin, lonMax, latMax});
}

ordered_json dataFacts(const scene::SceneSpec& spec, const geo::ControlNet& net) {
    ordered_json d;
    d["path"] = spec.samples.pathAsWritten;
    d["kind"] = net.raster.empty() ? "scattered samples" : "raster";
    if (!net.raster.empty()) d["raster"] = net.raster;
    d["samples"] = net.sampleCount;
    d["extent_lonlat"] = lonLatBox(net);
    const std::string credit = !spec.samples.attribution.empty() ? spec.samples.attribution : net.attribution;
    if (!credit.empty()) d["attribution"] = credit;
    return d;
}

// The net's facts. An estimate's (estimateSurface) are its size's, its
// heights' and its nodes without data the stand-in's, counted in proportion.
ordered_json netFacts(const Surface& s) {
    const geo::ControlNet& net = s.net;
    const NetSize& size = s.size;
    const auto [zmin, zmax] = net.grid.zRange();
    const double perNode = double(size.rows) * size.cols / (double(net.rows()) * net.cols());
    const auto counted = [perNode](size_t n) { return static_cast<size_t>(std::llround(double(n) * perNode)); };
    ordered_json facts = {{"frame", net.frame.describe()},
                          {"rows", size.rows},
                          {"cols", size.cols},
                          {"spacing_m", size.dx},
                          {"spacing_reason", net.spacingReason},
                          {"extent_m", {size.x0, size.y0, size.xMax(), size.yMax()}},
                          {"elevation_range_m", {zmin, zmax}},
                          {"masked_nodata", counted(net.maskedCount())},
                          {"filled_nodata", counted(net.filledNodata)}};
    if (s.heightsReadAtM > 0)
        facts["estimated"] = fmt::format("the net is not read ({:.3g} nodes): its heights and nodes without data are "
                                         "those of a net at {:.3g} m over the same extent",
                                         double(size.rows) * size.cols, s.heightsReadAtM);
    return facts;
}

// Each figure of the estimate and the limit it meets ("-" where it does not apply).
ordered_json costFacts(const subdiv::Budget& b, const Surface& s) {
    const subdiv::OutputEstimate& e = s.estimate;
    const bool triangles = !e.heightField && !e.meshAfterBuild;
    ordered_json c;
    c["triangles"] = {{"estimate", e.triangles},
                      {"limit", triangles ? ordered_json(b.maxTriangles) : ordered_json("none for this geometry")}};
    c["pov_mb"] = {{"estimate", e.sdlBytes / 1e6}, {"limit", b.maxSdlMB}};
    c["parse_s"] = {{"estimate", e.parseSeconds}, {"limit", b.maxParseS}};
    c["memory_mb"] = {{"estimate", e.memoryBytes / 1e6}, {"limit", b.maxMemoryMB}};
    return c;
}

// Relief over extent: the exaggeration at which the relief would rise a
// twentieth of the terrain's width, offered when 1 leaves it flatter.
ordered_json exaggerationAdvice(const geo::ControlNet& net) {
    const auto [zmin, zmax] = net.grid.zRange();
    const double extent = std::max(net.xMax() - net.x0, net.yMax() - net.y0), relief = zmax - zmin;
    const double ratio = relief / std::max(extent, 1e-9);
    ordered_json a = {{"relief_over_extent", ratio}};
    if (ratio < 0.05 && relief > 0) {
        const double suggested = std::min(100.0, std::max(1.0, std::round(0.05 / ratio)));
        a["advice"] = fmt::format("the relief is {:.2g} of the extent: vertical.exaggeration = {} would make it show",
                                  ratio, formatShortest(suggested));
    }
    return a;
}

constexpr double kNetPixelsWarning = 2;

// A net finer than the still can show: more than twice the nodes the still has pixels
// costs memory and time for detail no pixel holds. Says so, with the spacing
// at which the nodes would match the pixels: a warning when the scene sized
// the net, advice when relief chose it (the data's own spacing).
void netAgainstStill(const NetSize& net, const scene::RenderSpec& render, const scene::NetSpec& spec,
                     ordered_json& facts, Diagnostics& diags) {
    const double nodes = static_cast<double>(net.rows) * net.cols, pixels = double(render.width) * render.height;
    facts["nodes"] = nodes;
    // Up to twice: a still's own net over a terrain whose shape is not the still's (808 x 808 nodes for 800 x 600).
    if (!(nodes > kNetPixelsWarning * pixels)) return;
    const double matching = net.dx * std::sqrt(nodes / pixels);
    facts["advice"] = fmt::format("the net's {} x {} nodes ({:.3g}) are more than twice the still's {} x {} pixels ({:.3g}): "
                                  "net.spacing_m = {} would match them",
                                  net.cols, net.rows, nodes, render.width, render.height, pixels,
                                  formatShortest(std::ceil(matching * 10) / 10));
    for (const char* key : {"net.spacing_m", "net.rows", "net.cols"})
        if (spec.locs.has(key)) return diags.warning(spec.locs.at(key), facts["advice"].get<std::string>());
}

}  // namespace

ordered_json sceneInfo(const LoadedScene& loaded, const Surface& s, Diagnostics& diags) {
    const scene::SceneSpec& spec = loaded.scene;
    ordered_json j;
    j["scene"] = spec.madeForData.empty() ? spec.sceneFile.string() : "made for the data (relief init writes it)";
    j["data"] = dataFacts(spec, s.net);
    j["net"] = netFacts(s);
    // A view of the whole terrain: an eye at a place or flying low sees the net's nodes near it.
    if (!spec.look.camera.position && spec.animation.path != scene::CameraPath::Flyover)
        netAgainstStill(s.size, spec.render, spec.net, j["net"], diags);
    j["subdivision"] = {{"scheme", loaded.resolved.family},
                        {"certified", subdiv::certifiedClass(loaded.resolved.report)},
                        {"depth", s.depth},
                        {"depth_reason", s.depthReason},
                        {"refined_rows", s.estimate.rows},
                        {"refined_cols", s.estimate.cols}};
    j["geometry"] = {{"kind", scene::nameOf(s.geometry.kind)}, {"reason", s.geometry.reason}};
    j["cost"] = costFacts(loaded.budget, s);
    j["still"] = {{"width", spec.render.width}, {"height", spec.render.height}};
    j["vertical"] = exaggerationAdvice(s.net);
    j["vertical"]["exaggeration"] = spec.look.vertical.exaggeration;
    if (const std::string bad = replaceNotUtf8(j); !bad.empty())
        warnNotUtf8(diags, {spec.sceneFile.string(), 0, 0}, bad);
    return j;
}

namespace {

std::string valueText(const ordered_json& v) {
    if (v.is_string()) return v.get<std::string>();
    if (v.is_number_float()) return fmt::format("{:.6g}", v.get<double>());
    if (v.is_array()) {
        std::string out;
        for (const auto& e : v) out += (out.empty() ? "" : ", ") + valueText(e);
        return out;
    }
    if (v.is_object() && v.contains("estimate"))
        return fmt::format("{} (limit {})", valueText(v["estimate"]), valueText(v["limit"]));
    return v.dump(-1, ' ', false, ordered_json::error_handler_t::replace);
}

}  // namespace

std::string sceneInfoText(const ordered_json& info) {
    std::string out;
    for (const auto& [group, facts] : info.items()) {
        if (!facts.is_object()) {
            out += fmt::format("{}: {}\n", group, valueText(facts));
            continue;
        }
        out += fmt::format("\n{}\n", group);
        for (const auto& [key, value] : facts.items()) out += fmt::format("  {}: {}\n", key, valueText(value));
    }
    return out;
}

}  // namespace relief
