#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <regex>
#include <set>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "scene/color_ramp.h"
#include "scene/read_scene.h"
#include "unit/test_dirs.h"

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
    const auto dir = relief::testing::freshTestDir("relief-scene-test");
    std::ofstream(dir / "s.csv") << "lon,lat,elev\n";
    std::ofstream(dir / "s.toml") << "[samples]\npath = \"s.csv\"\n";
    Diagnostics diags;
    auto s = readScene(dir / "s.toml", diags);
    ASSERT_TRUE(s);
    EXPECT_FALSE(diags.hasErrors());
    EXPECT_EQ(s->samples.path, dir / "s.csv");
    EXPECT_EQ(s->frame.kind, FrameKind::Utm);
    EXPECT_EQ(s->net.rows, 64);
    EXPECT_EQ(s->subdivision.scheme.name, "dlg4");
    EXPECT_FALSE(s->subdivision.depthGiven);  // chosen for the still (Pipeline.DefaultDepthIsChosenForTheStill)
    EXPECT_EQ(s->render.width, 800);
    EXPECT_EQ(s->look.texture.ramp.preset, "terrain");
    std::filesystem::remove_all(dir);
}

// Every key relief's stages look up by name (`locs.at("net.spacing_m")`,
// `locs.has(...)`) is a key the reader reads: a typo would silently report a
// problem at the section instead of the key.
TEST(ReadScene, EveryKeyTheStagesLookUpIsASceneKey) {
    const auto dir = relief::testing::freshTestDir("relief-scene-keys-test");
    std::ofstream(dir / "s.csv") << "lon,lat,elev\n";
    std::ofstream(dir / "s.toml") << "[samples]\npath = \"s.csv\"\n[animation]\nframes = 2\npath = \"orbit\"\n"
                                     "[[layer]]\npath = \"s.csv\"\n";
    Diagnostics diags;
    const auto s = readScene(dir / "s.toml", diags);
    ASSERT_TRUE(s);
    ASSERT_EQ(s->layers.size(), 1u);
    std::set<std::string> known;
    for (const KeyLocations* locs :
         {&s->samples.locs, &s->frame.locs, &s->net.locs, &s->subdivision.locs, &s->look.vertical.locs,
          &s->look.texture.locs, &s->look.lighting.locs, &s->look.camera.locs, &s->look.base.locs, &s->look.water.locs,
          &s->look.atmosphere.locs, &s->geometry.locs, &s->render.locs, &s->overlay.locs, &s->limits.locs,
          &s->animation.locs, &s->layers[0].locs})
        known.insert(locs->known.begin(), locs->known.end());
    ASSERT_GT(known.size(), 50u);
    const std::regex lookup(R"re(locs\.(?:at|has)\("([a-z_]+\.[a-z_.]+)"\))re");
    int lookups = 0;
    for (const auto& entry : std::filesystem::recursive_directory_iterator(std::filesystem::path(RELIEF_SOURCE_DIR) / "src")) {
        if (!entry.is_regular_file()) continue;
        std::ifstream in(entry.path());
        const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
        for (std::sregex_iterator m(text.begin(), text.end(), lookup), end; m != end; ++m, ++lookups)
            EXPECT_TRUE(known.count((*m)[1])) << entry.path().filename().string() << " looks up " << (*m)[1]
                                              << ", which the scene reader does not read";
    }
    EXPECT_GT(lookups, 15);
    std::filesystem::remove_all(dir);
}

