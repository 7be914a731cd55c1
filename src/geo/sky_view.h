#pragma once
// The sky-view factor of a grid's nodes: the share of the sky hemisphere a
// node sees above its horizon (Zakšek, Oštir and Kokalj 2011, "Sky-View
// Factor as a Relief Visualization Technique", Remote Sensing 3(2)). Flat open
// ground sees all of it (1); the floor of a gully or a pit sees less. Light
// from a uniform sky falls on a node in that proportion, which is why it reads
// as the soft light of an overcast day and shows ridges and gullies that a
// single sun leaves flat.
#include <vector>

#include "geo/geo_grid.h"

namespace relief::geo {

struct SkyViewOptions {
    int directions = 16;  ///< azimuths searched for the horizon, evenly spaced
    double radiusM = 0;   ///< how far the horizon is searched for; <= 0: kDefaultRadiusShare of the extent
    int threads = 0;      ///< <= 0: every core (the result does not depend on it)
};

/// The default search radius as a share of the grid's larger side: the light
/// of a still shows the valleys and ridges of its own scale, not a mountain's
/// shadow on the plain beyond it (which is the sun's work).
inline constexpr double kDefaultRadiusShare = 1.0 / 40;

/// The radius `options` asks for, in metres: radiusM, or the default, at least
/// four node spacings.
double skyViewRadiusM(const GeoGrid& grid, const SkyViewOptions& options);

/// Per node (row-major, as grid.points): 1 - (1/n) sum_i sin(max(0, h_i)),
/// h_i the elevation angle of the horizon along the i-th of n azimuths,
/// searched out to the radius at distances of one node spacing for the first
/// eight, then each a fifth further than the one before. Heights between
/// nodes are bilinear. The grid's edge and nodes without data hide no sky;
/// a masked node gets 1.
std::vector<float> skyViewFactor(const GeoGrid& grid, const SkyViewOptions& options);

}  // namespace relief::geo
