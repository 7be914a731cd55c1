#pragma once
// The one georeferenced grid of relief: a regular lattice of nodes in a
// projected frame (metres, x = east, y = north, z = up). Normalization makes
// one (the control net), refinement makes a finer one over the same extent, and
// emit, profiles, contours, compare-geometry and automatic depth read them.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/types.h"
#include "scene/scene_spec.h"

namespace relief::geo {

/// The projected frame a grid lives in.
struct Frame {
    scene::FrameKind kind = scene::FrameKind::Utm;
    int utmZone = 0;           ///< 1..60 (0 = UPS), for Utm
    bool northp = true;        ///< hemisphere, for Utm
    double originLatDeg = 0;   ///< tangent point, for Local
    double originLonDeg = 0;
    std::string crsWkt;            ///< the raster's CRS (WKT2), for Raster: x, y are its easting and northing
    std::string crsName;           ///< its name, e.g. "OSGB36 / British National Grid"
    std::string describe() const;  ///< e.g. "UTM zone 60S", "local tangent plane at ..." or a CRS's name
};

/// Node (r, c) sits at (x0 + c dx, y0 + r dy) in `frame`; row 0 is the southern
/// edge, column 0 the western. `grid.at(r, c)` holds the node's x, y and its
/// height z (metres). Refinement keeps the lattice regular (point reflection
/// reproduces linear data), so x and y of every node stay on the lattice.
struct GeoGrid {
    Frame frame;
    Grid grid;
    double x0 = 0, y0 = 0;  ///< position of node (0, 0), metres
    double dx = 0, dy = 0;  ///< node spacing, metres
    /// Per node (row-major, as grid.points): 1 where the data have none
    /// (nodata = "mask"), else 0; empty when every node has data. Masked nodes
    /// still hold finite heights, filled from their neighbours, so that the
    /// refiner's stencils read no NaN; the mesh leaves them out and sample()
    /// does not read them.
    std::vector<std::uint8_t> masked;

    int rows() const { return grid.rows; }
    int cols() const { return grid.cols; }
    double xMax() const { return x0 + (grid.cols - 1) * dx; }
    double yMax() const { return y0 + (grid.rows - 1) * dy; }
    bool isMasked(int r, int c) const {
        return !masked.empty() && masked[static_cast<size_t>(r) * grid.cols + c] != 0;
    }
    size_t maskedCount() const;
    /// A whole node index computed in double (e.g. ceil((x - x0) / dx)) as an
    /// int within [-1, n]: a coordinate far off the grid (or NaN) stays one.
    static int indexWithin(double v, int n) { return !(v >= -1) ? -1 : v > n ? n : static_cast<int>(v); }

    /// Height at (x, y) in the frame by bilinear interpolation between the
    /// four surrounding nodes; nullopt outside the lattice or where one of
    /// those nodes is masked.
    std::optional<double> sample(double x, double y) const;

    /// The same extent and frame with new nodes: `nodes` refines this grid's
    /// nodes by `factor` along each axis (arity^depth), so the spacing shrinks
    /// by that factor and the origin stays. A refined node is masked when a
    /// control node of the cell (or edge) it lies in is masked, so the holes
    /// keep the control net's outline.
    GeoGrid refined(Grid nodes, double factor) const;
};

}  // namespace relief::geo
