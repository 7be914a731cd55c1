#include "plot/svg.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "core/text_escape.h"

namespace relief::plot {

namespace {

constexpr const char* kColors[] = {"#d62728", "#1f77b4", "#2ca02c", "#9467bd",
                                   "#ff7f0e", "#8c564b", "#e377c2", "#17becf"};

}  // namespace

std::string plotSvg(const std::string& title, const std::vector<SvgLayer>& layers,
                    const std::vector<SvgMarker>& markers, const SvgAxes& axes) {
    curves::Bounds2 bounds;
    for (const auto& layer : layers)
        for (const auto& c : layer.lines)
            for (const auto& p : c.points) bounds.add(p);
    if (bounds.empty()) bounds = {0, 0, 1, 1};
    const double xmin = bounds.xmin, xmax = bounds.xmax, ymin = bounds.ymin, ymax = bounds.ymax;
    const double ve = axes.verticalExaggeration;
    const double span = std::max({xmax - xmin, (ymax - ymin) * ve, 1e-12});
    const double margin = axes.show ? 70 : 20, plotW = axes.show ? 700 : 760, titleH = 30;
    const double scale = plotW / span;  // one scale for x and y (times ve): equal axes
    const double plotH = std::max((ymax - ymin) * ve * scale, axes.show ? 60.0 : 0.0);
    const double legendH = 20.0 * static_cast<double>(layers.size()) + 10;
    const double width = plotW + 2 * margin, height = titleH + plotH + 2 * margin + legendH;
    auto X = [&](double x) { return margin + (x - xmin) * scale; };
    auto Y = [&](double y) { return titleH + margin + (ymax - y) * ve * scale; };
    auto path = [&](const SvgCurve& c) {
        std::string d;
        for (size_t i = 0; i < c.points.size(); ++i)
            d += fmt::format("{}{:.3f},{:.3f}", i ? " L" : "M", X(c.points[i].x), Y(c.points[i].y));
        if (c.closed) d += " Z";
        return d;
    };

    std::string s = fmt::format(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{:.0f}\" height=\"{:.0f}\" "
        "viewBox=\"0 0 {:.0f} {:.0f}\" font-family=\"sans-serif\" font-size=\"14\">\n"
        "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n"
        "<text x=\"{}\" y=\"20\" font-size=\"16\">{}</text>\n",
        width, height, width, height, margin, markupText(title));
    if (axes.show) {
        // Ticks at 1, 2 or 5 times a power of ten, about five per axis.
        auto step = [](double range) {
            const double raw = range / 5, p = std::pow(10.0, std::floor(std::log10(raw)));
            return raw / p < 2 ? p : raw / p < 5 ? 2 * p : 5 * p;
        };
        // Map coordinates (UTM eastings, northings) in full, not as 5.53e+06.
        auto tick = [](double v) { return std::fabs(v) >= 1e5 ? fmt::format("{:.0f}", v) : fmt::format("{:g}", v); };
        const double x0 = X(xmin), x1 = X(xmax), y0 = Y(ymin), y1 = Y(ymax);
        s += fmt::format("<path d=\"M{0:.1f},{1:.1f} L{2:.1f},{1:.1f} M{0:.1f},{1:.1f} L{0:.1f},{3:.1f}\" "
                         "stroke=\"#000\" fill=\"none\"/>\n", x0, y0 + 5, x1, y1 - 5);
        const double sx = step(std::max(xmax - xmin, 1e-12)), sy = step(std::max(ymax - ymin, 1e-12));
        for (double v = std::ceil(xmin / sx) * sx; v <= xmax + 1e-9 * sx; v += sx)
            s += fmt::format("<line x1=\"{0:.1f}\" y1=\"{1:.1f}\" x2=\"{0:.1f}\" y2=\"{2:.1f}\" stroke=\"#000\"/>"
                             "<text x=\"{0:.1f}\" y=\"{3:.1f}\" text-anchor=\"middle\" font-size=\"11\">{4}</text>\n",
                             X(v), y0 + 5, y0 + 10, y0 + 24, tick(v));
        for (double v = std::ceil(ymin / sy) * sy; v <= ymax + 1e-9 * sy; v += sy)
            s += fmt::format("<line x1=\"{0:.1f}\" y1=\"{1:.1f}\" x2=\"{2:.1f}\" y2=\"{1:.1f}\" stroke=\"#000\"/>"
                             "<text x=\"{3:.1f}\" y=\"{4:.1f}\" text-anchor=\"end\" font-size=\"11\">{5}</text>\n",
                             x0 - 5, Y(v), x0, x0 - 8, Y(v) + 4, tick(v));
        s += fmt::format("<text x=\"{:.1f}\" y=\"{:.1f}\" text-anchor=\"middle\">{}</text>\n", 0.5 * (x0 + x1),
                         y0 + 42, markupText(axes.xLabel));
        s += fmt::format("<text x=\"14\" y=\"{:.1f}\" transform=\"rotate(-90 14 {:.1f})\" "
                         "text-anchor=\"middle\">{}</text>\n",
                         0.5 * (y0 + y1), 0.5 * (y0 + y1), markupText(axes.yLabel));
    }
    // Layers, then markers, then the legend.
    std::vector<std::string> colours;
    size_t next = 0;
    for (const auto& layer : layers) {
        const std::string colour = layer.colour.empty() ? kColors[next++ % 8] : layer.colour;
        colours.push_back(colour);
        const std::string style = layer.dashed ? "stroke-width=\"1.2\" stroke-dasharray=\"5,4\""
                                               : "stroke-width=\"2\"";
        for (const auto& c : layer.lines) {
            s += fmt::format("<path d=\"{}\" fill=\"none\" stroke=\"{}\" {}/>\n", path(c), colour, style);
            if (layer.vertices)
                for (const auto& p : c.points)
                    s += fmt::format("<circle cx=\"{:.3f}\" cy=\"{:.3f}\" r=\"3.5\" fill=\"#444\"/>\n", X(p.x), Y(p.y));
        }
    }
    for (const auto& m : markers) {
        s += fmt::format("<line x1=\"{:.3f}\" y1=\"{:.3f}\" x2=\"{:.3f}\" y2=\"{:.3f}\" stroke=\"#000\" "
                         "stroke-width=\"2.5\"/><circle cx=\"{:.3f}\" cy=\"{:.3f}\" r=\"5\" fill=\"none\" "
                         "stroke=\"#000\" stroke-width=\"2\"/>\n",
                         X(m.from.x), Y(m.from.y), X(m.to.x), Y(m.to.y), X(m.from.x), Y(m.from.y));
        const bool right = X(m.from.x) > margin + 0.6 * plotW;  // keep the label inside the plot
        s += fmt::format("<text x=\"{:.1f}\" y=\"{:.1f}\" text-anchor=\"{}\" font-size=\"12\" stroke=\"white\" "
                         "stroke-width=\"3\" paint-order=\"stroke\">{}</text>\n",
                         X(m.from.x) + (right ? -8 : 8), Y(m.from.y) - 8, right ? "end" : "start", markupText(m.label));
    }
    double ly = titleH + plotH + 2 * margin + (axes.show ? 0 : 10);
    for (size_t i = 0; i < layers.size(); ++i, ly += 20)
        s += fmt::format("<line x1=\"{0}\" y1=\"{1}\" x2=\"{2}\" y2=\"{1}\" stroke=\"{3}\" {4}/>"
                         "<text x=\"{5}\" y=\"{6}\">{7}</text>\n",
                         margin, ly, margin + 30, colours[i],
                         layers[i].dashed ? "stroke-dasharray=\"5,4\"" : "stroke-width=\"2\"", margin + 40,
                         ly + 5, markupText(layers[i].label));
    s += "</svg>\n";
    return s;
}

std::string curvesSvg(const std::string& title, const SvgCurve& control,
                      const std::vector<SvgCurve>& curves, const SvgAxes& axes) {
    std::vector<SvgLayer> layers{{control.label, {control}, "#888", true, !axes.show}};
    for (const auto& c : curves) layers.push_back({c.label, {c}, "", false, false});
    return plotSvg(title, layers, {}, axes);
}

}  // namespace relief::plot
