#include "measure/compare_geometry.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>
#include <GeographicLib/Geodesic.hpp>
#include <GeographicLib/GeodesicLine.hpp>

#include "core/number_format.h"
#include "plot/svg.h"
#include "geo/profile.h"

namespace relief::measure {

namespace {

using Box = curves::Bounds2;

Box gridBox(const geo::GeoGrid& g) { return {g.x0, g.y0, g.xMax(), g.yMax()}; }

bool sameFrame(const geo::Frame& p, const geo::Frame& q) {
    if (p.kind != q.kind) return false;
    switch (p.kind) {
        case scene::FrameKind::Utm:
            return p.utmZone == q.utmZone && p.northp == q.northp;
        case scene::FrameKind::Local:
            return p.originLatDeg == q.originLatDeg && p.originLonDeg == q.originLonDeg;
        case scene::FrameKind::Raster:
            return p.crsWkt == q.crsWkt;
    }
    return false;
}

// A point of b's frame at height z (in b's frame) in a's frame.
curves::Point2 carry(const geo::Frame& from, const geo::Frame& to, curves::Point2 p, double z) {
    if (sameFrame(from, to)) return p;
    std::optional<Vec3> q;
    if (auto g = geo::reverse(from, {p.x, p.y, z})) q = geo::forward(to, *g);
    return q ? curves::Point2{q->x, q->y} : p;
}

// The part of a's box that b covers: b's corners carried into a's frame,
// where b's rectangle may be turned a little (another frame); the box inside it.
Box overlap(const FramedSurface& a, const FramedSurface& b) {
    const Box ba = gridBox(*a.grid), bb = gridBox(*b.grid);
    const auto sw = carry(b.frame(), a.frame(), {bb.xmin, bb.ymin}, 0.0), se = carry(b.frame(), a.frame(), {bb.xmax, bb.ymin}, 0.0);
    const auto nw = carry(b.frame(), a.frame(), {bb.xmin, bb.ymax}, 0.0), ne = carry(b.frame(), a.frame(), {bb.xmax, bb.ymax}, 0.0);
    return {std::max({ba.xmin, sw.x, nw.x}), std::max({ba.ymin, sw.y, se.y}),
            std::min({ba.xmax, se.x, ne.x}), std::min({ba.ymax, nw.y, ne.y})};
}

Where locate(const curves::HausdorffResult& h) {
    Where w;
    const curves::OneSided& side = h.ab.value >= h.ba.value ? h.ab : h.ba;
    w.onA = h.ab.value >= h.ba.value;
    w.point = side.a;
    w.foot = side.foot.point;
    return w;
}

}  // namespace

std::vector<ProfileLine> defaultProfiles(const FramedSurface& a, const FramedSurface& b) {
    const Box o = overlap(a, b);
    if (!(o.xmax > o.xmin && o.ymax > o.ymin)) return {};
    const double ix = 0.01 * (o.xmax - o.xmin), iy = 0.01 * (o.ymax - o.ymin);
    const double cx = 0.5 * (o.xmin + o.xmax), cy = 0.5 * (o.ymin + o.ymax);
    std::vector<ProfileLine> out;
    auto add = [&](const char* name, double x1, double y1, double x2, double y2) {
        const auto g1 = geo::reverse(a.frame(), {x1, y1, 0}), g2 = geo::reverse(a.frame(), {x2, y2, 0});
        if (g1 && g2) out.push_back({name, {g1->lonDeg, g1->latDeg, 0}, {g2->lonDeg, g2->latDeg, 0}});
    };
    add("west-east", o.xmin + ix, cy, o.xmax - ix, cy);
    add("south-north", cx, o.ymin + iy, cx, o.ymax - iy);
    return out;
}

std::vector<double> defaultLevels(const FramedSurface& a, const FramedSurface& b) {
    auto range = [](const Grid& g) {
        double lo = 1e300, hi = -1e300;
        for (const auto& p : g.points) lo = std::min(lo, p.z), hi = std::max(hi, p.z);
        return std::pair{lo, hi};
    };
    const auto [loA, hiA] = range(a.grid->grid);
    const auto [loB, hiB] = range(b.grid->grid);
    return geo::niceLevels(std::max(loA, loB), std::min(hiA, hiB), 5);
}

std::optional<GeometryComparison> compareGeometry(const FramedSurface& a, const FramedSurface& b,
                                                  const std::vector<ProfileLine>& profiles,
                                                  const std::vector<double>& levels, int samples,
                                                  Diagnostics& diags) {
    GeometryComparison out;
    const Box common = overlap(a, b);
    if (!(common.xmax > common.xmin && common.ymax > common.ymin)) {
        diags.error({b.name, 0, 0}, fmt::format("surface b covers no part of surface a ({}): nothing to "
                                                "compare; compare scenes of the same area",
                                                a.name));
        return std::nullopt;
    }
    const auto& wgs84 = GeographicLib::Geodesic::WGS84();
    for (const ProfileLine& line : profiles) {
        ProfileComparison pc;
        pc.line = line;
        for (const FramedSurface* s : {&a, &b}) {
            const auto pts = geo::geodesicProfile(s->frame(), line.from, line.to, samples);
            auto& curve = s == &a ? pc.a : pc.b;
            size_t outside = 0;
            const auto z = geo::heightsAlong(*s->grid, pts, outside);
            if (!z) {
                const auto& p = pts[outside];
                diags.error({s->name, 0, 0},
                            fmt::format("profile {} leaves surface {} {:.0f} m from its start "
                                        "(lat {:.6f}, lon {:.6f}); choose points both surfaces cover",
                                        line.name, s == &a ? "a" : "b", p.distanceM, p.latDeg, p.lonDeg));
                return std::nullopt;
            }
            for (size_t i = 0; i < pts.size(); ++i) curve.push_back({pts[i].distanceM, (*z)[i]});
            pc.lengthM = pts.back().distanceM;
            if (s == &a)
                for (const auto& p : pts) pc.path.push_back({p.x, p.y});
        }
        const curves::CurveFile fa{"polyline", false, pc.a}, fb{"polyline", false, pc.b};
        pc.h = curves::hausdorff(curves::toBezier(fa), curves::toBezier(fb));
        pc.where = locate(pc.h);
        const GeographicLib::GeodesicLine g =
            wgs84.InverseLine(line.from.latDeg, line.from.lonDeg, line.to.latDeg, line.to.lonDeg);
        g.Position(pc.where.point.x, pc.where.latDeg, pc.where.lonDeg);
        out.profiles.push_back(std::move(pc));
    }

    std::string error;
    const auto linesA = geo::contourLines(*a.grid, levels, error);
    auto linesB = error.empty() ? geo::contourLines(*b.grid, levels, error) : linesA;
    if (!error.empty()) {
        diags.error({a.name, 0, 0}, "contour lines: " + error);
        return std::nullopt;
    }
    if (!sameFrame(a.frame(), b.frame()))
        for (auto& set : linesB)
            for (auto& curve : set)
                for (auto& seg : curve.segments)
                    for (auto& p : seg.control) p = carry(b.frame(), a.frame(), p, levels[&set - linesB.data()]);
    // Only where both surfaces are: a line outside the other's area has nothing to match.
    for (size_t i = 0; i < levels.size(); ++i) {
        ContourComparison cc;
        cc.level = levels[i];
        auto la = geo::clipToBox(linesA[i], common.xmin, common.ymin, common.xmax, common.ymax);
        auto lb = geo::clipToBox(linesB[i], common.xmin, common.ymin, common.xmax, common.ymax);
        cc.linesA = la.size();
        cc.linesB = lb.size();
        cc.h = curves::hausdorff(la, lb);
        cc.a = std::move(la);
        cc.b = std::move(lb);
        cc.where = locate(cc.h);
        if (std::isfinite(cc.h.H))
            if (auto g = geo::reverse(a.frame(), {cc.where.point.x, cc.where.point.y, cc.level}))
                cc.where.latDeg = g->latDeg, cc.where.lonDeg = g->lonDeg;
        out.contours.push_back(std::move(cc));
    }
    return out;
}

std::string formatDistance(double m) {
    if (!std::isfinite(m)) return "infinite";
    return std::fabs(m) >= 10000 ? fmt::format("{:.2f} km", m / 1000) : fmt::format("{:.3f} m", m);
}

std::string comparisonMapSvg(const GeometryComparison& r, const std::string& a,
                             const std::string& b, const std::string& frame) {
    using plot::SvgCurve;
    auto lines = [](const curves::CurveSet& set) {
        std::vector<SvgCurve> out;
        for (const auto& c : set) {
            SvgCurve s{"", {}, c.closed};
            for (const auto& seg : c.segments) s.points.push_back(seg.control.front());
            if (!c.segments.empty() && !c.closed) s.points.push_back(c.segments.back().control.back());
            out.push_back(std::move(s));
        }
        return out;
    };
    // One colour per level; a solid, b dashed.
    static constexpr const char* kLevelColours[] = {"#1f77b4", "#d62728", "#2ca02c", "#9467bd",
                                                    "#ff7f0e", "#8c564b", "#e377c2", "#17becf"};
    std::vector<plot::SvgLayer> layers{{"profiles", {}, "#888", true}};
    std::vector<plot::SvgMarker> markers;
    std::string levels;
    for (size_t i = 0; i < r.contours.size(); ++i) {
        const auto& c = r.contours[i];
        const std::string level = formatShortest(c.level) + " m";
        layers.push_back({level + ", a", lines(c.a), kLevelColours[i % 8], false});
        layers.push_back({level + ", b", lines(c.b), kLevelColours[i % 8], true});
        levels += (levels.empty() ? "" : ", ") + formatShortest(c.level);
        if (std::isfinite(c.h.H) && c.h.H > 0)
            markers.push_back({c.where.point, c.where.foot, fmt::format("{}: H = {}", level, formatDistance(c.h.H))});
    }
    auto& profiles = layers.front();
    for (const auto& p : r.profiles) profiles.lines.push_back({"", p.path, false});
    plot::SvgAxes axes{true, 1, fmt::format("x (m, {})", frame), "y (m)"};
    if (layers.size() > 1) layers[1].label += " (" + a + ")";
    if (layers.size() > 2) layers[2].label += " (" + b + ")";
    return plot::plotSvg(fmt::format("contour lines at {} m (a solid, b dashed); circles: where H is reached",
                                             levels),
                                 layers, markers, axes);
}


}  // namespace relief::measure
