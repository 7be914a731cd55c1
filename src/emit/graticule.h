#pragma once
// Stage 4, [overlay] graticule: lines of longitude and latitude lying on the
// terrain's surface as ribbons (surface_ribbons.h), every `step` degrees over
// the terrain's extent, each with its label text ("174°46′E"); where on the
// still a line's label goes is the composition's to say (it needs the view).

#include <string>
#include <vector>

#include "emit/surface_ribbons.h"
#include "geo/geo_grid.h"
#include "scene/scene_spec.h"

namespace relief::emit {

struct GraticuleLine {
    bool meridian = true;            ///< a line of longitude (else of latitude)
    double valueDeg = 0;
    std::string label;               ///< "174°46′E", "36°52′S"
    std::vector<curves::Point2> frame;  ///< its points in the frame, metres, where the frame reaches
};

struct Graticule {
    double stepDeg = 0;
    std::vector<GraticuleLine> lines;
    Ribbons ribbons;
};

/// At most this many lines: more would be a grey wash, not a graticule.
inline constexpr int kMaxGraticuleLines = 200;

/// The step "auto" takes over a span of `spanDeg`: the finest of 1, 2, 5 x
/// 10^k degrees and 1, 2, 5, 10, 15, 30 minutes and seconds giving at most
/// five lines over it.
double graticuleStepDeg(double spanDeg);

/// A line's label: degrees, then minutes and seconds when the step needs
/// them (decimal degrees below a second), and the hemisphere.
std::string graticuleLabel(double valueDeg, bool meridian, double stepDeg);

/// The terrain's longitudes and latitudes (its refined grid's edges carried
/// back to WGS84): west, south, east, north.
LonLatBox terrainLonLatBox(const geo::GeoGrid& refined);

/// The graticule over `refined`: how many lines `spec` gives (lines() before
/// building, to check the limit), and the lines as ribbons `widthM` wide.
int graticuleLineCount(const scene::GraticuleSpec& spec, const LonLatBox& box);
Graticule buildGraticule(const scene::GraticuleSpec& spec, const LonLatBox& box, const geo::GeoGrid& refined,
                         const ScenePlacement& where, double widthM);

}  // namespace relief::emit
