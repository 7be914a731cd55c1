#include <gtest/gtest.h>

#include <string>

#include "core/diagnostics.h"
#include "film/frames.h"
#include "scene/read_scene.h"

namespace relief::film {
namespace {

// A scene with [animation] `animation` over the committed Maungawhau raster.
scene::SceneSpec sceneWith(const std::string& animation, const std::string& extra = "") {
    const std::string text = std::string("[samples]\npath = \"") + RELIEF_SOURCE_DIR +
                             "/tests/data/rasters/maungawhau-20m.tif\"\nvertical_unit = \"m\"\n" + extra +
                             "\n[animation]\n" + animation;
    Diagnostics diags;
    auto s = scene::readSceneText(text, "film.toml", diags);
    for (const auto& d : diags.all()) ADD_FAILURE() << formatDiagnostic(d);
    return s ? *s : scene::SceneSpec{};
}

// The value frame `k` (0-based) sets for `key`, "" when it sets none.
std::string valueOf(const std::vector<FrameSettings>& frames, size_t k, const std::string& key) {
    for (const auto& [name, value] : frames.at(k).overrides)
        if (name == key) return value;
    return "";
}

TEST(FrameSettings, AFullOrbitLeavesOutItsFirstFrameAgain) {
    const auto frames = frameSettings(sceneWith("frames = 4\npath = \"orbit\"\n", "[camera]\nazimuth_deg = 200\n"));
    ASSERT_EQ(frames.size(), 4u);
    const char* expected[] = {"200", "290", "20", "110"};
    for (size_t k = 0; k < 4; ++k) {
        EXPECT_EQ(frames[k].number, int(k) + 1);
        EXPECT_EQ(valueOf(frames, k, "camera.azimuth_deg"), expected[k]) << "frame " << k + 1;
    }
}

TEST(FrameSettings, APartOrbitIncludesBothEnds) {
    const auto frames =
        frameSettings(sceneWith("frames = 3\npath = \"orbit\"\nazimuth_from_deg = 350\n"
                                "azimuth_to_deg = 450\n"));
    EXPECT_EQ(valueOf(frames, 0, "camera.azimuth_deg"), "350");
    EXPECT_EQ(valueOf(frames, 1, "camera.azimuth_deg"), "40");
    EXPECT_EQ(valueOf(frames, 2, "camera.azimuth_deg"), "90");
}

TEST(FrameSettings, TheSunsInstantsAreEvenlySpacedWithTheirClockAsSubtitle) {
    const auto frames = frameSettings(
        sceneWith("frames = 3\nsun = { from = \"2026-06-21T09:00:00+12:00\", to = \"2026-06-21T18:00:00+12:00\" }\n",
                  "[overlay]\nsubtitle = \"Auckland\"\n"));
    ASSERT_EQ(frames.size(), 3u);
    EXPECT_EQ(valueOf(frames, 1, "lighting.datetime"), "\"2026-06-21T13:30:00+12:00\"");
    EXPECT_EQ(valueOf(frames, 1, "overlay.subtitle"), "\"Auckland  2026-06-21 13:30:00 +12:00\"");
    EXPECT_EQ(valueOf(frames, 2, "lighting.datetime"), "\"2026-06-21T18:00:00+12:00\"");
    ASSERT_TRUE(frames[2].sunTime);
    EXPECT_EQ(frames[2].sunTime->utcSeconds - frames[0].sunTime->utcSeconds, 9 * 3600);
    EXPECT_EQ(valueOf(frames, 0, "camera.azimuth_deg"), "");
}

TEST(FrameSettings, AVariedKeyIsEasedAndAnIntegerKeyRounded) {
    const auto frames = frameSettings(
        sceneWith("frames = 5\nvary = { \"vertical.exaggeration\" = [1, 3], \"render.width\" = [100, 201] }\n"));
    ASSERT_EQ(frames.size(), 5u);
    // (1 - cos(pi t)) / 2 at t = 1/4: 0.14645; the exaggeration is a real number, the width whole.
    EXPECT_NEAR(std::stod(valueOf(frames, 1, "vertical.exaggeration")), 1 + 2 * 0.1464466094, 1e-9);
    EXPECT_EQ(valueOf(frames, 2, "vertical.exaggeration"), "2");
    EXPECT_EQ(valueOf(frames, 4, "vertical.exaggeration"), "3");
    EXPECT_EQ(valueOf(frames, 1, "render.width"), "115");  // 100 + 101 * 0.14645 = 114.79
    EXPECT_EQ(valueOf(frames, 4, "render.width"), "201");
}

TEST(FrameSettings, EasingIsFlatAtBothEnds) {
    EXPECT_DOUBLE_EQ(eased(0), 0);
    EXPECT_DOUBLE_EQ(eased(1), 1);
    EXPECT_DOUBLE_EQ(eased(0.5), 0.5);
    EXPECT_LT(eased(0.01), 0.01 * 0.01 * 3);  // ~ (pi t)^2 / 4
}

TEST(FrameSettings, OnlyViewKeysShareATerrain) {
    for (const char* key : {"camera.azimuth_deg", "lighting.datetime", "atmosphere.haze", "overlay.title"})
        EXPECT_TRUE(changesOnlyTheView(key)) << key;
    for (const char* key : {"vertical.exaggeration", "overlay.contours", "render.width", "subdivision.depth"})
        EXPECT_FALSE(changesOnlyTheView(key)) << key;
}

TEST(FrameSettings, ACounterFollowsTheSubtitleAndTheClock) {
    const auto frames = frameSettings(sceneWith(
        "frames = 3\ncounter = true\nsun = { from = \"2026-06-21T09:00:00+12:00\", to = \"2026-06-21T11:00:00+12:00\" }\n",
        "[overlay]\nsubtitle = \"Maungawhau\"\n"));
    ASSERT_EQ(frames.size(), 3u);
    EXPECT_EQ(valueOf(frames, 1, "overlay.subtitle"), "\"Maungawhau  2026-06-21 10:00:00 +12:00  frame 2 of 3\"");
    const auto alone = frameSettings(sceneWith("frames = 2\npath = \"orbit\"\ncounter = true\n"));
    EXPECT_EQ(valueOf(alone, 0, "overlay.subtitle"), "\"frame 1 of 2\"");
    const auto none = frameSettings(sceneWith("frames = 2\npath = \"orbit\"\n"));
    EXPECT_EQ(valueOf(none, 0, "overlay.subtitle"), "");
}

}  // namespace
}  // namespace relief::film
