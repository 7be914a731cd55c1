#pragma once
// Figures as SVG, equal axes: curves (a control polygon and refined curves),
// profiles, and maps of contour lines.
#include <string>
#include <vector>

#include "curves/curve_file.h"

namespace relief::plot {

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

/// A legend entry and its lines, drawn alike.
struct SvgLayer {
    std::string label;
    std::vector<SvgCurve> lines;
    std::string colour;     ///< "" = the next colour of the palette
    bool dashed = false;
    bool vertices = false;  ///< dots at the points
};

/// A labelled segment drawn over the layers (e.g. where a distance is reached).
struct SvgMarker {
    curves::Point2 from, to;
    std::string label;
};

/// An SVG (800 px wide): the layers in order, the markers, and a legend;
/// x and y share one scale (times the vertical exaggeration). y points up.
std::string plotSvg(const std::string& title, const std::vector<SvgLayer>& layers,
                    const std::vector<SvgMarker>& markers = {}, const SvgAxes& axes = {});

/// The control polygon (grey, dashed, with its vertices) and each curve in
/// its own colour: plotSvg with one layer per curve.
std::string curvesSvg(const std::string& title, const SvgCurve& control,
                      const std::vector<SvgCurve>& curves, const SvgAxes& axes = {});

}  // namespace relief::plot
