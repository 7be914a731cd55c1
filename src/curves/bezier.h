#pragma once
// Planar curves as sequences of Bézier segments, whatever the file type:
// a Bézier curve is one segment, a uniform cubic B-spline one cubic segment
// per knot interval, a polyline one linear segment per edge.
#include <vector>

#include "curves/curve_file.h"

namespace relief::curves {

struct Segment {
    std::vector<Point2> control;  ///< degree = size - 1 (0: a single point)
    double paramStart = 0;        ///< the file's parameter at t = 0 ...
    double paramEnd = 1;          ///< ... and at t = 1
};

struct PiecewiseBezier {
    std::vector<Segment> segments;
    bool closed = false;
};

/// Converts a curve file. bezier: t in [0, 1]; bspline3 (uniform, unit knot
/// spacing, not clamped): u in [0, n-3] open, [0, n) closed; polyline: the
/// vertex index.
PiecewiseBezier toBezier(const CurveFile& curve);

Point2 evaluate(const Segment& s, double t);
Point2 derivative(const Segment& s, double t);
/// Splits the control points at t (de Casteljau).
void split(const std::vector<Point2>& control, double t, std::vector<Point2>& left,
           std::vector<Point2>& right);

/// The largest distance between any two control points of the whole curve
/// (the curve's size, for relative tolerances).
double curveSize(const PiecewiseBezier& c);

}  // namespace relief::curves
