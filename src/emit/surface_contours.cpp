#include "emit/surface_contours.h"

#include <cmath>
#include <memory>
#include <vector>

#include <fmt/format.h>

#include "core/number_format.h"
#include "geo/contours.h"

namespace relief::emit {

namespace {

std::vector<double> levelsOf(const ScenePlacement& where, const scene::ContourSpec& spec) {
    std::vector<double> levels;
    for (double k = std::ceil(where.zMinM / spec.intervalM); k * spec.intervalM <= where.zMaxM && levels.size() < 100000;
         ++k)
        levels.push_back(k * spec.intervalM);
    return levels;
}

}  // namespace

int contourLevelCount(const ScenePlacement& where, const scene::ContourSpec& spec) {
    return static_cast<int>(levelsOf(where, spec).size());
}

std::optional<ContourRibbons> buildSurfaceContours(const geo::GeoGrid& refined, const ScenePlacement& where,
                                                   const scene::ContourSpec& spec, double widthM, const SourceLoc& at,
                                                   Diagnostics& diags) {
    ContourRibbons contours;
    SurfaceContours& made = contours.made;
    const std::vector<double> levels = levelsOf(where, spec);
    made.levels = static_cast<int>(levels.size());
    if (levels.empty()) return contours;
    std::string error;
    const auto lines = geo::contourLines(refined, levels, error);
    if (!error.empty()) {
        diags.error(at, "overlay.contours: GDAL: " + error);
        return std::nullopt;
    }
    for (size_t li = 0; li < lines.size(); ++li) {
        const long long index = std::llround(levels[li] / spec.intervalM);
        const bool heavy = spec.indexEvery > 0 && index % spec.indexEvery == 0;
        const double width = widthM * (heavy ? 2 : 1);
        // GDAL traces a point at every cell a line crosses, several a pixel: simplified to a
        // quarter of the line's width, which no pixel shows; pieces at most six widths long.
        const RibbonStyle style{width, 0.25 * widthM, 6 * widthM};
        for (const curves::PiecewiseBezier& line : lines[li]) {
            std::vector<curves::Point2> traced;
            for (const auto& seg : line.segments) traced.insert(traced.end(), seg.control.begin(), seg.control.end());
            addRibbon(contours.ribbons, refined, where, traced, style);
        }
    }
    made.lines = contours.ribbons.lines;
    made.points = contours.ribbons.points;
    return contours;
}

void writeSurfaceContours(std::FILE* out, const ContourRibbons& contours, const scene::ContourSpec& spec) {
    writeRibbons(out, contours.ribbons, spec.colour,
                 fmt::format("Contour lines every {} m ([overlay] contours), lying on the surface.",
                             formatShortest(spec.intervalM)));
}

}  // namespace relief::emit
