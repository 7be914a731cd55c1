#include "emit/surface_layers.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "core/number_format.h"
#include "core/text_escape.h"
#include "geo/normalize.h"

namespace relief::emit {

namespace {

constexpr int kOffTerrainNamed = 5;  // features off the terrain named a layer; the rest counted

// A part's vertices in the frame (metres), those forward() cannot carry left out.
std::vector<curves::Point2> inFrame(const geo::Frame& frame, const std::vector<GeoPoint>& part) {
    std::vector<curves::Point2> out;
    out.reserve(part.size());
    for (const GeoPoint& g : part)
        if (const auto p = geo::forward(frame, g)) out.push_back({p->x, p->y});
    return out;
}

// Marks the nodes of `refined` inside the polygon `rings` (even-odd: holes are
// outside) with `fill`, a row of nodes at a time from the rings' crossings.
// Returns how many nodes it marked.
long long fillPolygon(const geo::GeoGrid& refined, const std::vector<std::vector<curves::Point2>>& rings,
                      std::uint8_t fill, std::vector<std::uint8_t>& fillOf) {
    const int rows = refined.rows(), cols = refined.cols();
    std::vector<std::vector<double>> crossings(static_cast<size_t>(rows));
    for (const auto& ring : rings)
        for (size_t i = 0; i < ring.size(); ++i) {
            const curves::Point2 a = ring[i], b = ring[(i + 1) % ring.size()];
            if (a.y == b.y) continue;
            const double lo = std::min(a.y, b.y), hi = std::max(a.y, b.y);
            const int r0 = std::max(0, geo::GeoGrid::indexWithin(std::ceil((lo - refined.y0) / refined.dy), rows));
            const int r1 = std::min(rows - 1, geo::GeoGrid::indexWithin(std::ceil((hi - refined.y0) / refined.dy), rows) - 1);
            for (int r = r0; r <= r1; ++r) {  // rows in [lo, hi): a vertex on a row counts once
                const double y = refined.y0 + r * refined.dy;
                crossings[static_cast<size_t>(r)].push_back(a.x + (b.x - a.x) * (y - a.y) / (b.y - a.y));
            }
        }
    long long marked = 0;
    for (int r = 0; r < rows; ++r) {
        auto& xs = crossings[static_cast<size_t>(r)];
        std::sort(xs.begin(), xs.end());
        for (size_t k = 0; k + 1 < xs.size(); k += 2) {
            const int c0 = std::max(0, geo::GeoGrid::indexWithin(std::ceil((xs[k] - refined.x0) / refined.dx), cols));
            const int c1 = std::min(cols - 1, geo::GeoGrid::indexWithin(std::ceil((xs[k + 1] - refined.x0) / refined.dx), cols) - 1);
            for (int c = c0; c <= c1; ++c, ++marked) fillOf[static_cast<size_t>(r) * cols + c] = fill;
        }
    }
    return marked;
}

// Places one layer's features; false for a feature wholly off the terrain.
class LayerPlacer {
public:
    LayerPlacer(const geo::GeoGrid& refined, const ScenePlacement& where, SurfaceLayers& out, int layer)
        : refined_(refined), where_(where), out_(out), layer_(layer) {}

    bool place(const geo::VectorFeature& f, const RibbonStyle& style, std::uint8_t fill, NodeFills* fills) {
        std::vector<std::vector<curves::Point2>> parts;
        for (const auto& part : f.parts) parts.push_back(inFrame(refined_.frame, part));
        if (f.kind == geo::FeatureKind::Point) return point(f, parts);
        Ribbons& lines = out_.lines[static_cast<size_t>(layer_)];
        const long long before = lines.points;
        for (auto& part : parts) {
            if (f.kind == geo::FeatureKind::Polygon && !part.empty()) part.push_back(part.front());  // closed
            addRibbon(lines, refined_, where_, part, style);
        }
        const bool filled = f.kind == geo::FeatureKind::Polygon && fill &&
                            fillPolygon(refined_, parts, fill, fills->fillOf) > 0;
        return lines.points > before || filled;
    }

private:
    bool point(const geo::VectorFeature& f, const std::vector<std::vector<curves::Point2>>& parts) {
        if (parts.empty() || parts.front().empty()) return false;
        const curves::Point2 p = parts.front().front();
        const auto z = refined_.sample(p.x, p.y);
        if (!z) return false;
        out_.points.push_back({layer_, f.fid, {p.x, p.y, *z}, f.label});
        return true;
    }

