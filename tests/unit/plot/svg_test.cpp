// The SVG plot writer: layers, markers and equal axes.
#include <gtest/gtest.h>

#include <string>

#include "plot/svg.h"

namespace relief::plot {
namespace {

// A map: two layers (solid and dashed, own colours), a marker with its label,
// equal axes (a 100 x 50 m box is twice as wide as high), full map ticks.
TEST(Svg, PlotLayersMarkersAndEqualAxes) {
    const SvgLayer a{"a", {{"", {{500000, 6000000}, {500100, 6000000}}, false}}, "#1f77b4"};
    const SvgLayer b{"b", {{"", {{500000, 6000050}, {500100, 6000050}}, false}}, "#d62728", true};
    const std::string svg = plotSvg("t", {a, b}, {{{500050, 6000050}, {500050, 6000000}, "H = 50 m"}},
                                    {true, 1, "x", "y"});
    auto count = [&](const std::string& what) {
        size_t n = 0;
        for (size_t at = svg.find(what); at != std::string::npos; at = svg.find(what, at + 1)) ++n;
        return n;
    };
    EXPECT_EQ(count("<path d=\"M"), 3u);  // two lines and the axes
    EXPECT_EQ(count("stroke=\"#d62728\" stroke-width=\"1.2\" stroke-dasharray"), 1u);
    EXPECT_NE(svg.find(">H = 50 m</text>"), std::string::npos);
    EXPECT_NE(svg.find(">6000000</text>"), std::string::npos);  // not 6e+06
    // Plot 700 px wide for 100 m: 7 px per metre both ways, so b is 350 px above a.
    EXPECT_NE(svg.find("M70.000,450.000 L770.000,450.000"), std::string::npos) << svg;
    EXPECT_NE(svg.find("M70.000,100.000 L770.000,100.000"), std::string::npos);
}

}  // namespace
}  // namespace relief::plot
