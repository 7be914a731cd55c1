#pragma once
// How much of the data's peak the rendered surface keeps: the highest sample
// (or, for a raster or a lattice, the net's highest node) against the refined
// surface's highest node within one net spacing of it. An approximating
// scheme's surface stays below the data's peaks; a fit (or net.fit) brings it
// back up. Reported for every scheme and gridding.
#include "core/types.h"
#include "geo/geo_grid.h"

namespace relief::measure {

struct PeakLoss {
    Vec3 peak;             ///< the data's highest point, frame metres
    Vec3 surfaceHighest;   ///< the surface's highest node near it
    double lossM = 0;      ///< peak.z - surfaceHighest.z: positive when the surface is lower
};

/// Within `radiusM` (horizontally) of `peak`; the surface's nodes without data are left out.
PeakLoss peakLoss(const Vec3& peak, const geo::GeoGrid& refined, double radiusM);

/// The net's highest node with data.
Vec3 highestNode(const geo::GeoGrid& net);

}  // namespace relief::measure