    const geo::GeoGrid& refined_;
    const ScenePlacement& where_;
    SurfaceLayers& out_;
    int layer_;
};

// "feature 7 ("Mt Eden") at lon 174.7644, lat -36.8767"
std::string featureText(const geo::VectorFeature& f) {
    const GeoPoint& g = f.parts.empty() || f.parts.front().empty() ? GeoPoint{} : f.parts.front().front();
    return fmt::format("feature {}{} at lon {}, lat {}", f.fid,
                       f.label.empty() ? "" : fmt::format(" (\"{}\")", printableExcerpt(f.label, 60)),
                       formatShortest(std::round(g.lonDeg * 1e6) / 1e6), formatShortest(std::round(g.latDeg * 1e6) / 1e6));
}

}  // namespace

long long SurfaceLayers::triangles() const {
    long long n = 0;
    for (const auto& l : lines) n += static_cast<long long>(l.faces.size());
    return n + 3 * static_cast<long long>(points.size());  // a marker is about three primitives
}

double SurfaceLayers::sdlBytes() const {
    double bytes = 0;
    for (const auto& l : lines) bytes += l.sdlBytes();
    return bytes + 120.0 * static_cast<double>(points.size());
}

SurfaceLayers placeLayers(const std::vector<scene::LayerSpec>& specs, const std::vector<geo::VectorLayer>& read,
                          const geo::GeoGrid& refined, const ScenePlacement& where, double metresPerPixel,
                          Diagnostics& diags) {
    SurfaceLayers out;
    out.lines.resize(specs.size());
    out.counts.resize(specs.size());
    std::shared_ptr<NodeFills> fills;
    for (size_t i = 0; i < specs.size(); ++i) {
        const scene::LayerSpec& spec = specs[i];
        const double widthM = spec.widthPx * metresPerPixel;
        // A quarter of the width, which no pixel shows; pieces no longer than a refined cell, so that
        // a track climbing a slope lies on it rather than cutting under it.
        RibbonStyle style{widthM, 0.25 * widthM, std::min(6 * widthM, std::max(refined.dx, refined.dy))};
        if (spec.dashPx.size() == 2) style.dashM = {spec.dashPx[0] * metresPerPixel, spec.dashPx[1] * metresPerPixel};
        std::uint8_t fill = 0;
        if (spec.fill) {
            if (!fills) fills = std::make_shared<NodeFills>(NodeFills{std::vector<std::uint8_t>(refined.grid.points.size(), 0), {}});
            fills->fills.push_back({*spec.fill, spec.fillOpacity});
            fill = static_cast<std::uint8_t>(fills->fills.size());
        }
        LayerPlacer placer(refined, where, out, static_cast<int>(i));
        LayerCounts& counts = out.counts[i];
        for (const geo::VectorFeature& f : read[i].features) {
            ++counts.read;
            for (const auto& part : f.parts) counts.vertices += static_cast<long long>(part.size());
            ++(f.kind == geo::FeatureKind::Point ? counts.points : f.kind == geo::FeatureKind::Line ? counts.lines
                                                                                                  : counts.polygons);
            if (placer.place(f, style, fill, fills.get())) {
                ++counts.drawn;
                continue;
            }
            if (++counts.offTerrain <= kOffTerrainNamed)
                diags.warning(spec.locs.at("layer.path"),
                              fmt::format("layer {} ({}): {} is off the terrain{}", spec.number,
                                          printableExcerpt(spec.pathAsWritten, 200), featureText(f),
                                          counts.offTerrain == kOffTerrainNamed ? " (further ones are counted in "
                                                                                  "the sidecar)"
                                                                                : ""));
        }
        counts.ribbonPoints = out.lines[i].points;
    }
    out.fills = fills;
    return out;
}

double unitsPerPixelAt(const CameraView& view, const SceneVec3& p, int widthPx) {
    if (!view.perspective) return view.orthoHeight * view.aspect / widthPx;
    const SceneVec3 forward = view.target - view.eye;
    // A panorama or a sphere sees every way: the distance itself, not the depth along the axis.
    const double depth = view.wide ? length(p - view.eye) : dot(p - view.eye, forward) / length(forward);
    return 2 * std::max(depth, 1e-9) * view.tanHalfFov / widthPx;
}

bool seenFromEye(const geo::GeoGrid& refined, const ScenePlacement& where, const CameraView& view, const SceneVec3& p,
                 double liftUnits) {
    const SceneVec3 start = p + SceneVec3{0, liftUnits, 0};
    SceneVec3 towards = view.perspective ? view.eye - start : view.eye - view.target;
    const double span = length(where.boundsMax - where.boundsMin);
    const double reach = view.perspective ? length(towards) : 2 * span;
    towards = (1 / length(towards)) * towards;
    const double step = 0.5 * std::min(refined.dx, refined.dy) / where.metresPerUnit;
    for (double t = step; t < reach; t += step) {
        const SceneVec3 q = start + t * towards;
        if (q.y > where.boundsMax.y) return true;  // above every point of the terrain
        const double x = q.x * where.metresPerUnit + where.originM.x, y = q.z * where.metresPerUnit + where.originM.y;
        const auto h = refined.sample(x, y);
        if (h && q.y < where.scenePoint({x, y, *h}).y) return false;
    }
    return true;
}

namespace {

// The markers' shapes, `P` the point on the surface, `S` the marker's height
// (scene units), `R` the view's right: a pin's ball on its stem, a dot, a flag
// on its pole turned to the viewer.
constexpr const char* kMarkerMacros = R"(#macro ReliefPin(P, S, R)
  cylinder { P, P + <0, 0.7 * S, 0>, 0.06 * S } sphere { P + <0, 0.78 * S, 0>, 0.22 * S }
#end
#macro ReliefDot(P, S, R)
  sphere { P + <0, 0.25 * S, 0>, 0.3 * S }
#end
#macro ReliefFlag(P, S, R)
  cylinder { P, P + <0, S, 0>, 0.04 * S }
  triangle { P + <0, S, 0>, P + <0, 0.62 * S, 0>, P + <0, 0.81 * S, 0> + 0.5 * S * R }
#end
)";

const char* macroOf(scene::MarkerKind kind) {
    switch (kind) {
        case scene::MarkerKind::Dot: return "ReliefDot";
        case scene::MarkerKind::Flag: return "ReliefFlag";
        default: return "ReliefPin";
    }
}

}  // namespace

