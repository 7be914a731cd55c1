// Banded linear gridding against GDAL's own (GDALGridCreate, "linear"), node
// by node: the bands must give the whole set's triangulation, not an
// approximation of it.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include <cpl_conv.h>
#include <gdal_alg.h>
#include <gdalgrid.h>

#include "geo/linear_gridding.h"

namespace relief::geo {
namespace {

constexpr double kNoData = -1e30;

std::vector<double> gdalLinear(const std::vector<double>& xs, const std::vector<double>& ys,
                               const std::vector<double>& zs, const GridLayout& g) {
    GDALGridAlgorithm algorithm;
    void* options = nullptr;
    EXPECT_EQ(ParseAlgorithmAndOptions("linear:radius=0:nodata=-1e30", &algorithm, &options), CE_None);
    std::vector<double> out(size_t(g.rows) * size_t(g.cols));
    EXPECT_EQ(GDALGridCreate(algorithm, options, GUInt32(xs.size()), xs.data(), ys.data(), zs.data(), g.xmin,
                             g.xmax, g.ymin, g.ymax, GUInt32(g.cols), GUInt32(g.rows), GDT_Float64,
                             out.data(), nullptr, nullptr),
              CE_None);
    CPLFree(options);
    return out;
}

// A terrain-like height: smooth, with detail, so that a wrong triangle shows.
double height(double x, double y) { return 300 * std::sin(x / 700) * std::cos(y / 500) + 0.02 * x * y / 1000; }

struct Cloud {
    std::vector<double> xs, ys, zs;
    void add(double x, double y) { xs.push_back(x), ys.push_back(y), zs.push_back(height(x, y)); }
};

void expectSameAsGdal(const Cloud& c, const GridLayout& g, int expectBands, bool expectWidened) {
    std::vector<double> banded;
    LinearGriddingStats stats;
    ASSERT_EQ(gridLinear(c.xs, c.ys, c.zs, g, kNoData, banded, &stats, 2), "");
    EXPECT_EQ(stats.bands, expectBands);
    if (expectWidened) {
        EXPECT_GT(stats.widenedBands, 0);
    }
    const auto reference = gdalLinear(c.xs, c.ys, c.zs, g);
    size_t outside = 0, differing = 0;
    for (size_t i = 0; i < reference.size(); ++i) {
        outside += reference[i] == kNoData;
        if (std::abs(banded[i] - reference[i]) > 1e-7 * (1 + std::abs(reference[i]))) ++differing;
    }
    EXPECT_EQ(differing, 0u) << "of " << reference.size() << " nodes";
    EXPECT_EQ(stats.outsideHull, outside);
    EXPECT_GT(outside, 0u);  // the grid's corners lie outside the samples' hull
}

TEST(LinearGridding, BandsGiveGdalsValuesOnScatteredPoints) {
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> u(0, 1);
    Cloud c;
    // 120,000 points in a disc of radius 5 km around a UTM-sized origin.
    while (c.xs.size() < 120000) {
        const double x = 2 * u(rng) - 1, y = 2 * u(rng) - 1;
        if (x * x + y * y <= 1) c.add(500000 + 5000 * x, 6200000 + 5000 * y);
    }
    const GridLayout g{495000, 505000, 6195000, 6205000, 300, 280};
    expectSameAsGdal(c, g, 2, false);
}

TEST(LinearGridding, WidensWhereTrianglesSpanAGap) {
    // An empty strip, 1 km tall, across the middle rows where the two bands
    // meet, closed at both ends: neither band's samples reach across it, so
    // the nodes in it are outside each band's triangulation but inside the
    // samples' hull, and the bands must widen to the whole set.
    std::mt19937_64 rng(11);
    std::uniform_real_distribution<double> u(0, 1);
    Cloud c;
    while (c.xs.size() < 70000) {
        const double x = u(rng) * 4000, y = u(rng) * 6000;
        if (y < 2500 || y > 3500 || x < 300 || x > 3700) c.add(300000 + x, 5000000 + y);
    }
    const GridLayout g{299900, 304100, 4999900, 5006100, 210, 310};
    expectSameAsGdal(c, g, 2, true);
}

TEST(LinearGridding, FewSamplesUseOneTriangulation) {
    Cloud c;
    for (int i = 0; i < 40; ++i)
        for (int j = 0; j < 40; ++j) c.add(1000 + 25.3 * i + 3 * std::sin(j), 2000 + 24.7 * j + 2 * std::cos(i));
    const GridLayout g{990, 2020, 1990, 3000, 57, 61};
    expectSameAsGdal(c, g, 1, false);
}

TEST(LinearGridding, CollinearSamplesAreAnError) {
    Cloud c;
    for (int i = 0; i < 10; ++i) c.add(i, 2 * i);
    std::vector<double> out;
    EXPECT_NE(gridLinear(c.xs, c.ys, c.zs, GridLayout{0, 10, 0, 20, 5, 5}, kNoData, out), "");
}

}  // namespace
}  // namespace relief::geo