// Every key's location is kept in the spec of the stage that reads it, so that
// stage can report a problem at the key; absent keys fall back to their
// section, then to the file.
TEST(ReadScene, EachSpecKeepsTheLocationOfEveryKey) {
    const auto dir = relief::testing::freshTestDir("relief-scene-locs-test");
    std::ofstream(dir / "s.csv") << "lon,lat,elev\n";
    std::ofstream(dir / "s.toml") << "[samples]\npath = \"s.csv\"\n"
                                     "[net]\nspacing_m = 20\n"
                                     "[subdivision]\nscheme = \"four-point-4p\"\n  omega = \"3/64\"\n"
                                     "[camera]\nfov_deg = 30\n";
    Diagnostics diags;
    const auto s = readScene(dir / "s.toml", diags);
    ASSERT_TRUE(s);
    ASSERT_FALSE(diags.hasErrors());
    auto expectAt = [](const SourceLoc& loc, int line, int column) {
        EXPECT_EQ(loc.line, line);
        EXPECT_EQ(loc.column, column);
        EXPECT_NE(loc.file.find("s.toml"), std::string::npos);
    };
    expectAt(s->samples.locs.at("samples.path"), 2, 8);
    expectAt(s->net.locs.at("net.spacing_m"), 4, 13);
    expectAt(s->net.locs.at("net.gridding"), 3, 1);            // absent: the [net] header
    expectAt(s->subdivision.scheme.locs.at("subdivision.scheme"), 6, 10);
    expectAt(s->subdivision.scheme.locs.at("subdivision.omega"), 7, 3);  // a parameter: its key
    expectAt(s->look.camera.locs.at("camera.fov_deg"), 9, 11);
    expectAt(s->render.locs.at("render.width"), 0, 0);         // no [render]: the file
    EXPECT_DOUBLE_EQ(s->subdivision.scheme.params.at("omega"), 3.0 / 64);
    std::filesystem::remove_all(dir);
}

// An override that names no key is an error at the command line's --set, as written.
TEST(ReadScene, ABadOverrideIsAnErrorAtItsSet) {
    const auto dir = relief::testing::freshTestDir("relief-scene-bad-override");
    std::ofstream(dir / "s.csv") << "lon,lat,elev\n";
    std::ofstream(dir / "s.toml") << "title = \"a value\"\n[samples]\npath = \"s.csv\"\n";
    for (const auto& [dotted, expected] : std::vector<std::pair<std::string, std::string>>{
             {"omega", "--set omega: error: \"omega\" must name section.key (e.g. subdivision.omega)"},
             {"title.x", "--set title.x: error: \"title\" is not a section: it holds a value"}}) {
        Diagnostics diags;
        EXPECT_FALSE(readScene(dir / "s.toml", diags, {{dotted, "1"}}));
        ASSERT_FALSE(diags.all().empty()) << dotted;
        EXPECT_EQ(formatDiagnostic(diags.all()[0]), expected);
    }
}

// The report-ready keys, from the file and from overrides written as TOML
// writes values (an inline table, a quoted string): the block's thickness or
// false, slope and blend colouring, contours, the sun's date and time.
TEST(ReadScene, ReportKeysFromTheFileAndFromOverrides) {
    const auto dir = relief::testing::freshTestDir("relief-scene-report-test");
    std::ofstream(dir / "s.csv") << "lon,lat,elev\n";
    std::ofstream(dir / "s.toml") << "[samples]\npath = \"s.csv\"\n"
                                     "[base]\nthickness_m = 40\n"
                                     "[texture]\nmode = \"blend\"\nrock_color = \"#808080\"\nrock_to_deg = 50\n";
    Diagnostics diags;
    auto s = readScene(dir / "s.toml", diags);
    ASSERT_TRUE(s);
    ASSERT_FALSE(diags.hasErrors());
    EXPECT_TRUE(s->look.base.enabled);
    EXPECT_EQ(s->look.base.thicknessM, 40.0);
    EXPECT_EQ(s->look.texture.colouring, TextureSpec::Colouring::Blend);
    EXPECT_DOUBLE_EQ(s->look.texture.rockFromDeg, 30);
    EXPECT_DOUBLE_EQ(s->look.texture.rockToDeg, 50);
    EXPECT_NEAR(s->look.texture.rockColour.r, 0.2158605, 1e-6);  // #80 made linear
    EXPECT_FALSE(s->overlay.contours);
    EXPECT_FALSE(s->look.lighting.sunTime);

    s = readScene(dir / "s.toml", diags,
                  {{"base.thickness_m", "false"},
                   {"overlay.contours", "{interval_m = 25, index_every = 4, color = \"#102030\"}"},
                   {"lighting.datetime", "\"2026-06-21T09:00:00+12:00\""},
                   {"texture.mode", "slope"}});
    ASSERT_TRUE(s);
    ASSERT_FALSE(diags.hasErrors());
    EXPECT_FALSE(s->look.base.enabled);
    ASSERT_TRUE(s->overlay.contours);
    EXPECT_DOUBLE_EQ(s->overlay.contours->intervalM, 25);
    EXPECT_EQ(s->overlay.contours->indexEvery, 4);
    ASSERT_TRUE(s->look.lighting.sunTime);
    EXPECT_EQ(s->look.lighting.sunTime->utcSeconds, 1781989200);  // 2026-06-20T21:00:00Z
    EXPECT_EQ(s->look.lighting.sunTimeText, "2026-06-21T09:00:00+12:00");
    EXPECT_EQ(s->look.texture.colouring, TextureSpec::Colouring::Slope);

    // Each wrong value: an error at its key.
    for (const auto& [key, value] : std::vector<std::pair<std::string, std::string>>{
             {"overlay.contours", "{interval_m = -5}"},
             {"overlay.contours", "{interval = 5}"},
             {"base.thickness_m", "-1"},
             {"texture.rock_from_deg", "60"},
             {"texture.mode", "shaded"}}) {
        Diagnostics bad;
        readScene(dir / "s.toml", bad, {{key, value}});
        EXPECT_EQ(bad.errorCount(), 1) << key << " = " << value;
    }
    std::filesystem::remove_all(dir);
}

