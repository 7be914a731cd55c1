// The [[layer]]s and the graticule: read, placed, budgeted, written, and
// described for each view (labels, legend entries, the sidecar's counts).
#include "pipeline/marks.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "core/number_format.h"
#include "core/text_escape.h"
#include "geo/vector_layer.h"
#include "subdiv/budget.h"

namespace relief {

namespace {

constexpr double kGraticuleLabelPx = 12;

}  // namespace

bool surfaceMarksWithinLimits(const SurfaceMarks& m, const scene::SceneSpec& spec, const subdiv::Budget& budget,
                              long long beside, Diagnostics& diags) {
    const auto est = subdiv::linesOnSurface(double(m.triangles()),
                                            m.layers.sdlBytes() + (m.graticule ? m.graticule->ribbons.sdlBytes() : 0),
                                            beside);
    const std::string over = subdiv::overBudget(est, budget);
    // Without marks the surface alone is over: its own check (the budget of the depth) says so.
    if (over.empty() || (!m.graticule && m.layers.lines.empty())) return true;
    // The layer drawing the most (its ribbons' triangles and its markers') is named.
    std::vector<long long> drawn(m.layers.lines.size());
    for (size_t i = 0; i < drawn.size(); ++i) drawn[i] = static_cast<long long>(m.layers.lines[i].faces.size());
    for (const auto& p : m.layers.points) drawn.at(static_cast<size_t>(p.layer)) += 3;
    const size_t most = drawn.empty() ? 0 : std::max_element(drawn.begin(), drawn.end()) - drawn.begin();
    if (m.graticule && (drawn.empty() || static_cast<long long>(m.graticule->ribbons.faces.size()) > drawn[most])) {
        diags.error(spec.overlay.locs.at("overlay.graticule"),
                    fmt::format("overlay.graticule: {} lines of {} triangles beside the surface's {}: {}; choose a "
                                "wider step_deg, or raise [limits]",
                                m.graticule->lines.size(), m.graticule->ribbons.faces.size(), beside, over));
        return false;
    }
    const scene::LayerSpec& l = spec.layers.at(most);
    diags.error(l.locs.at("layer.path"),
                fmt::format("layer {} ({}): {} vertices, simplified to the still's resolution, make {} triangles "
                            "beside the surface's {}: {}; simplify the file, draw fewer features, or raise [limits]",
                            l.number, printableExcerpt(l.pathAsWritten, 200), m.layers.counts.at(most).vertices,
                            drawn[most], beside, over));
    return false;
}

namespace {

bool addGraticule(SurfaceMarks& m, const scene::SceneSpec& spec, const geo::GeoGrid& refined,
                  const emit::ScenePlacement& where, double metresPerPixel, Diagnostics& diags) {
    if (!spec.overlay.graticule) return true;
    const scene::GraticuleSpec& g = *spec.overlay.graticule;
    const LonLatBox box = emit::terrainLonLatBox(refined);
    if (!(box.east >= box.west && box.north >= box.south)) {
        diags.error(spec.overlay.locs.at("overlay.graticule"),
                    "overlay.graticule: the terrain's frame has no longitude and latitude to draw");
        return false;
    }
    if (const int n = emit::graticuleLineCount(g, box); n > emit::kMaxGraticuleLines) {
        diags.error(spec.overlay.locs.at("overlay.graticule"),
                    fmt::format("overlay.graticule: step_deg = {} gives {} lines over the terrain's {:.4f} x {:.4f} "
                                "degrees, more than {}: choose a wider step, or \"auto\"",
                                formatShortest(g.stepDeg), n, box.east - box.west, box.north - box.south,
                                emit::kMaxGraticuleLines));
        return false;
    }
    m.graticule = emit::buildGraticule(g, box, refined, where, g.widthPx * metresPerPixel);
    return true;
}

// Where a graticule line's label goes: of its points on the terrain that the
// eye sees, the lowest on the still (a meridian's, where it leaves the
// terrain's front) or the nearest a side (a parallel's), but not in the
// still's outer band, where the scale bar, the credits and the legends stand.
std::optional<std::array<double, 2>> graticuleAnchor(const emit::GraticuleLine& line, const geo::GeoGrid& refined,
                                                     const emit::ScenePlacement& where, const emit::CameraView& view,
                                                     int W, int H) {
    std::optional<std::array<double, 2>> best;
    double bestScore = -1e300;
    const size_t stride = std::max<size_t>(1, line.frame.size() / 200);
    for (size_t i = 0; i < line.frame.size(); i += stride) {
        const auto& p = line.frame[i];
        const auto h = refined.sample(p.x, p.y);
        if (!h) continue;
        const SceneVec3 s = where.scenePoint({p.x, p.y, *h});
        const auto px = emit::projectToImage(view, s, W, H);
        if (!(px[0] >= 0.04 * W && px[0] < 0.96 * W && px[1] >= 0.04 * H && px[1] < 0.86 * H)) continue;
        const double score = line.meridian ? px[1] : -std::min(px[0], W - px[0]);
        if (score <= bestScore || !emit::seenFromEye(refined, where, view, s, 0.5 * emit::unitsPerPixelAt(view, s, W)))
            continue;
        best = px, bestScore = score;
    }
    return best;
}

annotate::LegendEntry legendEntryOf(const scene::LayerSpec& l, const emit::LayerCounts& c) {
    using Kind = annotate::LegendEntry::Kind;
    const Kind kind = c.polygons > 0 ? Kind::Polygon : c.lines > 0 ? Kind::Line : Kind::Point;
    return {l.legend, kind, l.colour, l.fill, l.fillOpacity, std::min(l.widthPx, 4.0), !l.dashPx.empty()};
}

}  // namespace

long long SurfaceMarks::triangles() const {
    return layers.triangles() + (graticule ? static_cast<long long>(graticule->ribbons.faces.size()) : 0);
}

bool SurfaceMarks::empty() const {
    return layers.points.empty() && std::all_of(layers.lines.begin(), layers.lines.end(),
                                                [](const emit::Ribbons& r) { return r.faces.empty(); }) &&
           (!graticule || graticule->ribbons.faces.empty());
}

std::optional<SurfaceMarks> buildSurfaceMarks(const scene::SceneSpec& spec, const geo::GeoGrid& refined,
                                              const emit::ScenePlacement& where, double metresPerPixel,
                                              Diagnostics& diags) {
    SurfaceMarks m;
    if (spec.overlay.enabled == scene::OverlaySpec::Enabled::Off) return m;
    std::vector<geo::VectorLayer> read;
    for (const scene::LayerSpec& l : spec.layers) {
        auto layer = geo::readVectorLayer(l, static_cast<long long>(spec.limits.maxLayerVertices), diags);
        if (!layer) return std::nullopt;
        m.layerNames.push_back(layer->name);
        read.push_back(std::move(*layer));
    }
    m.layers = emit::placeLayers(spec.layers, read, refined, where, metresPerPixel, diags);
    if (!addGraticule(m, spec, refined, where, metresPerPixel, diags)) return std::nullopt;
    return m;
}

void writeSurfaceMarks(std::FILE* out, const SurfaceMarks& m, const scene::SceneSpec& spec,
                       const emit::ScenePlacement& where, const emit::CameraView& view) {
    emit::writeSurfaceLayers(out, m.layers, spec.layers, where, view, spec.render.width);
    if (m.graticule)
        emit::writeRibbons(out, m.graticule->ribbons, spec.overlay.graticule->colour,
                           fmt::format("The graticule every {} degrees ([overlay] graticule), lying on the surface.",
                                       formatShortest(m.graticule->stepDeg)));
}

nlohmann::ordered_json describeSurfaceMarks(const SurfaceMarks& m, const scene::SceneSpec& spec,
                                            const geo::GeoGrid& refined, const emit::ScenePlacement& where,
                                            const emit::CameraView& view, annotate::OverlayFacts& facts) {
    if (m.layers.counts.size() != spec.layers.size()) return nlohmann::ordered_json::array();  // overlays off
    const int W = spec.render.width, H = spec.render.height;
    std::vector<long long> hidden(spec.layers.size(), 0), offStill(spec.layers.size(), 0);
    for (const emit::LayerPoint& p : m.layers.points) {
        const scene::LayerSpec& l = spec.layers[static_cast<size_t>(p.layer)];
        const SceneVec3 s = where.scenePoint(p.groundM);
        const double unitsPerPx = emit::unitsPerPixelAt(view, s, W);
        if (!emit::seenFromEye(refined, where, view, s, 0.5 * unitsPerPx)) {
            ++hidden[static_cast<size_t>(p.layer)];
            continue;
        }
        const bool marker = l.marker != scene::MarkerKind::None;
        const SceneVec3 top = s + SceneVec3{0, marker ? l.markerSizePx * unitsPerPx : 0, 0};
        const auto anchor = emit::projectToImage(view, top, W, H), ground = emit::projectToImage(view, s, W, H);
        if (!(anchor[0] >= 0 && anchor[0] < W && anchor[1] >= 0 && anchor[1] < H)) {
            ++offStill[static_cast<size_t>(p.layer)];
            continue;
        }
        if (p.label.empty()) continue;
        facts.labels.push_back({drawnText(p.label), {anchor[0], anchor[1]}, marker ? 0.25 * l.markerSizePx : 0,
                                ground[1], l.labelSizePx, l.number});
    }
    nlohmann::ordered_json layers = nlohmann::ordered_json::array();
    if (m.graticule) {
        // Each line's label on the line (annotate places it there or leaves it out, and says so);
        // a line with no point to hold one is said here.
        nlohmann::ordered_json unlabelled = nlohmann::ordered_json::array();
        for (const emit::GraticuleLine& line : m.graticule->lines)
            if (const auto a = graticuleAnchor(line, refined, where, view, W, H))
                facts.labels.push_back({line.label, {(*a)[0], (*a)[1]}, 0, (*a)[1], kGraticuleLabelPx, 0});
            else
                unlabelled.push_back({{"label", line.label},
                                      {"why", "no point of it that the eye sees inside the still, clear of the "
                                              "furniture's band at its edges"}});
        layers.push_back({{"number", 0},
                          {"layer", "graticule"},
                          {"lines", m.graticule->lines.size()},
                          {"unlabelled", unlabelled}});
    }
    for (size_t i = 0; i < spec.layers.size(); ++i) {
        const scene::LayerSpec& l = spec.layers[i];
        const emit::LayerCounts& c = m.layers.counts[i];
        if (!l.legend.empty()) facts.layerLegend.push_back(legendEntryOf(l, c));
        layers.push_back({{"number", l.number},
                          {"path", l.pathAsWritten},
                          {"layer", m.layerNames[i]},
                          {"features", c.read},
                          {"points", c.points},
                          {"lines", c.lines},
                          {"polygons", c.polygons},
                          {"drawn", c.drawn},
                          {"off_terrain", c.offTerrain},
                          {"hidden_from_eye", hidden[i]},
                          {"off_still", offStill[i]},
                          {"vertices_read", c.vertices},
                          {"ribbon_points", c.ribbonPoints}});
    }
    return layers;
}

}  // namespace relief
