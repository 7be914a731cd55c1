#include "measure/profile.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "plot/svg.h"

namespace relief::measure {

std::optional<SurfaceProfile> cutProfile(const geo::GeoGrid& net, const geo::GeoGrid& refined, const GeoPoint& from,
                                         const GeoPoint& to, int samples, const SourceLoc& where, Diagnostics& diags) {
    SurfaceProfile out;
    out.line = geo::geodesicProfile(net.frame, from, to, samples);
    size_t outside = 0;
    const auto zr = geo::heightsAlong(refined, out.line, outside);
    const auto zc = zr ? geo::heightsAlong(net, out.line, outside) : std::nullopt;
    if (!zr || !zc) {
        const auto& p = out.line[outside];
        diags.error(where, fmt::format("the profile leaves the net {:.0f} m from the start (lat {:.6f}, "
                                       "lon {:.6f}); the net covers x {:.0f}..{:.0f} m, y {:.0f}..{:.0f} m "
                                       "in {}: choose points inside it",
                                       p.distanceM, p.latDeg, p.lonDeg, net.x0, net.xMax(), net.y0,
                                       net.yMax(), net.frame.describe()));
        return std::nullopt;
    }
    out.refined = {"polyline", false, {}};
    out.control = {"polyline", false, {}};
    out.zMinM = 1e300, out.zMaxM = -1e300;
    for (size_t i = 0; i < out.line.size(); ++i) {
        out.refined.points.push_back({out.line[i].distanceM, (*zr)[i]});
        out.control.points.push_back({out.line[i].distanceM, (*zc)[i]});
        out.zMinM = std::min(out.zMinM, (*zr)[i]);
        out.zMaxM = std::max(out.zMaxM, (*zr)[i]);
    }
    out.lengthM = out.line.back().distanceM;
    return out;
}

std::string profileSvg(const SurfaceProfile& p, const std::string& sceneName,
                       const std::string& refinedLabel, double exaggeration, double& used) {
    // Relief about a third of the length unless asked otherwise.
    used = exaggeration > 0
               ? exaggeration
               : std::max(1.0, std::round(0.3 * p.lengthM / std::max(p.zMaxM - p.zMinM, 1e-9)));
    const plot::SvgAxes axes{true, used, "distance along the geodesic (m)", "elevation (m)"};
    const std::string title = fmt::format("{}: profile, {:.0f} m, vertical exaggeration {:g}", sceneName,
                                          p.lengthM, used);
    return plot::curvesSvg(title, {"control net (bilinear)", p.control.points, false},
                           {{refinedLabel, p.refined.points, false}}, axes);
}

}  // namespace relief::measure