// The author's furniture: each item at a place or off, the text's scale, the
// legend's title and unit, the scale bar's units and length; every wrong
// value an error at overlay.<key> that names the choices.
TEST(ReadScene, TheAuthorPlacesTheFurniture) {
    const auto dir = relief::testing::freshTestDir("relief-scene-furniture-test");
    std::ofstream(dir / "s.csv") << "lon,lat,elev\n";
    std::ofstream(dir / "s.toml") << "[samples]\npath = \"s.csv\"\n"
                                     "[overlay]\nplace = { legend = \"left\", north_arrow = \"off\", "
                                     "title = \"auto\", scale_bar = \"top-right\" }\n"
                                     "text_scale = 1.5\nlegend_title = \"Height\"\nlegend_units = \"ft\"\n"
                                     "scale_bar_length = \"2.5 mi\"\n";
    Diagnostics diags;
    auto s = readScene(dir / "s.toml", diags);
    ASSERT_TRUE(s);
    ASSERT_FALSE(diags.hasErrors());
    EXPECT_EQ(s->overlay.places, (std::map<std::string, std::string>{
                                     {"legend", "left"}, {"north_arrow", "off"}, {"scale_bar", "top-right"}}));
    EXPECT_DOUBLE_EQ(s->overlay.textScale, 1.5);
    EXPECT_EQ(s->overlay.legendTitle, "Height");
    EXPECT_TRUE(s->overlay.legendFeet);
    ASSERT_TRUE(s->overlay.scaleBarUnit);
    EXPECT_EQ(s->overlay.scaleBarUnit->name, "mi");
    EXPECT_DOUBLE_EQ(s->overlay.scaleBarUnit->metres, 1609.344);
    EXPECT_DOUBLE_EQ(s->overlay.scaleBarLength, 2.5);
    EXPECT_TRUE(s->overlay.scaleBarImperial);

    // Every place of every item is read (the space, not one point of it).
    for (const std::string& item : kFurnitureItems)
        for (const std::string& where : kFurniturePlaces) {
            Diagnostics d;
            const auto placed = readScene(dir / "s.toml", d, {{"overlay.place", "{" + item + " = \"" + where + "\"}"}});
            ASSERT_TRUE(placed) << item << " " << where;
            EXPECT_EQ(placed->overlay.places.count(item), where == "auto" ? 0u : 1u) << item << " " << where;
        }

    for (const auto& [key, value, says] : std::vector<std::tuple<std::string, std::string, std::string>>{
             {"overlay.place", "{ legend = \"middle\" }", "overlay.place.legend must be one of \"auto\", \"top-left\""},
             {"overlay.place", "{ legend = 3 }", "overlay.place.legend must be one of"},
             {"overlay.place", "{ compass = \"top\" }", "overlay.place.compass: no such item; the items are \"title\""},
             {"overlay.place", "\"top-left\"", "overlay.place must be a table"},
             {"overlay.text_scale", "0.1", "overlay.text_scale"},
             {"overlay.legend_units", "\"yd\"", "\"m\", \"ft\""},
             {"overlay.scale_bar_units", "\"nautical\"", "\"metric\", \"imperial\""},
             {"overlay.scale_bar_length", "\"2 leagues\"", "must be a length and a unit"},
             {"overlay.scale_bar_length", "\"km\"", "must be a length and a unit"},
             {"overlay.scale_bar_length", "\"-1 km\"", "must be a length and a unit"},
             {"overlay.scale_bar_length", "\"2,5 km\"", "must be a length and a unit"}}) {
        Diagnostics bad;
        readScene(dir / "s.toml", bad, {{key, value}});
        ASSERT_EQ(bad.errorCount(), 1) << key << " = " << value;
        const std::string text = formatDiagnostic(bad.all()[0]);
        EXPECT_NE(text.find(says), std::string::npos) << text;
    }
    std::filesystem::remove_all(dir);
}

