#pragma once
// The one georeferenced grid of relief: a regular lattice of nodes in a
// projected frame (metres, x = east, y = north, z = up). Normalization makes
// one (the control net), refinement makes a finer one over the same extent, and
// emit, profiles, contours, compare-geometry and automatic depth read them.
#include <optional>
#include <string>

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
    std::string describe() const;  ///< e.g. "UTM zone 60S" or "local tangent plane at ..."
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

    int rows() const { return grid.rows; }
    int cols() const { return grid.cols; }
    double xMax() const { return x0 + (grid.cols - 1) * dx; }
    double yMax() const { return y0 + (grid.rows - 1) * dy; }

    /// Height at (x, y) in the frame by bilinear interpolation between the
    /// four surrounding nodes; nullopt outside the lattice.
    std::optional<double> sample(double x, double y) const;

    /// The same extent and frame with new nodes: `nodes` refines this grid's
    /// nodes by `factor` along each axis (arity^depth), so the spacing shrinks
    /// by that factor and the origin stays.
    GeoGrid refined(Grid nodes, double factor) const;
};

}  // namespace relief::geo
