#pragma once
// Curve figures as SVG: a control polygon and refined curves, equal axes.
#include <string>
#include <vector>

#include "curves/curve_file.h"

namespace relief::emit {

struct SvgCurve {
    std::string label;
    std::vector<curves::Point2> points;
    bool closed = false;
};

/// Plot options: axes with ticks in data units, and a vertical exaggeration
/// for profiles (y drawn `verticalExaggeration` times the x scale).
struct SvgAxes {
    bool show = false;
    double verticalExaggeration = 1;
    std::string xLabel, yLabel;
};

/// An SVG (800 px wide) with the control polygon (grey, dashed, with its
/// vertices), each curve in its own colour, and a legend; x and y share one
/// scale. y points up, as in the data.
std::string curvesSvg(const std::string& title, const SvgCurve& control,
                      const std::vector<SvgCurve>& curves, const SvgAxes& axes = {});

}  // namespace relief::emit
