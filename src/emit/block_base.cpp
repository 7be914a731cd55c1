#include "emit/block_base.h"

#include <array>
#include <unordered_map>
#include <vector>

#include <fmt/format.h>

#include "core/number_format.h"

namespace relief::emit {

namespace {

std::string point(const SceneVec3& v) {
    return fixedVector(v.x, v.y, v.z, 5);
}

}  // namespace

BlockGeometry buildBlockBase(const geo::GeoGrid& refined) {
    const Grid& g = refined.grid;
    const size_t cols = static_cast<size_t>(g.cols), rows = static_cast<size_t>(g.rows);
    BlockGeometry block;
    if (rows < 2 || cols < 2) return block;
    auto kept = [&](size_t i) { return refined.masked.empty() || refined.masked[i] == 0; };
    // The lattice's triangles, as the surface's writers cut a cell (sw, se, ne, nw):
    // the lower one (sw, se, nw) and the upper one (se, ne, nw).
    auto lower = [&](size_t r, size_t c) {
        const size_t sw = r * cols + c;
        return kept(sw) && kept(sw + 1) && kept(sw + cols);
    };
    auto upper = [&](size_t r, size_t c) {
        const size_t sw = r * cols + c;
        return kept(sw + 1) && kept(sw + cols + 1) && kept(sw + cols);
    };
    std::unordered_map<size_t, std::uint32_t> topOf, bottomOf;
    auto vertex = [&](std::unordered_map<size_t, std::uint32_t>& of, size_t node, bool floor) {
        auto [it, added] = of.try_emplace(node, static_cast<std::uint32_t>(block.vertices.size()));
        if (added) block.vertices.push_back({node, floor});
        return it->second;
    };
    auto top = [&](size_t node) { return vertex(topOf, node, false); };
    auto bottom = [&](size_t node) { return vertex(bottomOf, node, true); };
    // A wall under edge (a, b): two triangles down to the floor.
    auto wall = [&](size_t a, size_t b) {
        const std::uint32_t ta = top(a), tb = top(b), ba = bottom(a), bb = bottom(b);
        block.faces.push_back({ta, tb, bb});
        block.faces.push_back({ta, bb, ba});
        block.wallTriangles += 2;
    };
    for (size_t r = 0; r < rows; ++r)
        for (size_t c = 0; c < cols; ++c) {
            const size_t n = r * cols + c;
            // Edge east of n, (r, c)-(r, c+1): the lower triangle of the cell
            // north of it, the upper triangle of the cell south of it.
            if (c + 1 < cols) {
                const bool north = r + 1 < rows && lower(r, c), south = r > 0 && upper(r - 1, c);
                if (north != south) wall(n, n + 1);
            }
            // Edge north of n, (r, c)-(r+1, c): the lower triangle of the cell to
            // its east, the upper triangle of the cell to its west.
            if (r + 1 < rows) {
                const bool east = c + 1 < cols && lower(r, c), west = c > 0 && upper(r, c - 1);
                if (east != west) wall(n, n + cols);
            }
            // The diagonal of the cell north-east of n, (r, c+1)-(r+1, c).
            if (r + 1 < rows && c + 1 < cols && lower(r, c) != upper(r, c)) wall(n + 1, n + cols);
        }
    // The floor: rectangles of whole cells (runs along a row, merged with the
    // same run in the rows above), and the half cells. Few large triangles:
    // long thin ones, a row each, cost POV-Ray's bounding hierarchy a third
    // of the default scene's trace.
    struct Run {
        size_t c0, c1, r0;  // cells c0..c1-1, from row r0
    };
    std::vector<Run> open;  // the rectangles still growing, from the previous row
    auto close = [&](const Run& run, size_t rowEnd) {  // rows run.r0 .. rowEnd-1
        const size_t sw = run.r0 * cols + run.c0, se = run.r0 * cols + run.c1;
        const size_t nw = rowEnd * cols + run.c0, ne = rowEnd * cols + run.c1;
        block.faces.push_back({bottom(sw), bottom(se), bottom(ne)});
        block.faces.push_back({bottom(sw), bottom(ne), bottom(nw)});
        block.floorTriangles += 2;
    };
    for (size_t r = 0; r + 1 < rows; ++r) {
        std::vector<Run> runs;
        size_t c = 0;
        while (c + 1 < cols) {
            const size_t sw = r * cols + c;
            if (lower(r, c) && upper(r, c)) {
                size_t end = c + 1;
                while (end + 1 < cols && lower(r, end) && upper(r, end)) ++end;
                runs.push_back({c, end, r});
                c = end;
                continue;
            }
            if (lower(r, c)) block.faces.push_back({bottom(sw), bottom(sw + 1), bottom(sw + cols)});
            if (upper(r, c)) block.faces.push_back({bottom(sw + 1), bottom(sw + cols + 1), bottom(sw + cols)});
            block.floorTriangles += lower(r, c) + upper(r, c);
            ++c;
        }
        // A run the same as one of the previous row's extends it; the rest close.
        std::vector<Run> next;
        size_t k = 0;
        for (Run& run : runs) {
            while (k < open.size() && open[k].c0 < run.c0) close(open[k++], r);
            if (k < open.size() && open[k].c0 == run.c0 && open[k].c1 == run.c1) run.r0 = open[k++].r0;
            next.push_back(run);
        }
        while (k < open.size()) close(open[k++], r);
        open = std::move(next);
    }
    for (const Run& run : open) close(run, rows - 1);
    return block;
}

LinearRgb blockWallColour(const ScenePlacement& where) {
    // The lowest colour of the ramp (in slope colouring, of the flat), half greyed: a ramp's lowest
    // colour may be near black (the deep sea of a topobathy), and the side of a block is not the
    // lowest ground's colour but a plinth under it. Then a shade darker than the surface.
    const LinearRgb grey{kBlockWallGrey, kBlockWallGrey, kBlockWallGrey};
    const LinearRgb lowest = where.paletteColors.empty() ? grey : where.paletteColors.front();
    const LinearRgb c = mix(lowest, grey, 0.5);
    return {kBlockWallShade * c.r, kBlockWallShade * c.g, kBlockWallShade * c.b};
}

void writeBlockBase(std::FILE* out, const geo::GeoGrid& refined, const ScenePlacement& where) {
    const BlockGeometry block = buildBlockBase(refined);
    if (block.faces.empty()) return;
    const double floorM = *where.baseElevationM;
    const auto& points = refined.grid.points;
    // Formatted in memory, then written: a failed write (a full disk) is the
    // .pov's AtomicFile's to report, not an exception from here.
    fmt::memory_buffer sdl;
    fmt::format_to(std::back_inserter(sdl), "// The block model ([base]): walls from the surface's edge down to a floor at {:.2f} m.\n", floorM);
    fmt::format_to(std::back_inserter(sdl), "mesh2 {{\n  vertex_vectors {{\n    {}", block.vertices.size());
    for (const auto& v : block.vertices)
        fmt::format_to(std::back_inserter(sdl), ",\n{}", point(v.floor ? where.scenePointAtElevation(points[v.node], floorM)
                                              : where.scenePoint(points[v.node])));
    fmt::format_to(std::back_inserter(sdl), "\n  }}\n  face_indices {{\n    {}", block.faces.size());
    for (const auto& f : block.faces) fmt::format_to(std::back_inserter(sdl), ",\n<{},{},{}>", f[0], f[1], f[2]);
    // One colour, lit mostly by the even light: a colour that changed along the walls would streak
    // them under every change of the surface's edge, and a wall facing away from the sun must not
    // go black. It casts no shadow the still could show: the walls hang below the surface's edge,
    // the floor under all.
    const LinearRgb c = blockWallColour(where);
    fmt::format_to(std::back_inserter(sdl),
                   "\n  }}\n  texture {{ pigment {{ rgb {} }} finish {{ ambient {} diffuse {} specular 0 }} }}\n"
                   "  no_shadow\n}}\n",
                   fixedVector(c.r, c.g, c.b, 5), kBlockWallAmbient, 1 - kBlockWallAmbient);
    std::fwrite(sdl.data(), 1, sdl.size(), out);
}

}  // namespace relief::emit
