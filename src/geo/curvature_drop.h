#pragma once
// In a local tangent-plane frame the Earth's surface falls away from the
// plane with distance (about d^2 / 2R: 0.8 m at 3 km, 20 km at 500 km), and a
// grid's heights there include that fall. Drawing the terrain, relief
// exaggerates heights above the ellipsoid, not the curvature, and colours by
// elevation: this is the fall at any (x, y) of a frame. In UTM it is zero.
#include <vector>

#include "geo/geo_grid.h"

namespace relief::geo {

class CurvatureDrop {
public:
    /// The fall over the box [x0, x1] x [y0, y1] of `frame`, exact (GeographicLib)
    /// at kSamples x kSamples points and bilinear between them (the fall is
    /// quadratic: the bilinear error is under 1.2 m across 2,000 km).
    CurvatureDrop(const Frame& frame, double x0, double y0, double x1, double y1);

    /// The ellipsoid's height above the frame's tangent plane below (x, y),
    /// metres (negative away from the tangent point); 0 for UTM.
    double at(double x, double y) const;

private:
    static constexpr int kSamples = 257;
    bool none_ = true;
    double x0_ = 0, y0_ = 0, stepX_ = 1, stepY_ = 1;
    std::vector<double> fall_;  ///< kSamples x kSamples, row-major from (x0, y0)
};

}  // namespace relief::geo
