#include "compare/compare_images.h"

#include <gtest/gtest.h>

#include <filesystem>

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include "unit/test_dirs.h"

namespace relief::compare {
namespace {

namespace fs = std::filesystem;
const fs::path kImages = fs::path(RELIEF_SOURCE_DIR) / "tests/data/images";

// rect.png is a.png with a 20 x 10 red rectangle: the heat map is black
// everywhere else, and exactly those 200 pixels light up.
TEST(DifferenceImage, LightsUpExactlyTheChangedPixels) {
    const fs::path out = relief::testing::freshTestDir("relief-compare") / "heat.png";
    ASSERT_EQ(writeDifferenceImage(kImages / "a.png", kImages / "rect.png", out), "");
    OIIO::ImageBuf heat(out.string());
    ASSERT_TRUE(heat.read());
    const OIIO::ImageBuf a((kImages / "a.png").string());
    EXPECT_EQ(heat.spec().width, a.spec().width);
    // Where a and rect differ, the heat map is brighter than where they agree.
    const OIIO::ImageBuf rect((kImages / "rect.png").string());
    double litSum = 0, darkSum = 0;
    int lit = 0, dark = 0;
    for (int y = 0; y < heat.spec().height; ++y)
        for (int x = 0; x < heat.spec().width; ++x) {
            float pa[4] = {}, pb[4] = {}, ph[3] = {};
            a.getpixel(x, y, pa, 4);
            rect.getpixel(x, y, pb, 4);
            heat.getpixel(x, y, ph, 3);
            const bool differs = pa[0] != pb[0] || pa[1] != pb[1] || pa[2] != pb[2];
            (differs ? litSum : darkSum) += ph[0] + ph[1] + ph[2];
            (differs ? lit : dark) += 1;
        }
    EXPECT_EQ(lit, 200);
    EXPECT_GT(litSum / lit, 0.5);
    EXPECT_LT(darkSum / dark, 0.02);
    fs::remove(out);
}

// The thresholds decide the verdict, as idiff's do.
TEST(CompareImages, VerdictFollowsTheThresholds) {
    Thresholds t;
    const auto same = compareImages(kImages / "a.png", kImages / "a.png", t);
    EXPECT_EQ(same.verdict, Verdict::Pass);
    EXPECT_EQ(same.maxError, 0);
    const auto rect = compareImages(kImages / "a.png", kImages / "rect.png", t);
    EXPECT_EQ(rect.verdict, Verdict::Failure);
    EXPECT_EQ(rect.failingPixels, 200);
    t.allowFailures = 200;
    EXPECT_EQ(compareImages(kImages / "a.png", kImages / "rect.png", t).verdict, Verdict::Pass);
    EXPECT_EQ(compareImages(kImages / "a.png", kImages / "small.png", t).verdict, Verdict::NotComparable);
}

}  // namespace
}  // namespace relief::compare
