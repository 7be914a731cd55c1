#pragma once
// How far two surfaces are apart, in metres and where: the exact Hausdorff
// distance (src/curves) between matching profiles along geodesics and between
// the contour lines at the same elevations. Used by `relief compare-geometry`
// to show how much two parameter sets, or two versions, move the terrain.
#include <optional>
#include <string>
#include <vector>

#include "core/diagnostics.h"
#include "curves/hausdorff.h"
#include "geo/normalize.h"
#include "geo/contours.h"

namespace relief::measure {

/// One refined surface (its grid carries its frame), named for messages.
struct FramedSurface {
    std::string name;  ///< "a", or the scene file
    const geo::GeoGrid* grid = nullptr;
    const geo::Frame& frame() const { return grid->frame; }
};

/// A geodesic between two points, WGS84 degrees.
struct ProfileLine {
    std::string name;
    GeoPoint from, to;  ///< heights unused
};

/// Where a Hausdorff distance is reached: the witness point (on the surface
/// named by `onA`) and its nearest point on the other.
struct Where {
    bool onA = true;
    double latDeg = 0, lonDeg = 0;
    curves::Point2 point, foot;  ///< contours: x, y in a's frame; profiles: distance, elevation
};

struct ProfileComparison {
    ProfileLine line;
    double lengthM = 0;
    std::vector<curves::Point2> a, b;  ///< (distance along the geodesic, elevation), metres
    std::vector<curves::Point2> path;  ///< the geodesic in a's frame (x, y), for maps
    curves::HausdorffResult h;         ///< in the (distance, elevation) plane
    Where where;
};

struct ContourComparison {
    double level = 0;
    size_t linesA = 0, linesB = 0;
    curves::CurveSet a, b;  ///< the lines compared: in a's frame, clipped to the common area
    curves::HausdorffResult h;  ///< in a's frame; infinite when one side has no line
    Where where;
};

struct GeometryComparison {
    std::vector<ProfileComparison> profiles;
    std::vector<ContourComparison> contours;
};

/// West-east and south-north geodesics through the centre of the area both
/// surfaces cover (inset by 1 % of it); empty when they do not overlap.
std::vector<ProfileLine> defaultProfiles(const FramedSurface& a, const FramedSurface& b);

/// About five round elevations inside the range both surfaces reach.
std::vector<double> defaultLevels(const FramedSurface& a, const FramedSurface& b);

/// Profiles sampled at `samples` points (bilinear on each lattice) and
/// contours at `levels`, b's contours carried into a's frame through
/// geographic coordinates when the frames differ, both clipped to the area
/// both surfaces cover. A profile leaving either surface is an error naming it.
std::optional<GeometryComparison> compareGeometry(const FramedSurface& a, const FramedSurface& b,
                                                  const std::vector<ProfileLine>& profiles,
                                                  const std::vector<double>& levels, int samples,
                                                  Diagnostics& diags);

/// "1.234 m", "12.35 km" (from 10 km), or "infinite".
std::string formatDistance(double m);

/// A map (SVG) of a comparison: both surfaces' contour lines in a's frame
/// (one colour per level, a solid, b dashed), the profiles, and a marker from
/// each level's witness to its nearest point on the other surface.
std::string comparisonMapSvg(const GeometryComparison& comparison, const std::string& nameA,
                             const std::string& nameB, const std::string& frame);

}  // namespace relief::measure
