#include "measure/surface_curves.h"

#include <cmath>

#include <fmt/format.h>

#include "curves/curve_file.h"
#include "curves/hausdorff.h"
#include "geo/profile.h"
#include "geo/contours.h"

namespace relief::measure {

namespace {

curves::PiecewiseBezier polyline(const std::vector<curves::Point2>& points) {
    return curves::toBezier(curves::CurveFile{"polyline", false, points});
}

CurveMove moveOf(const curves::HausdorffResult& h) {
    CurveMove m;
    m.distanceM = h.H;
    const bool onNew = h.ab.value >= h.ba.value;
    const curves::OneSided& side = onNew ? h.ab : h.ba;
    m.witnessOnNew = onNew;
    m.witness = side.a;
    m.foot = side.foot.point;
    return m;
}

}  // namespace

std::optional<SurfaceCurves> surfaceCurves(const geo::GeoGrid& refined, const std::vector<ProfileLine>& profiles,
                                           const std::vector<double>& levels, int samples, const SourceLoc& at,
                                           Diagnostics& diags) {
    SurfaceCurves out;
    out.frame = refined.frame.describe();
    for (const ProfileLine& line : profiles) {
        const auto pts = geo::geodesicProfile(refined.frame, line.from, line.to, samples);
        size_t outside = 0;
        const auto z = geo::heightsAlong(refined, pts, outside);
        if (!z) {
            diags.error(at, fmt::format("profile {} leaves the surface {:.0f} m from its start (lon {:.6f}, lat "
                                        "{:.6f}): choose points on the terrain",
                                        line.name, pts[outside].distanceM, pts[outside].lonDeg, pts[outside].latDeg));
            return std::nullopt;
        }
        SurfaceCurves::Profile p{line.name, {}};
        for (size_t i = 0; i < pts.size(); ++i) p.points.push_back({pts[i].distanceM, (*z)[i]});
        out.profiles.push_back(std::move(p));
    }
    std::string error;
    const auto sets = geo::contourLines(refined, levels, error);
    if (!error.empty()) {
        diags.error(at, "contour lines: " + error);
        return std::nullopt;
    }
    for (size_t i = 0; i < levels.size(); ++i) {
        SurfaceCurves::Level l{levels[i], {}};
        for (const auto& curve : sets[i]) {
            std::vector<curves::Point2> line;
            for (const auto& seg : curve.segments) line.push_back(seg.control.front());
            if (!curve.segments.empty()) line.push_back(curve.segments.back().control.back());
            if (line.size() >= 2) l.lines.push_back(std::move(line));
        }
        out.levels.push_back(std::move(l));
    }
    return out;
}

CurveMove profileMove(const std::vector<curves::Point2>& now, const std::vector<curves::Point2>& kept) {
    return moveOf(curves::hausdorff(polyline(now), polyline(kept)));
}

CurveMove levelMove(const std::vector<std::vector<curves::Point2>>& now,
                    const std::vector<std::vector<curves::Point2>>& kept) {
    curves::CurveSet a, b;
    for (const auto& l : now) a.push_back(polyline(l));
    for (const auto& l : kept) b.push_back(polyline(l));
    return moveOf(curves::hausdorff(a, b));
}

}  // namespace relief::measure