// A panorama is 180 degrees wide unless fov_deg says otherwise (up to 360);
// a perspective camera stops at 170; a sphere takes no fov_deg (a warning).
TEST(ReadScene, WideCamerasTakeTheirFieldsOfView) {
    const auto dir = relief::testing::freshTestDir("relief-scene-wide-cameras");
    std::ofstream(dir / "s.csv") << "lon,lat,elev\n";
    std::ofstream(dir / "s.toml") << "[samples]\npath = \"s.csv\"\n";
    const auto read = [&](const SceneOverrides& sets, Diagnostics& d) { return readScene(dir / "s.toml", d, sets); };
    Diagnostics d;
    auto s = read({{"camera.projection", "\"panoramic\""}}, d);
    ASSERT_TRUE(s);
    EXPECT_EQ(s->look.camera.projection, Projection::Panoramic);
    EXPECT_EQ(s->look.camera.fovDeg, 180);
    s = read({{"camera.projection", "\"panoramic\""}, {"camera.fov_deg", "360"}}, d);
    ASSERT_TRUE(s);
    EXPECT_EQ(s->look.camera.fovDeg, 360);
    EXPECT_FALSE(d.hasErrors());
    s = read({{"camera.projection", "\"spherical\""}, {"camera.fov_deg", "90"}}, d);
    ASSERT_TRUE(s);
    EXPECT_EQ(s->look.camera.projection, Projection::Spherical);
    EXPECT_EQ(d.warningCount(), 1);
    Diagnostics bad;
    read({{"camera.fov_deg", "171"}}, bad);
    EXPECT_EQ(bad.errorCount(), 1);
    std::filesystem::remove_all(dir);
}

TEST(ColorRamp, HexAndInterpolation) {
    LinearRgb c;
    ASSERT_TRUE(parseHexColor("#ff0000", c));
    EXPECT_DOUBLE_EQ(c.r, 1.0);
    EXPECT_DOUBLE_EQ(c.g, 0.0);
    EXPECT_FALSE(parseHexColor("ff0000", c));
    EXPECT_FALSE(parseHexColor("#ff00zz", c));
    // A sign or a space is no hex digit (fuzz_cpt found "#-88e0d" read as negative colours).
    EXPECT_FALSE(parseHexColor("#-88e0d", c));
    EXPECT_FALSE(parseHexColor("#+8ffff", c));
    EXPECT_FALSE(parseHexColor("# 8ffff", c));
    ASSERT_TRUE(parseHexColor("#0A0b0C", c));
    EXPECT_GT(c.b, c.r);
    const std::vector<ColorStop> stops{{0, {0, 0, 0}}, {100, {1, 0.5, 0}}};
    const LinearRgb mid = sampleRamp(stops, 50);
    EXPECT_DOUBLE_EQ(mid.r, 0.5);
    EXPECT_DOUBLE_EQ(mid.g, 0.25);
    EXPECT_DOUBLE_EQ(sampleRamp(stops, -10).r, 0.0);
    EXPECT_DOUBLE_EQ(sampleRamp(stops, 1e9).r, 1.0);
}

