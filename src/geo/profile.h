#pragma once
// Terrain profiles: the surface cut along the geodesic between two points.
#include <optional>
#include <vector>

#include "core/diagnostics.h"
#include "core/types.h"
#include "geo/normalize.h"

namespace relief::geo {

struct ProfilePoint {
    double distanceM;  ///< along the geodesic from the start
    double latDeg, lonDeg;
    double x, y;       ///< in the net's frame, metres
};

/// `count` points (>= 2) equally spaced along the WGS84 geodesic from
/// (lat1, lon1) to (lat2, lon2) (GeographicLib Geodesic / GeodesicLine),
/// projected into the frame.
std::vector<ProfilePoint> geodesicProfile(const Frame& frame, double lat1, double lon1, double lat2,
                                          double lon2, int count);

/// Height of a regular lattice (node (r, c) at x0 + c dx, y0 + r dy) at (x, y)
/// by bilinear interpolation; nullopt outside it.
std::optional<double> sampleLattice(const Grid& grid, double x0, double y0, double dx, double dy,
                                    double x, double y);

}  // namespace relief::geo
