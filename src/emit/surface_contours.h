#pragma once
// Stage 4, contour lines on the terrain ([overlay] contours): GDAL's contours
// of the refined surface drawn as thin ribbons lying on it, so that ridges
// hide them as they hide the ground, every n-th (an index contour) heavier.

#include <array>
#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include "emit/mesh.h"
#include "emit/surface_ribbons.h"
#include "geo/geo_grid.h"
#include "scene/scene_spec.h"

namespace relief::emit {

struct SurfaceContours {
    int levels = 0;
    long long lines = 0, points = 0;
};

struct ContourRibbons {
    SurfaceContours made;
    Ribbons ribbons;
};

/// The contour lines of `refined` at every multiple of spec.intervalM within
/// the surface's range (GDAL), each as a ribbon lying on the surface (its
/// edges' heights sampled from it, lifted a fifth of its width), `widthM` wide
/// (index contours twice that). Nodes without data have none. Nullopt when
/// GDAL fails, with the error at `at` (overlay.contours).
std::optional<ContourRibbons> buildSurfaceContours(const geo::GeoGrid& refined, const ScenePlacement& where,
                                                   const scene::ContourSpec& spec, double widthM, const SourceLoc& at,
                                                   Diagnostics& diags);

/// Writes the ribbons as one mesh2, unshadowed, in spec.colour.
void writeSurfaceContours(std::FILE* out, const ContourRibbons& ribbons, const scene::ContourSpec& spec);

/// How many levels spec gives over the surface's range.
int contourLevelCount(const ScenePlacement& where, const scene::ContourSpec& spec);

}  // namespace relief::emit
