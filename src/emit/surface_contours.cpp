#include "emit/surface_contours.h"

#include <cmath>
#include <memory>
#include <vector>

#include <fmt/format.h>
#include <ogr_geometry.h>

#include "core/number_format.h"
#include "measure/contours.h"

namespace relief::emit {

namespace {

std::string point(const SceneVec3& v) {
    return fixedVector(v.x, v.y, v.z, 5);
}

std::vector<double> levelsOf(const ScenePlacement& where, const scene::ContourSpec& spec) {
    std::vector<double> levels;
    for (double k = std::ceil(where.zMinM / spec.intervalM); k * spec.intervalM <= where.zMaxM && levels.size() < 100000;
         ++k)
        levels.push_back(k * spec.intervalM);
    return levels;
}

}  // namespace

int contourLevelCount(const ScenePlacement& where, const scene::ContourSpec& spec) {
    return static_cast<int>(levelsOf(where, spec).size());
}

ContourRibbons buildSurfaceContours(const geo::GeoGrid& refined, const ScenePlacement& where,
                                    const scene::ContourSpec& spec, double widthM, std::string& error) {
    ContourRibbons ribbons;
    SurfaceContours& made = ribbons.made;
    const std::vector<double> levels = levelsOf(where, spec);
    made.levels = static_cast<int>(levels.size());
    if (levels.empty()) return ribbons;
    const auto lines = measure::contourLines(refined, levels, error);
    if (!error.empty()) return ribbons;

    std::vector<SceneVec3>& vertices = ribbons.vertices;
    std::vector<std::array<std::uint32_t, 3>>& faces = ribbons.faces;
    for (size_t li = 0; li < lines.size(); ++li) {
        const long long index = std::llround(levels[li] / spec.intervalM);
        const bool heavy = spec.indexEvery > 0 && index % spec.indexEvery == 0;
        const double half = 0.5 * widthM * (heavy ? 2 : 1);
        for (const curves::PiecewiseBezier& line : lines[li]) {
            // The line as GDAL traced it has a point at every cell it crosses, several a
            // pixel: simplified (GEOS, Douglas-Peucker) to a quarter of the line's width, which
            // no pixel shows, it takes a fraction of the SDL and of POV-Ray's time.
            OGRLineString traced;
            for (const auto& seg : line.segments)
                for (const auto& p : seg.control) traced.addPoint(p.x, p.y);
            std::vector<curves::Point2> pts;
            const std::unique_ptr<OGRGeometry> simple(traced.Simplify(0.25 * widthM));
            const auto* simpleLine = simple ? dynamic_cast<const OGRLineString*>(simple.get()) : nullptr;
            const OGRLineString& kept = simpleLine && simpleLine->getNumPoints() >= 2 ? *simpleLine : traced;
            // ... but not into long thin triangles, whose bounding boxes POV-Ray's rays
            // would meet everywhere: pieces at most six widths long, each end on the surface.
            const double longest = 6 * widthM;
            for (int i = 0; i < kept.getNumPoints(); ++i) {
                const curves::Point2 p{kept.getX(i), kept.getY(i)};
                if (!pts.empty()) {
                    const curves::Point2 a = pts.back();
                    const double d = std::hypot(p.x - a.x, p.y - a.y);
                    if (d <= 1e-9) continue;
                    const int pieces = static_cast<int>(std::ceil(d / longest));
                    for (int k = 1; k < pieces; ++k)
                        pts.push_back({a.x + (p.x - a.x) * k / pieces, a.y + (p.y - a.y) * k / pieces});
                }
                pts.push_back(p);
            }
            if (pts.size() < 2) continue;
            ++made.lines;
            // Two vertices a point, across the line; a run of quads along it,
            // broken where the surface has no data.
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
                const auto v = static_cast<std::uint32_t>(vertices.size());
                vertices.push_back(where.scenePoint({pts[i].x + nx, pts[i].y + ny, *left + lift}));
                vertices.push_back(where.scenePoint({pts[i].x - nx, pts[i].y - ny, *right + lift}));
                ++made.points;
                if (previous >= 0) {
                    const auto u = static_cast<std::uint32_t>(previous);
                    faces.push_back({u, u + 1, v + 1});
                    faces.push_back({u, v + 1, v});
                }
                previous = v;
            }
        }
    }
    return ribbons;
}

void writeSurfaceContours(std::FILE* out, const ContourRibbons& ribbons, const scene::ContourSpec& spec) {
    const auto& vertices = ribbons.vertices;
    const auto& faces = ribbons.faces;
    if (faces.empty()) return;
    const auto& c = spec.colour;
    fmt::memory_buffer sdl;  // written at once: a failed write is the .pov's AtomicFile's to report
    fmt::format_to(std::back_inserter(sdl), "// Contour lines every {} m ([overlay] contours), lying on the surface.\n",
               formatShortest(spec.intervalM));
    fmt::format_to(std::back_inserter(sdl), "mesh2 {{\n  vertex_vectors {{\n    {}", vertices.size());
    for (const SceneVec3& v : vertices) fmt::format_to(std::back_inserter(sdl), ",\n{}", point(v));
    fmt::format_to(std::back_inserter(sdl), "\n  }}\n  face_indices {{\n    {}", faces.size());
    for (const auto& f : faces) fmt::format_to(std::back_inserter(sdl), ",\n<{},{},{}>", f[0], f[1], f[2]);
    fmt::format_to(
        std::back_inserter(sdl),
        "\n  }}\n  texture {{ pigment {{ rgb {} }} finish {{ ambient 0.35 diffuse 0.4 }} }}\n  no_shadow\n}}\n",
        fixedVector(c.r, c.g, c.b, 5));
    std::fwrite(sdl.data(), 1, sdl.size(), out);
}

}  // namespace relief::emit
