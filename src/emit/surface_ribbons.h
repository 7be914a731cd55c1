#pragma once
// Stage 4: lines lying on the terrain's surface (contour lines, a layer's
// tracks and outlines, the graticule) as thin ribbons: two vertices across
// each point, their heights sampled from the refined surface and lifted a
// little, so that ridges hide them as they hide the ground, and a line is cut
// where the surface has no data.

#include <array>
#include <cstdint>
#include <cstdio>
#include <span>
#include <string_view>
#include <vector>

#include "core/types.h"
#include "curves/bezier.h"
#include "emit/mesh.h"
#include "geo/geo_grid.h"

namespace relief::emit {

/// Ribbons: two vertices a point of a line (scene units), two triangles
/// between consecutive points.
struct Ribbons {
    std::vector<SceneVec3> vertices;
    std::vector<std::array<std::uint32_t, 3>> faces;
    long long lines = 0, points = 0;  ///< lines with a ribbon, points on them
    /// The SDL they will take, in bytes (about 30 a vertex, 20 a face).
    double sdlBytes() const { return 30.0 * vertices.size() + 20.0 * faces.size(); }
};

struct RibbonStyle {
    double widthM = 1;                 ///< across, in frame metres
    double simplifyM = 0;              ///< Douglas-Peucker (GEOS) tolerance first; 0: none
    double longestM = 1e300;           ///< then no piece longer: each end on the surface
    std::array<double, 2> dashM{0, 0};  ///< drawn, left out, along the line; {0, 0}: solid
};

/// Adds `line` (frame metres, x east, y north) as a ribbon on `refined`.
void addRibbon(Ribbons& out, const geo::GeoGrid& refined, const ScenePlacement& where,
               std::span<const curves::Point2> line, const RibbonStyle& style);

/// Writes the ribbons as one mesh2 in `colour`, unshadowed, after a comment line.
void writeRibbons(std::FILE* out, const Ribbons& ribbons, const LinearRgb& colour, std::string_view comment);

}  // namespace relief::emit
