#pragma once
// Inside geo: a net in a raster's own frame (crs_frame.h) read straight from
// the cells. Nodes on the cells' centres are the cells. A coarser net whose
// nodes stand k cells apart and are averaged lies on the centres of k x k
// blocks of cells, and each node is its block's mean, as gdal_translate
// -outsize -r average and gdaladdo make them. The blocks tile the raster from
// one anchor (the cells left over, fewer than k a side, split between its
// edges), so every such net of one raster reads the same blocks, whether
// relief chose it or a scene written by relief init gives it.
#include <array>
#include <optional>

#include "geo/geo_grid.h"
#include "geo/raster_source.h"

namespace relief::geo {

/// The raster's cells in blocks of k x k: block (i, j) (row i from the north)
/// covers columns column0 + j k .. + k - 1 and rows row0 + i k .. + k - 1;
/// `columns` x `rows` blocks. k = 1: the cells themselves.
struct CellBlocks {
    int k = 1;
    int column0 = 0, row0 = 0;
    int columns = 0, rows = 0;
    /// The blocks as cells of a raster of their own: its geotransform in the raster's CRS.
    std::array<double, 6> geo(const RasterPlace& place) const;
};
CellBlocks cellBlocks(const RasterPlace& place, int k);

/// The widest block, in cells: one is read whole (a quarter of a million cells).
inline constexpr int kMaxBlockSide = 512;

/// The block side, in cells, of a net in `place`'s own frame spaced a whole
/// number k of its square cells (within 1e-9), 2 <= k <= kMaxBlockSide; else 0.
int blockSideOf(const GeoGrid& net, const RasterPlace& place);

/// `net` (in `place`'s own frame, spaced k cells: blockSideOf) moved onto the
/// centres of the blocks whose centres lie inside `box` (of cell centres in
/// the frame): a shift of less than half a block, and
/// a node fewer or more a side. False, with the net as it was, when fewer than
/// 4 x 4 blocks are inside.
bool onBlockCentres(GeoGrid& net, const RasterPlace& place, const FrameBox& box);

/// The block of `blocks` (or the cell, for k = 1) under the net's north-west
/// node when every node is a block's centre, all inside the raster; nullopt
/// otherwise.
struct BlockWindow {
    int column = 0, row = 0;
};
std::optional<BlockWindow> nodesOnBlockCentres(const GeoGrid& net, const RasterPlace& place, const CellBlocks& blocks);

}  // namespace relief::geo
