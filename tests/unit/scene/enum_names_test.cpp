#include <gtest/gtest.h>

#include <fstream>
#include <set>
#include <string>

#include "scene/enum_names.h"
#include "scene/read_scene.h"
#include "scene/read_sections.h"
#include "unit/test_dirs.h"

namespace relief::scene {
namespace {

// Every value of E, from the first to `last`, has exactly one row, and its
// name leads back to it: a value added to the enum without its row fails here.
template <class E>
void expectOneNameEach(E last) {
    const auto rows = std::span(EnumNames<E>::rows);
    EXPECT_EQ(rows.size(), static_cast<size_t>(last) + 1);
    std::set<std::string> names;
    for (int v = 0; v <= static_cast<int>(last); ++v) {
        const std::string name = nameOf(static_cast<E>(v));
        EXPECT_NE(name, "?") << "value " << v << " has no name";
        EXPECT_TRUE(names.insert(name).second) << name << " names two values";
        EXPECT_EQ(valueNamed<E>(name), static_cast<E>(v)) << name;
    }
    EXPECT_FALSE(valueNamed<E>("no such name"));
}

TEST(EnumNames, EveryValueHasOneName) {
    expectOneNameEach(FrameKind::Raster);
    expectOneNameEach(Gridding::Fit);
    expectOneNameEach(Projection::Spherical);
    expectOneNameEach(Resample::Nearest);
    expectOneNameEach(NodataPolicy::Error);
    expectOneNameEach(TextureSpec::Colouring::Image);
    expectOneNameEach(GeometryKind::HeightField);
    expectOneNameEach(CameraPath::Flyover);
    expectOneNameEach(Quality::High);
    expectOneNameEach(MarkerKind::None);
    EXPECT_STREQ(nameOf(Gridding::InverseDistance), "invdist");
    EXPECT_STREQ(nameOf(GeometryKind::HeightField), "height_field");
}

TEST(SectionReaders, EverySectionHasOneReader) {
    std::set<std::string> names;
    for (const auto& reader : sectionReaders()) {
        EXPECT_TRUE(names.insert(reader.name).second) << reader.name << " has two readers";
        EXPECT_NE(reader.read, nullptr);
    }
    EXPECT_EQ(names.size(), 17u);
}

struct SceneText {
    std::filesystem::path dir = relief::testing::freshTestDir("relief-section-readers-test");
    std::optional<SceneSpec> read(const std::string& sections, Diagnostics& diags) {
        std::ofstream(dir / "s.csv") << "lon,lat,elev\n";
        std::ofstream(dir / "s.toml") << "[samples]\npath = \"s.csv\"\n" << sections;
        return readScene(dir / "s.toml", diags);
    }
    ~SceneText() { std::filesystem::remove_all(dir); }
};

// A key naming an enum's value takes the names of its table, and a wrong
// one is refused at the key, listing them in the table's order.
TEST(SectionReaders, NamedValuesComeFromTheTables) {
    SceneText scene;
    Diagnostics diags;
    auto s = scene.read("[net]\ngridding = \"invdist\"\n[geometry]\nkind = \"height_field\"\n"
                        "[camera]\nprojection = \"orthographic\"\n",
                        diags);
    ASSERT_TRUE(s);
    EXPECT_EQ(s->net.gridding, Gridding::InverseDistance);
    EXPECT_EQ(s->geometry.kind, GeometryKind::HeightField);
    EXPECT_EQ(s->look.camera.projection, Projection::Orthographic);

    Diagnostics wrong;
    scene.read("[net]\ngridding = \"liner\"\n", wrong);
    ASSERT_EQ(wrong.errorCount(), 1);
    EXPECT_EQ(wrong.all()[0].loc.line, 4);
    EXPECT_NE(wrong.all()[0].message.find("net.gridding = \"liner\" is not one of \"linear\", \"invdist\", \"nearest\""),
              std::string::npos)
        << wrong.all()[0].message;
    // texture.mode offers the ramp's colourings; an image is texture.image's.
    Diagnostics image;
    scene.read("[texture]\nmode = \"image\"\n", image);
    ASSERT_EQ(image.errorCount(), 1);
    EXPECT_NE(image.all()[0].message.find("is not one of \"elevation\", \"slope\", \"blend\""), std::string::npos)
        << image.all()[0].message;
}

}  // namespace
}  // namespace relief::scene
