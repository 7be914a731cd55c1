#include "figures/sweep.h"

#include <gtest/gtest.h>

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include "unit/test_dirs.h"

namespace relief::figures {
namespace {

TEST(Sweep, CombinationsFirstVariationFastest) {
    const auto c = combinations({{"subdivision.omega", {"1", "2", "3"}}, {"subdivision.lambda", {"a", "b"}}});
    ASSERT_EQ(c.size(), 6u);
    const std::vector<std::pair<std::string, std::string>> first{{"subdivision.omega", "1"}, {"subdivision.lambda", "a"}};
    EXPECT_EQ(c[0], first);
    EXPECT_EQ(c[1][0].second, "2");
    EXPECT_EQ(c[2][0].second, "3");
    EXPECT_EQ(c[3][0].second, "1");
    EXPECT_EQ(c[3][1].second, "b");
    EXPECT_TRUE(combinations({{"a.b", {}}}).empty());
}

// Tiles land where the layout says, with white between them and a label strip under each.
TEST(Sweep, ContactSheetLayout) {
    const auto dir = relief::testing::freshTestDir("relief-sheet-test");
    const float red[3] = {1, 0, 0}, blue[3] = {0, 0, 1};
    OIIO::ImageBuf a(OIIO::ImageSpec(64, 48, 3, OIIO::TypeDesc::UINT8)), b(a.spec());
    OIIO::ImageBufAlgo::fill(a, red);
    OIIO::ImageBufAlgo::fill(b, blue);
    ASSERT_TRUE(a.write((dir / "a.png").string()));
    ASSERT_TRUE(b.write((dir / "b.png").string()));
    const auto err = writeContactSheet({{dir / "a.png", "omega = 1"}, {dir / "b.png", "omega = 2\nC1"}}, 2,
                                       "title", dir / "sheet.png");
    EXPECT_EQ(err, "");
    OIIO::ImageBuf sheet((dir / "sheet.png").string());
    ASSERT_TRUE(sheet.read());
    EXPECT_EQ(sheet.spec().width, 2 * 64 + 3 * 12);
    EXPECT_EQ(sheet.spec().height, 44 + 48 + 46 + 2 * 12);
    float px[3];
    sheet.getpixel(12 + 30, 44 + 12 + 20, px);  // inside the first tile
    EXPECT_NEAR(px[0], 1, 1e-6);
    EXPECT_NEAR(px[2], 0, 1e-6);
    sheet.getpixel(12 + 64 + 12 + 30, 44 + 12 + 20, px);  // inside the second
    EXPECT_NEAR(px[2], 1, 1e-6);
    sheet.getpixel(12 + 64 + 6, 44 + 12 + 20, px);  // the gap between them
    EXPECT_NEAR(px[0], 1, 1e-6);
    EXPECT_NEAR(px[1], 1, 1e-6);
    std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace relief::figures
