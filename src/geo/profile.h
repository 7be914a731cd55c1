#pragma once
// Terrain profiles: the surface cut along the geodesic between two points.
#include <optional>
#include <vector>

#include "core/diagnostics.h"
#include "core/types.h"
#include "geo/geo_grid.h"
#include "geo/normalize.h"

namespace relief::geo {

struct ProfilePoint {
    double distanceM;  ///< along the geodesic from the start
    double latDeg, lonDeg;
    double x, y;       ///< in the net's frame, metres
};

/// `count` points (>= 2) equally spaced along the WGS84 geodesic from `from`
/// to `to` (GeographicLib Geodesic / GeodesicLine; their heights unused),
/// projected into the frame.
std::vector<ProfilePoint> geodesicProfile(const Frame& frame, const GeoPoint& from, const GeoPoint& to, int count);

/// The heights of `grid` at each point of `profile` (bilinear, GeoGrid::sample),
/// the profile already in the grid's frame. nullopt when a point is outside
/// the grid; `outside` is then its index.
std::optional<std::vector<double>> heightsAlong(const GeoGrid& grid,
                                                const std::vector<ProfilePoint>& profile,
                                                size_t& outside);

}  // namespace relief::geo
