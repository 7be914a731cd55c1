#include "core/png_file.h"

#include <gtest/gtest.h>

#include <filesystem>

#include <OpenImageIO/imagebuf.h>

#include "core/atomic_file.h"
#include "unit/test_dirs.h"

namespace relief {
namespace {

namespace fs = std::filesystem;

// Two PNGs with the same pixels but different dates and software give the
// same bytes once canonical, with the pixels unchanged.
TEST(CanonicalPng, SamePixelsGiveSameBytes) {
    const fs::path dir = relief::testing::freshTestDir("relief-png-test");
    OIIO::ImageSpec spec(4, 3, 3, OIIO::TypeDesc::UINT8);
    for (const char* when : {"2026:01:01 00:00:00", "2026:11:30 12:00:00"}) {
        OIIO::ImageBuf image(spec);
        for (int y = 0; y < 3; ++y)
            for (int x = 0; x < 4; ++x) {
                const float px[3] = {x / 4.f, y / 3.f, 0.5f};
                image.setpixel(x, y, px);
            }
        image.specmod().attribute("DateTime", when);
        image.specmod().attribute("Software", when);
        ASSERT_TRUE(image.write((dir / (std::string(when).substr(5, 2) + ".png")).string()));
    }
    EXPECT_NE(readFile(dir / "01.png"), readFile(dir / "11.png"));
    ASSERT_EQ(writeCanonicalPng(dir / "01.png", dir / "a.png"), "");
    ASSERT_EQ(writeCanonicalPng(dir / "11.png", dir / "b.png"), "");
    EXPECT_EQ(readFile(dir / "a.png"), readFile(dir / "b.png"));
    OIIO::ImageBuf canonical((dir / "a.png").string());
    float px[3];
    canonical.getpixel(3, 2, px);
    EXPECT_NEAR(px[0], 0.75f, 1.0f / 255);
    EXPECT_NEAR(px[1], 2.f / 3, 1.0f / 255);
    EXPECT_TRUE(canonical.spec().get_string_attribute("DateTime").empty());
    // No temporary file is left beside the output.
    int files = 0;
    for (const auto& e : fs::directory_iterator(dir)) files += e.is_regular_file();
    EXPECT_EQ(files, 4);
    // A missing input is an error naming it, and nothing is written.
    EXPECT_NE(writeCanonicalPng(dir / "none.png", dir / "c.png").find("none.png"), std::string::npos);
    EXPECT_FALSE(fs::exists(dir / "c.png"));
    fs::remove_all(dir);
}

}  // namespace
}  // namespace relief
