#include "measure/compare_geometry.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>
#include <GeographicLib/Geodesic.hpp>
#include <GeographicLib/GeodesicLine.hpp>

#include "geo/profile.h"

namespace relief::measure {

namespace {

using Box = curves::Bounds2;

Box latticeBox(const Lattice& l) {
    return {l.x0, l.y0, l.x0 + (l.grid->cols - 1) * l.dx, l.y0 + (l.grid->rows - 1) * l.dy};
}

bool sameFrame(const geo::Frame& p, const geo::Frame& q) {
    return p.kind == q.kind && (p.kind == scene::FrameKind::Utm
                                    ? p.utmZone == q.utmZone && p.northp == q.northp
                                    : p.originLatDeg == q.originLatDeg && p.originLonDeg == q.originLonDeg);
}

// A point of b's frame at height z (in b's frame) in a's frame.
curves::Point2 carry(const geo::Frame& from, const geo::Frame& to, curves::Point2 p, double z) {
    if (sameFrame(from, to)) return p;
    double lat, lon, h;
    Vec3 q{p.x, p.y, z};
    if (geo::frameToGeodetic(from, q, lat, lon, h)) geo::geodeticToFrame(to, lat, lon, h, q);
    return {q.x, q.y};
}

// Latitude and longitude of a point of a's frame.
void geodetic(const geo::Frame& frame, curves::Point2 p, double z, double& lat, double& lon) {
    double h;
    geo::frameToGeodetic(frame, {p.x, p.y, z}, lat, lon, h);
}

// The part of a's box that b covers: b's corners carried into a's frame,
// where b's rectangle may be turned a little (another frame); the box inside it.
Box overlap(const FramedSurface& a, const FramedSurface& b) {
    const Box ba = latticeBox(a.lattice), bb = latticeBox(b.lattice);
    const auto sw = carry(b.frame, a.frame, {bb.xmin, bb.ymin}, 0.0), se = carry(b.frame, a.frame, {bb.xmax, bb.ymin}, 0.0);
    const auto nw = carry(b.frame, a.frame, {bb.xmin, bb.ymax}, 0.0), ne = carry(b.frame, a.frame, {bb.xmax, bb.ymax}, 0.0);
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
        ProfileLine l{name};
        double h;
        if (geo::frameToGeodetic(a.frame, {x1, y1, 0}, l.lat1, l.lon1, h) &&
            geo::frameToGeodetic(a.frame, {x2, y2, 0}, l.lat2, l.lon2, h))
            out.push_back(l);
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
    const auto [loA, hiA] = range(*a.lattice.grid);
    const auto [loB, hiB] = range(*b.lattice.grid);
    return niceLevels(std::max(loA, loB), std::min(hiA, hiB), 5);
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
            const auto pts = geo::geodesicProfile(s->frame, line.lat1, line.lon1, line.lat2, line.lon2, samples);
            auto& curve = s == &a ? pc.a : pc.b;
            for (const auto& p : pts) {
                const Lattice& l = s->lattice;
                const auto z = geo::sampleLattice(*l.grid, l.x0, l.y0, l.dx, l.dy, p.x, p.y);
                if (!z) {
                    diags.error({s->name, 0, 0},
                                fmt::format("profile {} leaves surface {} {:.0f} m from its start "
                                            "(lat {:.6f}, lon {:.6f}); choose points both surfaces cover",
                                            line.name, s == &a ? "a" : "b", p.distanceM, p.latDeg, p.lonDeg));
                    return std::nullopt;
                }
                curve.push_back({p.distanceM, *z});
            }
            pc.lengthM = pts.back().distanceM;
            if (s == &a)
                for (const auto& p : pts) pc.path.push_back({p.x, p.y});
        }
        const curves::CurveFile fa{"polyline", false, pc.a}, fb{"polyline", false, pc.b};
        pc.h = curves::hausdorff(curves::toBezier(fa), curves::toBezier(fb));
        pc.where = locate(pc.h);
        const GeographicLib::GeodesicLine g = wgs84.InverseLine(line.lat1, line.lon1, line.lat2, line.lon2);
        g.Position(pc.where.point.x, pc.where.latDeg, pc.where.lonDeg);
        out.profiles.push_back(std::move(pc));
    }

    std::string error;
    const auto linesA = contourLines(a.lattice, levels, error);
    auto linesB = error.empty() ? contourLines(b.lattice, levels, error) : linesA;
    if (!error.empty()) {
        diags.error({a.name, 0, 0}, "contour lines: " + error);
        return std::nullopt;
    }
    if (!sameFrame(a.frame, b.frame))
        for (auto& set : linesB)
            for (auto& curve : set)
                for (auto& seg : curve.segments)
                    for (auto& p : seg.control) p = carry(b.frame, a.frame, p, levels[&set - linesB.data()]);
    // Only where both surfaces are: a line outside the other's area has nothing to match.
    for (size_t i = 0; i < levels.size(); ++i) {
        ContourComparison cc;
        cc.level = levels[i];
        auto la = clipToBox(linesA[i], common.xmin, common.ymin, common.xmax, common.ymax);
        auto lb = clipToBox(linesB[i], common.xmin, common.ymin, common.xmax, common.ymax);
        cc.linesA = la.size();
        cc.linesB = lb.size();
        cc.h = curves::hausdorff(la, lb);
        cc.a = std::move(la);
        cc.b = std::move(lb);
        cc.where = locate(cc.h);
        if (std::isfinite(cc.h.H))
            geodetic(a.frame, cc.where.point, cc.level, cc.where.latDeg, cc.where.lonDeg);
        out.contours.push_back(std::move(cc));
    }
    return out;
}

}  // namespace relief::measure
