#include "emit/surface_ribbons.h"

#include <algorithm>
#include <cmath>
#include <memory>

#include <fmt/format.h>
#include <ogr_geometry.h>

#include "core/number_format.h"

namespace relief::emit {

namespace {

// The part of segment a-b inside `box` as parameters t0 <= t1 in [0, 1]
// (Liang-Barsky); false when it misses the box.
bool clipToBox(curves::Point2 a, curves::Point2 b, const FrameBox& box, double& t0, double& t1) {
    t0 = 0, t1 = 1;
    const double d[2] = {b.x - a.x, b.y - a.y}, lo[2] = {box.west - a.x, box.south - a.y},
                 hi[2] = {box.east - a.x, box.north - a.y};
    for (int k = 0; k < 2; ++k) {
        if (d[k] == 0) {
            if (lo[k] > 0 || hi[k] < 0) return false;
            continue;
        }
        const double u = lo[k] / d[k], v = hi[k] / d[k];
        t0 = std::max(t0, std::min(u, v));
        t1 = std::min(t1, std::max(u, v));
    }
    return t0 <= t1;
}

// The line simplified (GEOS, Douglas-Peucker) to `tolerance`, then cut into
// pieces at most `longest` long where it crosses `box` (a boundary file's
// thousands of kilometres off the terrain are not cut into metres): a traced
// line's point a pixel costs SDL and POV-Ray's time no pixel shows, and long
// thin triangles have bounding boxes POV-Ray's rays would meet everywhere.
std::vector<curves::Point2> simplifiedAndCut(std::span<const curves::Point2> line, double tolerance, double longest,
                                             const FrameBox& box) {
    OGRLineString traced;
    // Sized once: addPoint grows the array a point at a time, a copy each where realloc cannot
    // grow in place (quadratic for a million-vertex track).
    traced.setNumPoints(static_cast<int>(line.size()), FALSE);
    for (size_t i = 0; i < line.size(); ++i) traced.setPoint(static_cast<int>(i), line[i].x, line[i].y);
    std::unique_ptr<OGRGeometry> simple(tolerance > 0 ? traced.Simplify(tolerance) : nullptr);
    const auto* simpleLine = simple ? dynamic_cast<const OGRLineString*>(simple.get()) : nullptr;
    const OGRLineString& kept = simpleLine && simpleLine->getNumPoints() >= 2 ? *simpleLine : traced;
    std::vector<curves::Point2> pts;
    for (int i = 0; i < kept.getNumPoints(); ++i) {
        const curves::Point2 p{kept.getX(i), kept.getY(i)};
        if (!pts.empty()) {
            const curves::Point2 a = pts.back();
            const double d = std::hypot(p.x - a.x, p.y - a.y);
            if (d <= 1e-9) continue;
            double t0 = 0, t1 = 1;
            if (clipToBox(a, p, box, t0, t1)) {
                const int pieces = std::max(1, static_cast<int>(std::ceil(d * (t1 - t0) / longest)));
                for (int k = 0; k <= pieces; ++k) {
                    const double at = t0 * pieces + (t1 - t0) * k;  // t * pieces; exact for a segment inside
                    if (at > 0 && at < pieces)
                        pts.push_back({a.x + (p.x - a.x) * at / pieces, a.y + (p.y - a.y) * at / pieces});
                }
            }
        }
        pts.push_back(p);
    }
    return pts;
}

// The drawn stretches of a dashed line: `on` metres drawn, `off` left out, from its start.
std::vector<std::vector<curves::Point2>> dashes(const std::vector<curves::Point2>& pts, double on, double off) {
    std::vector<std::vector<curves::Point2>> out;
    if (pts.empty()) return out;
    bool drawing = true;
    double left = on;  // of the current dash or gap
    out.push_back({pts.front()});
    for (size_t i = 1; i < pts.size(); ++i) {
        curves::Point2 a = pts[i - 1];
        const curves::Point2 b = pts[i];
        double d = std::hypot(b.x - a.x, b.y - a.y);
        while (d > left) {
            const double t = left / d;
            a = {a.x + (b.x - a.x) * t, a.y + (b.y - a.y) * t};
            d -= left;
            if (drawing) out.back().push_back(a);
            else out.push_back({a});
            drawing = !drawing;
            left = drawing ? on : off;
        }
        left -= d;
        if (drawing) out.back().push_back(b);
    }
    std::erase_if(out, [](const auto& dash) { return dash.size() < 2; });
    return out;
}

// Two vertices a point, across the line; a run of quads along it, broken
// where the surface has no data.
void addStrip(Ribbons& out, const geo::GeoGrid& refined, const ScenePlacement& where,
              const std::vector<curves::Point2>& pts, double half) {
    std::int64_t previous = -1;
    for (size_t i = 0; i < pts.size(); ++i) {
        const auto& a = pts[i > 0 ? i - 1 : i];
        const auto& b = pts[i + 1 < pts.size() ? i + 1 : i];
        double tx = b.x - a.x, ty = b.y - a.y;
        if (std::hypot(tx, ty) < 1e-9) tx = pts[i].x - a.x, ty = pts[i].y - a.y;  // a line back on itself
        const double len = std::hypot(tx, ty);
        if (!(len > 1e-9)) {
            previous = -1;
            continue;
        }
        tx /= len, ty /= len;
        const double nx = -ty * half, ny = tx * half;
        const auto left = refined.sample(pts[i].x + nx, pts[i].y + ny);
        const auto right = refined.sample(pts[i].x - nx, pts[i].y - ny);
        if (!left || !right) {
            previous = -1;
            continue;
        }
        const double lift = 0.4 * half;
        const auto v = static_cast<std::uint32_t>(out.vertices.size());
        out.vertices.push_back(where.scenePoint({pts[i].x + nx, pts[i].y + ny, *left + lift}));
        out.vertices.push_back(where.scenePoint({pts[i].x - nx, pts[i].y - ny, *right + lift}));
        ++out.points;
        if (previous >= 0) {
            const auto u = static_cast<std::uint32_t>(previous);
            out.faces.push_back({u, u + 1, v + 1});
            out.faces.push_back({u, v + 1, v});
        }
        previous = v;
    }
}

}  // namespace

void addRibbon(Ribbons& out, const geo::GeoGrid& refined, const ScenePlacement& where,
               std::span<const curves::Point2> line, const RibbonStyle& style) {
    const double margin = style.widthM + style.longestM;
    const FrameBox box{std::min(refined.x0, refined.xMax()) - margin, std::min(refined.y0, refined.yMax()) - margin,
                       std::max(refined.x0, refined.xMax()) + margin, std::max(refined.y0, refined.yMax()) + margin};
    const std::vector<curves::Point2> pts = simplifiedAndCut(line, style.simplifyM, style.longestM, box);
    if (pts.size() < 2) return;
    ++out.lines;
    const double half = 0.5 * style.widthM;
    if (!(style.dashM[0] > 0 && style.dashM[1] > 0)) return addStrip(out, refined, where, pts, half);
    for (const auto& dash : dashes(pts, style.dashM[0], style.dashM[1])) addStrip(out, refined, where, dash, half);
}

void writeRibbons(std::FILE* out, const Ribbons& ribbons, const LinearRgb& c, std::string_view comment) {
    if (ribbons.faces.empty()) return;
    fmt::memory_buffer sdl;  // written at once: a failed write is the .pov's AtomicFile's to report
    fmt::format_to(std::back_inserter(sdl), "// {}\n", comment);
    fmt::format_to(std::back_inserter(sdl), "mesh2 {{\n  vertex_vectors {{\n    {}", ribbons.vertices.size());
    for (const SceneVec3& v : ribbons.vertices) fmt::format_to(std::back_inserter(sdl), ",\n{}", fixedVector(v.x, v.y, v.z, 5));
    fmt::format_to(std::back_inserter(sdl), "\n  }}\n  face_indices {{\n    {}", ribbons.faces.size());
    for (const auto& f : ribbons.faces) fmt::format_to(std::back_inserter(sdl), ",\n<{},{},{}>", f[0], f[1], f[2]);
    fmt::format_to(
        std::back_inserter(sdl),
        "\n  }}\n  texture {{ pigment {{ rgb {} }} finish {{ ambient 0.35 diffuse 0.4 }} }}\n  no_shadow\n}}\n",
        fixedVector(c.r, c.g, c.b, 5));
    std::fwrite(sdl.data(), 1, sdl.size(), out);
}

}  // namespace relief::emit
