#pragma once
// `relief profile`: a refined surface and its control net cut along the WGS84
// geodesic between two points, as curves (distance along it, elevation; metres)
// and as a figure.
#include <optional>
#include <string>
#include <vector>

#include "core/diagnostics.h"
#include "curves/curve_file.h"
#include "geo/geo_grid.h"
#include "geo/profile.h"

namespace relief::measure {

struct SurfaceProfile {
    std::vector<geo::ProfilePoint> line;  ///< the geodesic's points, in the net's frame
    curves::CurveFile refined, control;   ///< open polylines (distance, elevation)
    double lengthM = 0;
    double zMinM = 0, zMaxM = 0;          ///< of the refined surface along the line
};

/// `samples` points (>= 2) from `from` to `to` (their heights unused);
/// heights bilinear on each grid (both in the net's frame). A line leaving the
/// net is an error at `where` naming the point and the net's extent.
std::optional<SurfaceProfile> cutProfile(const geo::GeoGrid& net, const geo::GeoGrid& refined, const GeoPoint& from,
                                         const GeoPoint& to, int samples, const SourceLoc& where, Diagnostics& diags);

/// The profile as an SVG with axes in metres: the control net (bilinear)
/// and the refined surface (`refinedLabel`). `exaggeration` <= 0 chooses one
/// that makes the relief about a third of the length; the one used is returned
/// in `used`.
std::string profileSvg(const SurfaceProfile& profile, const std::string& sceneName,
                       const std::string& refinedLabel, double exaggeration, double& used);

}  // namespace relief::measure