// The topobathy preset puts the shore (first land colour) at exactly 0 m.
TEST(ColorRamp, TopobathyShoreAtSeaLevel) {
    const auto stops = resolveRamp({"topobathy", {}, {}}, -1000, 2000);
    const auto land = sampleRamp(stops, 0.0), sea = sampleRamp(stops, -1.0);
    EXPECT_GT(sea.b, sea.g);
    EXPECT_GT(land.g, land.b);
}

}  // namespace
// [[layer]] tables: each a layer of its own, in order, its keys at their own
// lines; colours taken in turn when none is given; [layer] written as one
// table, a label too small to read, both label keys, and --set of a layer key
// are errors saying what to write.
TEST(ReadScene, LayerTablesAreReadInOrderWithTheirOwnLocations) {
    const auto dir = relief::testing::freshTestDir("relief-scene-layers-test");
    std::ofstream(dir / "s.csv") << "lon,lat,elev\n";
    std::ofstream(dir / "a.geojson") << "{}";
    std::ofstream(dir / "s.toml") << "[samples]\npath = \"s.csv\"\n"
                                     "[[layer]]\npath = \"a.geojson\"\nlabel = \"name\"\nlegend = \"Summits\"\n"
                                     "[[layer]]\npath = \"a.geojson\"\nlayer = \"tracks\"\ncolor = \"#112233\"\n"
                                     "dash_px = [6, 4]\nfill = \"#0000ff\"\nmarker = \"flag\"\n";
    Diagnostics diags;
    const auto s = readScene(dir / "s.toml", diags);
    ASSERT_TRUE(s);
    EXPECT_EQ(diags.errorCount(), 0) << (diags.all().empty() ? "" : diags.all().front().message);
    ASSERT_EQ(s->layers.size(), 2u);
    EXPECT_EQ(s->layers[0].number, 1);
    EXPECT_EQ(s->layers[0].labelField, "name");
    EXPECT_EQ(s->layers[0].legend, "Summits");
    EXPECT_EQ(s->layers[0].marker, MarkerKind::Pin);
    EXPECT_EQ(s->layers[0].path, dir / "a.geojson");
    EXPECT_EQ(s->layers[1].layer, "tracks");
    EXPECT_EQ(s->layers[1].marker, MarkerKind::Flag);
    EXPECT_EQ(s->layers[1].dashPx, (std::vector<double>{6, 4}));
    EXPECT_TRUE(s->layers[1].fill);
    EXPECT_NE(s->layers[0].colour, s->layers[1].colour);
    EXPECT_EQ(s->layers[0].locs.at("layer.label").line, 5);
    EXPECT_EQ(s->layers[1].locs.at("layer.layer").line, 9);

    const auto errorsOf = [&](const std::string& text, const SceneOverrides& overrides = {}) {
        std::ofstream(dir / "b.toml") << "[samples]\npath = \"s.csv\"\n" << text;
        Diagnostics d;
        readScene(dir / "b.toml", d, overrides);
        std::string all;
        for (const auto& x : d.all()) all += formatDiagnostic(x) + "\n";
        return all;
    };
    EXPECT_NE(errorsOf("[layer]\npath = \"a.geojson\"\n").find("\"layer\" must be tables, each written [[layer]]"),
              std::string::npos);
    EXPECT_NE(errorsOf("[[layer]]\npath = \"a.geojson\"\nlabel_size_px = 8\n").find("b.toml:5:17: error: layer.label_size_px"),
              std::string::npos)
        << errorsOf("[[layer]]\npath = \"a.geojson\"\nlabel_size_px = 8\n");
    EXPECT_NE(errorsOf("[[layer]]\npath = \"a.geojson\"\nlabel = \"name\"\nlabel_text = \"x\"\n")
                  .find("give label (an attribute's name) or label_text (one text), not both"),
              std::string::npos);
    EXPECT_NE(errorsOf("[[layer]]\npath = \"missing.gpx\"\n").find("layer.path: file \"missing.gpx\" not found"),
              std::string::npos);
    EXPECT_NE(errorsOf("[[layer]]\npath = \"a.geojson\"\n", {{"layer.color", "\"#ffffff\""}})
                  .find("[[layer]] keys cannot be set with --set"),
              std::string::npos);
    // Nor varied in a film; asking must not add a layer.
    std::ofstream(dir / "v.toml") << "[samples]\npath = \"s.csv\"\n[[layer]]\npath = \"a.geojson\"\n"
                                     "[animation]\nframes = 2\npath = \"orbit\"\nvary = { \"layer.width_px\" = [1, 3] }\n";
    Diagnostics varied;
    const auto v = readScene(dir / "v.toml", varied);
    ASSERT_EQ(varied.errorCount(), 1);
    EXPECT_NE(varied.all().front().message.find("[[layer]] keys cannot be varied"), std::string::npos)
        << varied.all().front().message;
    if (v) {
        EXPECT_EQ(v->layers.size(), 1u);
    }
}

}  // namespace relief::scene
