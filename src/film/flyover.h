#pragma once
// A flyover's cameras: the eye along a smooth path through the given points
// at constant ground speed, at the points' own heights or a height above the
// ground under it, looking at the ground ahead or at a fixed point. Input:
// the points in the terrain's frame (metres) and the refined surface; output:
// an eye and a target a frame. Plain geometry: the caller names the keys.
#include <optional>
#include <span>
#include <vector>

#include "core/types.h"
#include "geo/geo_grid.h"

namespace relief::film {

/// Points on the centripetal Catmull-Rom spline through `points` (alpha =
/// 1/2: no cusp or loop within a segment, and no overshoot at sharp turns;
/// Yuksel, Schaefer and Keyser 2011): segment i from points[i] towards
/// points[i + 1] in perSegment[i] steps, then the last point. The ends are
/// extended by mirroring their neighbour. Needs two points or more, no two in
/// a row the same.
std::vector<Vec3> centripetalCatmullRom(std::span<const Vec3> points, std::span<const int> perSegment);

/// The rendered surface under a flyover: heights of the refined grid.
class Ground {
public:
    explicit Ground(const geo::GeoGrid& grid) : grid_(grid) {}
    bool covers(double x, double y) const;
    /// Bilinear between the cell's four nodes; outside, at the nearest edge.
    double heightAt(double x, double y) const;
    /// The highest of the cell's four nodes: no triangle of the cell is above it.
    double highestAt(double x, double y) const;
    double spacing() const { return std::min(grid_.dx, grid_.dy); }
    double diagonal() const;

private:
    struct Cell {
        int r, c;
        double fx, fy;
    };
    Cell cellAt(double x, double y) const;
    const geo::GeoGrid& grid_;
};

struct FlyoverPath {
    std::vector<Vec3> points;            ///< frame metres; z the eye's height (frame z) unless aboveGroundM
    std::optional<double> aboveGroundM;  ///< set: the eye this far above the ground, points' z unused
    std::optional<double> lookAheadM;    ///< unset: max(ground length / 10, 4 x the eye's mean height above ground)
    std::optional<Vec3> lookAtM;         ///< set: every frame looks here
};

struct FlyoverCamera {
    Vec3 eyeM, targetM;
};

/// The cameras of `frames` frames (both ends of the path included) at equal
/// steps of ground distance. Above the ground, the eye's height is
/// aboveGroundM over the highest ground (highestAt) within that distance along the path
/// (before and after), so that it rises before a ridge and never dips into a
/// gully's far side. Looking ahead, the target is the ground at look-ahead
/// distance along the path (past its end, straight on).
std::vector<FlyoverCamera> flyoverCameras(const FlyoverPath& path, int frames, const Ground& ground);

}  // namespace relief::film
