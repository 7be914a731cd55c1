#include "geo/cell_blocks.h"

#include <algorithm>
#include <cmath>

namespace relief::geo {

namespace {

bool nearly(double a, double b) {
    return std::fabs(a - b) <= 1e-9 * std::fabs(b);
}

// A square-celled, north-up raster: the only kind whose blocks are squares of the frame.
bool squareCells(const RasterPlace& place) {
    const auto& g = place.geo;
    return g[2] == 0 && g[4] == 0 && g[1] > 0 && g[5] < 0 && nearly(-g[5], g[1]);
}

// The first and last block (0-based, clipped to `count`) whose centre lies in
// the cell-centre range [lo, hi], in cells from the raster's edge.
std::array<int, 2> blocksWithin(double lo, double hi, int first, int k, int count) {
    const double half = 0.5 * k;  // a block's centre, from its first cell's edge
    const int a = std::max(0, static_cast<int>(std::ceil((lo - first - half) / k - 1e-9)));
    const int b = std::min(count - 1, static_cast<int>(std::floor((hi - first - half) / k + 1e-9)));
    return {a, b};
}

}  // namespace

std::array<double, 6> CellBlocks::geo(const RasterPlace& place) const {
    const auto& g = place.geo;
    return {g[0] + column0 * g[1], k * g[1], 0, g[3] + row0 * g[5], 0, k * g[5]};
}

CellBlocks cellBlocks(const RasterPlace& place, int k) {
    const int columns = place.width / k, rows = place.height / k;
    return {k, (place.width - columns * k) / 2, (place.height - rows * k) / 2, columns, rows};
}

int blockSideOf(const GeoGrid& net, const RasterPlace& place) {
    if (net.frame.kind != scene::FrameKind::Raster || !squareCells(place) || !nearly(net.dx, net.dy)) return 0;
    const double k = net.dx / place.geo[1];
    return k >= 1.5 && k <= kMaxBlockSide && std::fabs(k - std::round(k)) <= 1e-9 * k ? static_cast<int>(std::round(k))
                                                                                      : 0;
}

bool onBlockCentres(GeoGrid& net, const RasterPlace& place, const FrameBox& box) {
    const int k = blockSideOf(net, place);
    if (k < 2) return false;
    const CellBlocks blocks = cellBlocks(place, k);
    const auto& g = place.geo;
    // The box's cell centres, in cells from the raster's west and north edges.
    const auto across =
        blocksWithin((box.west - g[0]) / g[1], (box.east - g[0]) / g[1], blocks.column0, k, blocks.columns);
    const auto down = blocksWithin((box.north - g[3]) / g[5], (box.south - g[3]) / g[5], blocks.row0, k, blocks.rows);
    const int cols = across[1] - across[0] + 1, rows = down[1] - down[0] + 1;
    if (cols < 4 || rows < 4) return false;
    const auto bg = blocks.geo(place);
    net.x0 = bg[0] + (across[0] + 0.5) * bg[1];
    net.y0 = bg[3] + (down[1] + 0.5) * bg[5];  // the southern row of nodes
    net.dx = net.dy = bg[1];
    net.grid.cols = cols;
    net.grid.rows = rows;
    return true;
}

std::optional<BlockWindow> nodesOnBlockCentres(const GeoGrid& net, const RasterPlace& place, const CellBlocks& blocks) {
    if (net.frame.kind != scene::FrameKind::Raster || !squareCells(place)) return std::nullopt;
    const auto bg = blocks.geo(place);
    if (!nearly(net.dx, bg[1]) || !nearly(net.dy, -bg[5])) return std::nullopt;
    const double column = (net.x0 - bg[0]) / bg[1] - 0.5, row = (net.yMax() - bg[3]) / bg[5] - 0.5;
    const double c = std::round(column), r = std::round(row);
    if (std::fabs(column - c) > 1e-6 || std::fabs(row - r) > 1e-6 || c < 0 || r < 0 ||
        c + net.cols() > blocks.columns || r + net.rows() > blocks.rows)
        return std::nullopt;
    return BlockWindow{static_cast<int>(c), static_cast<int>(r)};
}

}  // namespace relief::geo
