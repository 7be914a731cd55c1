#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "scene/color_ramp.h"
#include "scene/read_scene.h"

namespace relief::scene {
namespace {

TEST(ParseFraction, NumbersAndFractions) {
    EXPECT_DOUBLE_EQ(*parseFraction("7/32"), 7.0 / 32);
    EXPECT_DOUBLE_EQ(*parseFraction("-1/16"), -1.0 / 16);
    EXPECT_DOUBLE_EQ(*parseFraction("0.25"), 0.25);
    EXPECT_FALSE(parseFraction("1/0"));
    EXPECT_FALSE(parseFraction("abc"));
    EXPECT_FALSE(parseFraction("1/2x"));
}

TEST(ReadScene, MinimalSceneGetsDefaults) {
    const auto dir = std::filesystem::temp_directory_path() / "relief-scene-test";
    std::filesystem::create_directories(dir);
    std::ofstream(dir / "s.csv") << "lon,lat,elev\n";
    std::ofstream(dir / "s.toml") << "[samples]\npath = \"s.csv\"\n";
    Diagnostics diags;
    auto s = readScene(dir / "s.toml", diags);
    ASSERT_TRUE(s);
    EXPECT_FALSE(diags.hasErrors());
    EXPECT_EQ(s->samplesPath, dir / "s.csv");
    EXPECT_EQ(s->frame, FrameKind::Utm);
    EXPECT_EQ(s->netRows, 64);
    EXPECT_EQ(s->scheme, "dlg4");
    EXPECT_EQ(s->depth, 3);
    EXPECT_EQ(s->width, 800);
    EXPECT_EQ(s->ramp.preset, "terrain");
    std::filesystem::remove_all(dir);
}

TEST(ColorRamp, HexAndInterpolation) {
    ColorStop c{};
    ASSERT_TRUE(parseHexColor("#ff0000", c));
    EXPECT_DOUBLE_EQ(c.r, 1.0);
    EXPECT_DOUBLE_EQ(c.g, 0.0);
    EXPECT_FALSE(parseHexColor("ff0000", c));
    EXPECT_FALSE(parseHexColor("#ff00zz", c));
    const std::vector<ColorStop> stops{{0, 0, 0, 0}, {100, 1, 0.5, 0}};
    const ColorStop mid = sampleRamp(stops, 50);
    EXPECT_DOUBLE_EQ(mid.r, 0.5);
    EXPECT_DOUBLE_EQ(mid.g, 0.25);
    EXPECT_DOUBLE_EQ(sampleRamp(stops, -10).r, 0.0);
    EXPECT_DOUBLE_EQ(sampleRamp(stops, 1e9).r, 1.0);
}

// The topobathy preset puts the shore (first land colour) at exactly 0 m.
TEST(ColorRamp, TopobathyShoreAtSeaLevel) {
    const auto stops = resolveRamp({"topobathy", {}}, -1000, 2000);
    const auto land = sampleRamp(stops, 0.0), sea = sampleRamp(stops, -1.0);
    EXPECT_GT(sea.b, sea.g);
    EXPECT_GT(land.g, land.b);
}

}  // namespace
}  // namespace relief::scene
