#include "figures/curve_figure.h"

#include <cmath>

#include <fmt/format.h>

#include "core/number_format.h"
#include "plot/svg.h"
#include "subdiv/refine.h"
#include "subdiv/resolve.h"

namespace relief::figures {

std::optional<CurveFigure> curveFigure(const curves::CurveFile& polygon, const std::string& polygonName,
                                       const std::vector<CurveVariant>& variants, int depth,
                                       const std::string& title, Diagnostics& diags) {
    if (polygon.type != "polyline") {
        diags.error({polygonName, 0, 0},
                    fmt::format("relief curve refines a control polygon (\"type\": \"polyline\"), not a {}",
                                polygon.type));
        return std::nullopt;
    }
    std::vector<Vec3> control;
    for (const auto& p : polygon.points) control.push_back({p.x, p.y, 0});
    CurveFigure figure;
    std::vector<plot::SvgCurve> drawn;
    for (const CurveVariant& variant : variants) {
        const auto resolved = subdiv::resolveScheme(variant.scheme, diags);
        if (!resolved) return std::nullopt;
        if (!polygon.closed && static_cast<int>(control.size()) < subdiv::minPoints(resolved->scheme)) {
            diags.error({polygonName, 0, 0}, fmt::format("an open polygon needs at least {} points for {}",
                                                         subdiv::minPoints(resolved->scheme),
                                                         resolved->family));
            return std::nullopt;
        }
        // Counted before refining: a figure has no use for more points than a screen has pixels many times over.
        const double points = double(control.size()) * std::pow(double(resolved->scheme.arity), depth);
        if (points > kMaxCurvePoints) {
            diags.error({polygonName, 0, 0},
                        fmt::format("--depth {} refines the {} points into about {:.3g} (x{} a level), more than the "
                                    "{:.0e} a figure may have: lower --depth",
                                    depth, control.size(), points, resolved->scheme.arity, kMaxCurvePoints));
            return std::nullopt;
        }
        const auto refined = subdiv::refineCurveLevels(resolved->scheme, control, polygon.closed, depth);
        curves::CurveFile file{"polyline", polygon.closed, {}};
        for (const auto& v : refined) file.points.push_back({v.x, v.y});
        std::string label = resolved->family;
        if (!variant.label.empty()) {
            label += ": " + variant.label;
        } else {
            std::string p;
            for (const auto& [k, v] : resolved->params)
                p += fmt::format("{}{} = {}", p.empty() ? "" : ", ", k, formatShortest(v));
            if (!p.empty()) label += ": " + p;
        }
        label += fmt::format(" ({})", subdiv::certifiedClass(resolved->report));
        drawn.push_back({label, file.points, polygon.closed});
        figure.refined.push_back(std::move(file));
    }
    figure.svg = plot::curvesSvg(title, {"control polygon", polygon.points, polygon.closed}, drawn);
    return figure;
}

}  // namespace relief::figures
