#include <cmath>

#include <gtest/gtest.h>

#include "measure/compare_geometry.h"
#include "geo/contours.h"

namespace relief::measure {
namespace {

// z = slope * (x - x0) + lift on an 41 x 31 lattice, 10 m spacing.
Grid ramp(double x0, double slope, double lift) {
    Grid g;
    g.rows = 31;
    g.cols = 41;
    for (int r = 0; r < g.rows; ++r)
        for (int c = 0; c < g.cols; ++c) g.points.push_back({0, 0, slope * (10.0 * c) + lift});
    (void)x0;
    return g;
}

TEST(Contours, PlaneGivesStraightLinesAtTheRightPlace) {
    const geo::GeoGrid l{{}, ramp(0, 1.0, 0), 300000, 6000000, 10, 10, {}};  // z = x - x0
    std::string error;
    const auto sets = geo::contourLines(l, {55, 200, 1000}, error);
    ASSERT_TRUE(error.empty()) << error;
    ASSERT_EQ(sets.size(), 3u);
    EXPECT_TRUE(sets[2].empty());  // above the surface
    for (size_t i = 0; i < 2; ++i) {
        ASSERT_EQ(sets[i].size(), 1u);
        const double x = 300000 + (i == 0 ? 55 : 200);
        double ymin = 1e300, ymax = -1e300;
        for (const auto& seg : sets[i][0].segments)
            for (const auto& p : seg.control) {
                EXPECT_NEAR(p.x, x, 1e-5);  // GDAL moves a level off exact node values by ~1e-6
                ymin = std::min(ymin, p.y), ymax = std::max(ymax, p.y);
            }
        // Across the whole lattice (GDAL takes the lines to the outer pixel edges, half a cell out).
        EXPECT_LE(ymin, 6000000.0);
        EXPECT_GE(ymax, 6000300.0);
    }
}

// Masked nodes (no data) stop contours: a level that crosses only the masked
// half of the lattice gives no line, and one in the other half ends at the mask.
TEST(Contours, MaskedNodesHaveNoContours) {
    geo::GeoGrid l{{}, ramp(0, 1.0, 0), 300000, 6000000, 10, 10, {}};
    l.masked.assign(l.grid.points.size(), 0);
    for (int r = 0; r < l.rows(); ++r)
        for (int c = 0; c < l.cols(); ++c) l.masked[static_cast<size_t>(r) * l.cols() + c] = r >= 15 || c >= 30;
    std::string error;
    const auto sets = geo::contourLines(l, {55, 350}, error);
    ASSERT_TRUE(error.empty()) << error;
    EXPECT_TRUE(sets[1].empty());  // x = 350 m lies in the masked columns
    ASSERT_EQ(sets[0].size(), 1u);
    for (const auto& seg : sets[0][0].segments)
        for (const auto& p : seg.control) EXPECT_LE(p.y, 6000000.0 + 145);  // rows 0-14, and half a cell
}

TEST(Contours, ClipToBox) {
    // A closed square around the box's corner: one line, the part inside.
    const auto square = curves::toBezier(curves::CurveFile{"polyline", true, {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}}});
    const auto clipped = geo::clipToBox({square}, 0, 0, 5, 5);
    ASSERT_EQ(clipped.size(), 1u);
    const auto& segs = clipped[0].segments;
    ASSERT_EQ(segs.size(), 2u);  // (1, 0) -> (1, 1) -> (0, 1)
    EXPECT_EQ(segs[0].control[0].x, 1.0);
    EXPECT_EQ(segs[0].control[0].y, 0.0);
    EXPECT_EQ(segs[1].control[1].x, 0.0);
    EXPECT_EQ(segs[1].control[1].y, 1.0);
    // Leaving and re-entering: two lines. Wholly inside: kept (closed).
    const auto zigzag = curves::toBezier(curves::CurveFile{"polyline", false, {{1, 1}, {1, 9}, {2, 1}}});
    EXPECT_EQ(geo::clipToBox({zigzag}, 0, 0, 5, 5).size(), 2u);
    const auto inside = geo::clipToBox({square}, -2, -2, 2, 2);
    ASSERT_EQ(inside.size(), 1u);
    EXPECT_TRUE(inside[0].closed);
    EXPECT_TRUE(geo::clipToBox({square}, 3, 3, 5, 5).empty());
}

TEST(Contours, NiceLevels) {
    EXPECT_EQ(geo::niceLevels(0, 1000, 5), (std::vector<double>{200, 400, 600, 800}));
    EXPECT_EQ(geo::niceLevels(102.5, 186.1, 5), (std::vector<double>{120, 140, 160, 180}));
    EXPECT_TRUE(geo::niceLevels(5, 5, 5).empty());
}

// Two ramps 3 m apart vertically (slope 1): their contour lines are 3 m apart
// horizontally (to GDAL's 1e-6 m); along the profiles, 3 m at the ends.
TEST(CompareGeometry, RampsLiftedByThreeMetres) {
    geo::Frame utm;
    utm.utmZone = 60;
    utm.northp = false;
    const geo::GeoGrid ga{utm, ramp(0, 1.0, 0), 300000, 6000000, 10, 10, {}};
    const geo::GeoGrid gb{utm, ramp(0, 1.0, 3.0), 300000, 6000000, 10, 10, {}};
    const FramedSurface a{"a", &ga}, b{"b", &gb};
    const auto profiles = defaultProfiles(a, b);
    ASSERT_EQ(profiles.size(), 2u);
    const auto levels = defaultLevels(a, b);
    ASSERT_FALSE(levels.empty());
    for (double z : levels) EXPECT_TRUE(z > 3 && z < 400) << z;
    Diagnostics diags;
    const auto r = compareGeometry(a, b, profiles, {100, 250}, 201, diags);
    ASSERT_TRUE(r) << (diags.all().empty() ? "" : diags.all()[0].message);
    // West-east: the lines (slope ~1) are 3 / sqrt(2) apart, but a's first point
    // is 3 m below b's first point, beyond the perpendicular's reach: an endpoint case.
    EXPECT_NEAR(r->profiles[0].h.H, 3.0, 1e-9);
    EXPECT_EQ(r->profiles[0].h.ab.kind, curves::WitnessCase::EndpointOfA);
    EXPECT_NEAR(r->profiles[0].where.point.x, 0.0, 1e-9);
    EXPECT_NEAR(r->profiles[0].lengthM, 392 * 1.0, 1.0);         // 400 m less 1 % each side, scale ~1.0
    EXPECT_NEAR(r->profiles[1].h.H, 3.0, 1e-9);                  // south-north: z is constant along it
    ASSERT_EQ(r->contours.size(), 2u);
    for (const auto& c : r->contours) {
        EXPECT_EQ(c.linesA, 1u);
        EXPECT_EQ(c.linesB, 1u);
        EXPECT_NEAR(c.h.H, 3.0, 1e-5) << c.level;
        EXPECT_NEAR(c.h.ab.value, 3.0, 1e-5);
        EXPECT_GT(c.where.latDeg, -47);  // UTM 60S near 300 km E, 6000 km N: about 36 S
        EXPECT_LT(c.where.latDeg, -35);
    }

    // A profile beyond b's lattice is an error naming it.
    ProfileLine outside = profiles[0];
    outside.to.lonDeg += 1.0;
    EXPECT_FALSE(compareGeometry(a, b, {outside}, {}, 11, diags));
    EXPECT_TRUE(diags.hasErrors());
}

TEST(CompareGeometry, FramesRoundTrip) {
    geo::Frame utm;
    utm.utmZone = 10;
    utm.northp = true;
    geo::Frame local;
    local.kind = scene::FrameKind::Local;
    local.originLatDeg = 49.5;
    local.originLonDeg = -123;
    for (const auto& f : {utm, local}) {
        const Vec3 p = f.kind == scene::FrameKind::Utm ? Vec3{500000, 5480000, 812} : Vec3{1234, -4321, 812};
        const auto g = geo::reverse(f, p);
        ASSERT_TRUE(g);
        EXPECT_NEAR(g->latDeg, 49.5, 0.1);
        const auto q = geo::forward(f, *g);
        ASSERT_TRUE(q);
        EXPECT_NEAR(q->x, p.x, 1e-6);
        EXPECT_NEAR(q->y, p.y, 1e-6);
        EXPECT_NEAR(q->z, p.z, 1e-6);
    }
}

}  // namespace
}  // namespace relief::measure
