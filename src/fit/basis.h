#pragma once
// The scheme's surface as weights on the net: refinement is linear in the
// net's heights and a tensor product (the same rule along rows, then along
// columns), so the refined grid at depth d is sum_ij z_ij Bx_j(col) By_i(row),
// each factor a net's unit impulse refined along one axis by the refiner's own
// arithmetic, its boundary rule included: what is fitted is what is rendered.
#include <utility>
#include <vector>

#include "geo/geo_grid.h"
#include "subdiv/scheme.h"

namespace relief::fit {

/// Along one axis of a net of `nodes` nodes, after `depth` levels: each
/// refined index's value as weights on the net's nodes, and its position.
struct AxisBasis {
    int nodes = 0;
    std::vector<std::vector<std::pair<int, double>>> weights;  ///< [refined index]: (node, weight), no zeros
    std::vector<double> position;  ///< [refined index]: in net spacings from node 0 (the refined nodes' own)
    int span = 0;  ///< the most nodes (first to last) a point between refined indices k and k+1 depends on
    /// The refined interval [k, k+1] holding position `u` (net spacings), and
    /// where in it (0..1); false outside the net.
    bool locate(double u, int& k, double& f) const;
};

AxisBasis axisBasis(const subdiv::Scheme& scheme, int nodes, int depth);

/// The surface at a point as weights on the net's nodes (row-major index r *
/// cols + c): bilinear between the four refined nodes around it.
struct SurfaceRow {
    std::vector<std::pair<int, double>> x, y;  ///< the two axes' weights (col, w), (row, w)
};
/// False outside the net.
bool surfaceRow(const AxisBasis& bx, const AxisBasis& by, const geo::GeoGrid& net, double x, double y, SurfaceRow& row);

}  // namespace relief::fit
