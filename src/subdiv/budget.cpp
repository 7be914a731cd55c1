#include "subdiv/budget.h"

#include <algorithm>
#include <bit>

#include <fmt/format.h>

#include "core/memory_budget.h"
#include "core/number_format.h"
#include "core/types.h"

namespace relief::subdiv {

OutputEstimate estimateOutput(const Scheme& scheme, int rows, int cols, int depth, GeometryCost kind) {
    OutputEstimate e;
    e.rows = rows;
    e.cols = cols;
    for (int i = 0; i < depth; ++i) {
        e.rows = scheme.refinedCount(e.rows);
        e.cols = scheme.refinedCount(e.cols);
    }
    const MeshSize size = gridMeshSize(e.rows, e.cols);
    e.vertices = static_cast<double>(size.vertices);
    e.triangles = static_cast<double>(size.triangles);
    e.sdlBytes = e.vertices * kSdlBytesPerVertex + e.triangles * kSdlBytesPerTriangle;
    e.parseSeconds = e.triangles * kParseSecondsPerTriangle;
    const double coarser = depth > 0 ? e.vertices / (scheme.arity * scheme.arity) : 0;
    e.memoryBytes = e.vertices * kMemoryBytesPerVertex + 24 * coarser;
    if (kind == GeometryCost::HeightField) {
        e.sdlBytes = kHeightFieldSdlBytes;
        e.parseSeconds = e.vertices * kParseSecondsPerHeightFieldNode;
        e.memoryBytes = e.vertices * (24 + 2) + 24 * coarser;
        e.heightField = true;
    } else if (kind == GeometryCost::Adaptive) {
        // Beside the grid: the faces (at most the full mesh's), and the
        // RTIN's error per node of the 2^k + 1 square that holds the grid.
        const double side = static_cast<double>(std::bit_ceil(static_cast<unsigned long long>(
                                std::max<long long>(std::max(e.rows, e.cols) - 1, 1)))) + 1;
        e.memoryBytes += e.vertices * kAdaptiveFaceBytesPerVertex + 4 * side * side;
        e.meshAfterBuild = true;
    }
    return e;
}

OutputEstimate withBuiltMesh(OutputEstimate e, double vertices, double triangles) {
    e.vertices = vertices;
    e.triangles = triangles;
    e.sdlBytes = vertices * kSdlBytesPerVertex + triangles * kSdlBytesPerTriangle;
    e.parseSeconds = triangles * kParseSecondsPerTriangle;
    e.meshAfterBuild = false;
    return e;
}

Budget Budget::of(const scene::LimitsSpec& limits) {
    return {limits.maxTriangles, limits.maxSdlMB, limits.maxParseS,
            limits.maxMemoryMB > 0 ? limits.maxMemoryMB : defaultMemoryBudgetMB()};
}

OutputEstimate linesOnSurface(double ribbonTriangles, double sdlBytes, long long meshTriangles) {
    OutputEstimate e;
    e.triangles = ribbonTriangles + double(meshTriangles);
    e.parseSeconds = e.triangles * kParseSecondsPerTriangle;
    e.sdlBytes = sdlBytes;
    return e;
}

bool withinBudget(const OutputEstimate& est, const Budget& budget) {
    if (est.meshAfterBuild) return est.memoryBytes / 1e6 <= budget.maxMemoryMB;
    return (est.heightField || est.triangles <= budget.maxTriangles) && est.sdlBytes / 1e6 <= budget.maxSdlMB &&
           est.parseSeconds <= budget.maxParseS && est.memoryBytes / 1e6 <= budget.maxMemoryMB;
}

int deepestWithinBudget(const Scheme& scheme, int rows, int cols, const Budget& budget, int maxDepth) {
    int depth = 0;
    while (depth < maxDepth && withinBudget(estimateOutput(scheme, rows, cols, depth + 1), budget)) ++depth;
    return depth;
}

std::string overBudget(const OutputEstimate& est, const Budget& budget) {
    if (withinBudget(est, budget)) return "";
    std::string over;
    auto add = [&](std::string s) { over += (over.empty() ? "" : "; ") + s; };
    const bool meshFigures = !est.meshAfterBuild;
    if (meshFigures && !est.heightField && est.triangles > budget.maxTriangles)
        add(fmt::format("{:.3g} triangles > limits.max_triangles = {:.3g}", est.triangles,
                        budget.maxTriangles));
    if (meshFigures && est.sdlBytes / 1e6 > budget.maxSdlMB)
        add(fmt::format("{:.0f} MB of SDL > limits.max_sdl_mb = {}", est.sdlBytes / 1e6,
                        formatShortest(budget.maxSdlMB)));
    if (meshFigures && est.parseSeconds > budget.maxParseS)
        add(fmt::format("~{:.1f} s of POV-Ray parsing > limits.max_parse_s = {}",
                        est.parseSeconds, formatShortest(budget.maxParseS)));
    if (est.memoryBytes / 1e6 > budget.maxMemoryMB)
        add(fmt::format("{:.0f} MB of memory > limits.max_memory_mb = {:.0f}", est.memoryBytes / 1e6,
                        budget.maxMemoryMB));
    return over;
}

bool checkBudget(const OutputEstimate& est, const Budget& budget, const SourceLoc& where, int depth, Diagnostics& diags,
                 bool adaptive) {
    const std::string over = overBudget(est, budget);
    if (over.empty()) return true;
    if (adaptive)
        diags.error(where, fmt::format("depth {} refines the net to {} x {} vertices, and their adaptive "
                                       "mesh2 still has {}; raise geometry.tolerance_px (or tolerance_m), "
                                       "lower subdivision.depth, or raise [limits]",
                                       depth, est.rows, est.cols, over));
    else
        diags.error(where, fmt::format("depth {} refines the net to {} x {} vertices: {}; lower "
                                       "subdivision.depth, use a coarser net, or raise [limits]",
                                       depth, est.rows, est.cols, over));
    return false;
}

}  // namespace relief::subdiv
