#pragma once
// What a geometry check in `relief test` compares: a surface's profiles along
// geodesics (distance, elevation) and its contour lines at given elevations
// (x, y in its frame), kept beside a case's reference images, and the exact
// Hausdorff distance between a new surface's curves and those kept.
#include <optional>
#include <string>
#include <vector>

#include "core/diagnostics.h"
#include "curves/bezier.h"
#include "geo/geo_grid.h"
#include "measure/compare_geometry.h"

namespace relief::measure {

struct SurfaceCurves {
    std::string frame;  ///< the frame the contour lines are in (Frame::describe)
    struct Profile {
        std::string name;                   ///< "LON,LAT:LON,LAT", as the manifest gives it
        std::vector<curves::Point2> points;  ///< (distance along the geodesic, elevation), metres
    };
    struct Level {
        double level = 0;
        std::vector<std::vector<curves::Point2>> lines;  ///< polylines in the frame
    };
    std::vector<Profile> profiles;
    std::vector<Level> levels;
};

/// The curves of `refined` along `profiles` (`samples` points each, bilinear)
/// and at `levels` (GDAL's contours). Nullopt, after an error at `at`, when a
/// profile leaves the surface.
std::optional<SurfaceCurves> surfaceCurves(const geo::GeoGrid& refined, const std::vector<ProfileLine>& profiles,
                                           const std::vector<double>& levels, int samples, const SourceLoc& at,
                                           Diagnostics& diags);

/// How far one curve (or set of curves) moved: the exact Hausdorff distance,
/// where it is reached on the new curve and its nearest point on the kept one.
struct CurveMove {
    double distanceM = 0;
    curves::Point2 witness, foot;
    bool witnessOnNew = true;
};
CurveMove profileMove(const std::vector<curves::Point2>& now, const std::vector<curves::Point2>& kept);
CurveMove levelMove(const std::vector<std::vector<curves::Point2>>& now,
                    const std::vector<std::vector<curves::Point2>>& kept);

}  // namespace relief::measure