void writeSurfaceLayers(std::FILE* out, const SurfaceLayers& layers, const std::vector<scene::LayerSpec>& specs,
                        const ScenePlacement& where, const CameraView& view, int widthPx) {
    for (size_t i = 0; i < specs.size(); ++i)
        writeRibbons(out, layers.lines[i], specs[i].colour,
                     fmt::format("[[layer]] {}: {}: lines and outlines lying on the surface.", specs[i].number,
                                 oneLineText(printableExcerpt(specs[i].pathAsWritten, 200))));
    fmt::memory_buffer sdl;  // written at once: a failed write is the .pov's AtomicFile's to report
    bool macros = false;
    for (size_t i = 0; i < specs.size(); ++i) {
        const scene::LayerSpec& spec = specs[i];
        if (spec.marker == scene::MarkerKind::None) continue;
        std::string items;
        for (const LayerPoint& p : layers.points) {
            if (p.layer != static_cast<int>(i)) continue;
            const SceneVec3 s = where.scenePoint(p.groundM);
            // Each marker its size on the still, near or far.
            const double size = spec.markerSizePx * unitsPerPixelAt(view, s, widthPx);
            items += fmt::format("  {}({}, {}, {})\n", macroOf(spec.marker), fixedVector(s.x, s.y, s.z, 5),
                                 formatShortest(std::round(size * 1e5) / 1e5),
                                 fixedVector(view.right.x, view.right.y, view.right.z, 5));
        }
        if (items.empty()) continue;
        if (!macros) fmt::format_to(std::back_inserter(sdl), "{}", kMarkerMacros);
        macros = true;
        const LinearRgb& c = spec.colour;
        fmt::format_to(std::back_inserter(sdl),
                       "// [[layer]] {}: its points' markers, standing on the surface.\nunion {{\n{}  texture {{ "
                       "pigment {{ rgb {} }} finish {{ ambient 0.4 diffuse 0.6 specular 0.2 }} }}\n  no_shadow\n}}\n",
                       spec.number, items, fixedVector(c.r, c.g, c.b, 5));
    }
    std::fwrite(sdl.data(), 1, sdl.size(), out);
}

}  // namespace relief::emit
