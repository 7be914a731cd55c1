#pragma once
// `relief curve`: a 2-D control polygon refined with one or more parameter
// sets of a scheme, drawn in one figure, like the curve figures of the source
// papers.
#include <optional>
#include <string>
#include <vector>

#include "core/diagnostics.h"
#include "curves/curve_file.h"
#include "scene/scene_spec.h"

namespace relief::figures {

/// One curve of the figure: a scheme spec and its label ("" = the scheme's
/// family and every parameter).
struct CurveVariant {
    std::string label;
    scene::SchemeSpec scheme;
};

struct CurveFigure {
    std::string svg;                        ///< the control polygon and every refined curve
    std::vector<curves::CurveFile> refined; ///< one per variant, in order
};

/// The most points a refined curve may have (each is SVG text and a point of
/// the curve file): 1e7, some 300 MB of SVG.
inline constexpr double kMaxCurvePoints = 1e7;

/// Refines `polygon` (a polyline, open or closed) `depth` times with each
/// variant's scheme. Reports (at `polygonName`) a polygon that is not a
/// polyline or too short for a scheme, a refinement beyond kMaxCurvePoints,
/// and every scheme problem at its key.
std::optional<CurveFigure> curveFigure(const curves::CurveFile& polygon, const std::string& polygonName,
                                       const std::vector<CurveVariant>& variants, int depth,
                                       const std::string& title, Diagnostics& diags);

}  // namespace relief::figures
