#include "pipeline/job.h"
#include "pipeline/load.h"
#include "pipeline/record.h"
#include "pipeline/surface.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <numbers>
#include <fstream>

#include <GeographicLib/UTMUPS.hpp>
#include <gdal.h>
#include <nlohmann/json.hpp>

#include "core/atomic_file.h"
#include "core/text_escape.h"
#include "geo/gdal_setup.h"
#include "scene/read_scene.h"
#include "unit/test_dirs.h"

namespace relief {
namespace {

namespace fs = std::filesystem;


fs::path freshDir(const std::string& name) {
    const fs::path dir = relief::testing::freshTestDir("relief-pipeline-" + name);
    return dir;
}

// A job that compiles `scene` to `pov` (and its sidecar), on one thread.
SceneJob compileJob(const fs::path& scene, const fs::path& pov) {
    SceneJob job;
    job.until = SceneJob::Until::Pov;
    job.scenePath = scene;
    job.output = pov;
    job.templatesDir = testing::kSourceDir / "templates";
    job.threads = 1;
    return job;
}

TEST(Pipeline, OutputPathsSitBesideTheStill) {
    const OutputPaths p = outputPathsFor("out/x/still.png");
    EXPECT_EQ(p.pov, fs::path("out/x/still.pov"));
    EXPECT_EQ(p.sidecar, fs::path("out/x/still.json"));
}

// Compiling only: the .pov is byte-identical to the golden one, and the
// library writes the sidecar, whose sizes come from the one mesh size formula.
TEST(Pipeline, CompileJobWritesThePovAndItsSidecar) {
    const fs::path dir = freshDir("compile");
    SceneJob job = compileJob(testing::kSourceDir / "tests/golden/small/scene.toml", dir / "small.pov");
    Diagnostics diags;
    std::vector<ProgressEvent> events;
    const JobOutcome outcome = runSceneJob(job, diags, [&](const ProgressEvent& e) { events.push_back(e); });
    ASSERT_EQ(outcome.status, JobStatus::Ok) << (diags.all().empty() ? "" : formatDiagnostic(diags.all()[0]));
    // Reading, compiling, then each task's percentages in order (how many of the
    // gridding's depends on GDAL's threads), each ending at 100 %; no render.
    ASSERT_GE(events.size(), 6u);
    EXPECT_EQ(events[0].stage, ProgressEvent::Stage::Reading);
    EXPECT_EQ(events[1].stage, ProgressEvent::Stage::Compiling);
    std::vector<std::string> tasks;
    for (size_t i = 2; i < events.size(); ++i) {
        EXPECT_EQ(events[i].stage, ProgressEvent::Stage::Compiling);
        if (tasks.empty() || events[i].text != tasks.back()) {
            if (!tasks.empty() && events[i - 1].percent >= 0) {
                EXPECT_EQ(events[i - 1].percent, 100) << tasks.back();
            }
            tasks.push_back(events[i].text);
        } else {
            EXPECT_GE(events[i].percent, events[i - 1].percent) << events[i].text;
        }
    }
    const std::vector<std::string> expected = {
        "gridding 300 samples", "subdividing to depth 2 (45 x 33 nodes)",
        "peak loss 10.9 m: the data's highest point 193.00 m, the surface's near it 182.06 m",
        "writing small.pov (2816 triangles)"};
    EXPECT_EQ(tasks, expected);
    EXPECT_EQ(events.back().percent, 100);
    const std::string pov = readFile(dir / "small.pov");
    const std::string golden = readFile(testing::kSourceDir / "tests/golden/small/ref.pov");
    // The header names the scene as given; everything after it must match.
    EXPECT_EQ(pov.substr(pov.find("\n#")), golden.substr(golden.find("\n#")));
    const auto sidecar = nlohmann::json::parse(readFile(dir / "small.json"));
    const auto& c = outcome.compiled->surface;
    EXPECT_EQ(sidecar["refined"]["rows"], c.estimate.rows);
    EXPECT_EQ(sidecar["refined"]["triangles"], 2 * (c.estimate.rows - 1) * (c.estimate.cols - 1));
    EXPECT_EQ(sidecar["refined"]["pov_bytes"], pov.size());
    EXPECT_EQ(sidecar["outputs"]["pov"], (dir / "small.pov").string());
    EXPECT_FALSE(sidecar["outputs"].contains("png"));
    EXPECT_FALSE(fs::exists(dir / "small.png"));
}

// A bad scene: the diagnostics say why, and nothing is written.
TEST(Pipeline, BadSceneWritesNothing) {
    const fs::path dir = freshDir("bad");
    std::ofstream(dir / "s.toml") << "[samples]\npath = \"missing.csv\"\n[render]\nwidth = 3\n";
    SceneJob job;
    job.scenePath = dir / "s.toml";
    job.output = dir / "out" / "s.png";
    job.templatesDir = testing::kSourceDir / "templates";
    Diagnostics diags;
    const JobOutcome outcome = runSceneJob(job, diags, nullptr);
    EXPECT_EQ(outcome.status, JobStatus::BadInput);
    EXPECT_EQ(diags.errorCount(), 2);  // every problem at once
    EXPECT_FALSE(fs::exists(dir / "out"));
}

// The surface: the refined grid keeps the net's frame and extent.
TEST(Pipeline, RefinedSurfaceKeepsTheNetsFrameAndExtent) {
    Diagnostics diags;
    const auto loaded = loadScene(testing::kSourceDir / "tests/golden/small/scene.toml", diags);
    ASSERT_TRUE(loaded);
    const auto s = buildSurface(*loaded, diags, 1);
    ASSERT_TRUE(s);
    EXPECT_EQ(s->refined.frame.describe(), s->net.frame.describe());
    EXPECT_NEAR(s->refined.xMax(), s->net.xMax(), 1e-6);
    EXPECT_NEAR(s->refined.yMax(), s->net.yMax(), 1e-6);
    EXPECT_EQ(s->refined.rows(), s->estimate.rows);
    // The refined lattice's nodes sit where its origin and spacing say.
    const Vec3& corner = s->refined.grid.at(s->refined.rows() - 1, s->refined.cols() - 1);
    EXPECT_NEAR(corner.x, s->refined.xMax(), 1e-6);
    EXPECT_NEAR(corner.y, s->refined.yMax(), 1e-6);
}

// [lighting] datetime: the sidecar's sun is the true bearing; the .pov's
// light comes from the grid bearing, the true one less the meridian
// convergence (Auckland is 2.2 degrees west of UTM 60's central meridian:
// grid north there is 1.3 degrees east of true north).
TEST(Pipeline, TheSunFromADateLightsAlongTheGridBearing) {
    const fs::path dir = freshDir("sun");
    SceneJob job = compileJob(testing::kSourceDir / "tests/golden/small/scene.toml", dir / "small.pov");
    job.overrides = {{"lighting.datetime", "2026-06-21T14:00:00+12:00"}};
    Diagnostics diags;
    const JobOutcome outcome = runSceneJob(job, diags, nullptr);
    ASSERT_EQ(outcome.status, JobStatus::Ok) << (diags.all().empty() ? "" : formatDiagnostic(diags.all()[0]));
    const auto sidecar = nlohmann::json::parse(readFile(dir / "small.json"));
    const auto& sun = sidecar["sun"];
    EXPECT_EQ(sun["from"], "datetime");
    const double lon = sun["at_lonlat"][0], lat = sun["at_lonlat"][1], trueAzimuth = sun["azimuth_deg"];
    // A winter afternoon in Auckland: the sun north-north-west, 25.5 degrees up (PyEphem 4.1.4, refracted
    // for 1010 hPa and 10 C: 335.245, 25.503).
    EXPECT_NEAR(trueAzimuth, 335.245, 0.02);
    EXPECT_NEAR(double(sun["altitude_deg"]), 25.503, 0.02);
    int zone = 0;
    bool northp = false;
    double x = 0, y = 0, gamma = 0, k = 0;
    GeographicLib::UTMUPS::Forward(lat, lon, zone, northp, x, y, gamma, k);
    EXPECT_NEAR(gamma, 1.34, 0.05);
    // The light's direction in the .pov: from the point it aims at to the light.
    const std::string pov = readFile(dir / "small.pov");
    const auto vectorAfter = [&](const std::string& key) {
        const size_t at = pov.find('<', pov.find(key));
        double v[3];
        EXPECT_EQ(std::sscanf(pov.c_str() + at, "<%lf,%lf,%lf>", &v[0], &v[1], &v[2]), 3) << key;
        return std::array<double, 3>{v[0], v[1], v[2]};
    };
    const auto light = vectorAfter("light_source {"), aim = vectorAfter("point_at");
    const double gridAzimuth = std::atan2(light[0] - aim[0], light[2] - aim[2]) * 180 / std::numbers::pi;
    EXPECT_NEAR(std::fmod(gridAzimuth + 360, 360), trueAzimuth - gamma, 1e-3);
}

// Whose data: a raster whose metadata names its credit (GeoTIFF's copyright
// tag) carries it to the header, the sidecar and the still's credits when the
// scene gives none; a draped image's credit joins it.
TEST(Pipeline, ARastersOwnCreditIsTheDefaultAttribution) {
    const fs::path dir = freshDir("credit");
    geo::setUpGdal();
    const auto copyWithCredit = [&](const fs::path& from, const fs::path& to, const char* credit) {
        GDALDatasetH src = GDALOpen(from.c_str(), GA_ReadOnly);
        ASSERT_NE(src, nullptr);
        GDALDatasetH mem = GDALCreateCopy(GDALGetDriverByName("MEM"), "", src, FALSE, nullptr, nullptr, nullptr);
        GDALSetMetadataItem(mem, "TIFFTAG_COPYRIGHT", credit, nullptr);
        GDALClose(GDALCreateCopy(GDALGetDriverByName("GTiff"), to.c_str(), mem, FALSE, nullptr, nullptr, nullptr));
        GDALClose(mem);
        GDALClose(src);
    };
    copyWithCredit(testing::kSourceDir / "scenes/data/rasters/cyl_elev.tif", dir / "dem.tif", "DEM: someone, CC BY 4.0");
    copyWithCredit(testing::kSourceDir / "scenes/data/rasters/cyl_tile.tif", dir / "map.tif", "Map: someone else, CC BY-SA");
    std::ofstream(dir / "s.toml") << "[samples]\npath = \"dem.tif\"\nvertical_unit = \"m\"\n[net]\nspacing_m = 10000\n"
                                     "[subdivision]\ndepth = 0\n";
    SceneJob job = compileJob(dir / "s.toml", dir / "s.pov");
    Diagnostics diags;
    JobOutcome outcome = runSceneJob(job, diags, nullptr);
    ASSERT_EQ(outcome.status, JobStatus::Ok) << (diags.all().empty() ? "" : formatDiagnostic(diags.all()[0]));
    auto sidecar = nlohmann::json::parse(readFile(dir / "s.json"));
    EXPECT_EQ(sidecar["inputs"]["attribution"], "DEM: someone, CC BY 4.0");
    EXPECT_EQ(outcome.compiled->view.overlayFacts.credits, "DEM: someone, CC BY 4.0");
    EXPECT_NE(readFile(dir / "s.pov").find("// samples.attribution: DEM: someone, CC BY 4.0 (from the raster's metadata)"),
              std::string::npos);

    job.overrides = {{"texture.image", "map.tif"}};
    outcome = runSceneJob(job, diags, nullptr);
    ASSERT_EQ(outcome.status, JobStatus::Ok) << (diags.all().empty() ? "" : formatDiagnostic(diags.all()[0]));
    sidecar = nlohmann::json::parse(readFile(dir / "s.json"));
    EXPECT_EQ(sidecar["texture"]["image_attribution"], "Map: someone else, CC BY-SA");
    EXPECT_EQ(outcome.compiled->view.overlayFacts.credits, "DEM: someone, CC BY 4.0 Map: someone else, CC BY-SA");

    // The scene's own line wins over the file's.
    job.overrides = {{"samples.attribution", "Ours"}};
    outcome = runSceneJob(job, diags, nullptr);
    ASSERT_EQ(outcome.status, JobStatus::Ok);
    EXPECT_EQ(outcome.compiled->view.overlayFacts.credits, "Ours");
}

// A DEM given alone: relief makes the scene, and the depth suits the still.
std::optional<Surface> planForStill(const std::string& width, const std::string& height, Diagnostics& diags,
                                    scene::SceneOverrides more = {}) {
    more.emplace_back("render.width", width);
    more.emplace_back("render.height", height);
    auto loaded = loadScene(testing::kSourceDir / "scenes/data/rasters/volcano2.tif", diags, more);
    if (!loaded) return std::nullopt;
    return planSurface(*loaded, diags, 1);
}

// A DEM that reaches the sea floor gets the topobathy ramp (blues below 0 m); one of dry land does not.
TEST(Pipeline, TheSceneForASeaFloorTakesTheTopobathyRamp) {
    const std::string asia = sceneTextForData(testing::kSourceDir / "scenes/data/rasters/asia.tif");  // -8,000 to 4,800 m
    EXPECT_NE(asia.find("\n[texture]\nramp = \"topobathy\"\n"), std::string::npos) << asia;
    const std::string volcano = sceneTextForData(testing::kSourceDir / "scenes/data/rasters/volcano2.tif");
    EXPECT_EQ(volcano.find("[texture]"), std::string::npos) << volcano;
    Diagnostics diags;
    const auto loaded = loadScene(testing::kSourceDir / "scenes/data/rasters/asia.tif", diags);
    ASSERT_TRUE(loaded) << (diags.all().empty() ? "" : formatDiagnostic(diags.all().back()));
    EXPECT_EQ(loaded->scene.look.texture.ramp.preset, "topobathy");
}

// A copy of the test DEM (Maungawhau, 20 m) with its metadata items set to `items` ("" removes one).
void copyDemWith(const fs::path& to, const std::vector<std::pair<const char*, std::string>>& items) {
    geo::setUpGdal();
    GDALDatasetH src = GDALOpen((testing::kSourceDir / "tests/data/rasters/maungawhau-20m.tif").c_str(), GA_ReadOnly);
    ASSERT_NE(src, nullptr);
    GDALDatasetH mem = GDALCreateCopy(GDALGetDriverByName("MEM"), "", src, FALSE, nullptr, nullptr, nullptr);
    for (const auto& [key, value] : items)
        GDALSetMetadataItem(mem, key, value.empty() ? nullptr : value.c_str(), nullptr);
    GDALClose(GDALCreateCopy(GDALGetDriverByName("GTiff"), to.c_str(), mem, FALSE, nullptr, nullptr, nullptr));
    GDALClose(mem);
    GDALClose(src);
}

// A title that closes TOML's strings and starts keys if pasted: quotes of every kind, line breaks,
// a section, a key, control characters, a backslash.
const std::string kHostileTitle = "Mt '''Eden\"\"\" 'x' \"y\"\n[render]\nwidth = 9999\r\n\x01\x1b[31m\ttab\x7f \\ end'";

std::string firstWarning(const Diagnostics& diags) {
    for (const auto& d : diags.all())
        if (d.severity != Severity::Note) return formatDiagnostic(d);
    return "";
}

// The title survives as data: in the scene relief makes for the DEM, and in relief init's scene
// read back, byte for byte, with every other key relief's (the still's size its default).
TEST(Pipeline, AHostileTitleStaysTheTitleThroughInit) {
    const fs::path dir = freshDir("hostile-title");
    copyDemWith(dir / "plain.tif", {{"TIFFTAG_DOCUMENTNAME", ""}});
    copyDemWith(dir / "dem.tif", {{"TIFFTAG_DOCUMENTNAME", kHostileTitle}});
    Diagnostics diags;
    const auto plain = loadScene(dir / "plain.tif", diags);
    const auto loaded = loadScene(dir / "dem.tif", diags);
    ASSERT_TRUE(plain && loaded) << firstWarning(diags);
    EXPECT_EQ(loaded->scene.overlay.title, kHostileTitle);
    EXPECT_EQ(loaded->scene.render.width, plain->scene.render.width);
    EXPECT_EQ(loaded->scene.render.height, plain->scene.render.height);
    // The record (the sidecar's) reads back as the same scene.
    const auto recorded = scene::readSceneText(loaded->scene.madeForData, dir / "dem.tif", diags);
    ASSERT_TRUE(recorded) << firstWarning(diags);
    EXPECT_EQ(recorded->overlay.title, kHostileTitle);
    EXPECT_EQ(recorded->render.width, plain->scene.render.width);

    const auto plainSurface = planSurface(*plain, diags, 1);
    const auto surface = planSurface(*loaded, diags, 1);
    ASSERT_TRUE(plainSurface && surface) << firstWarning(diags);
    const std::string plainText = initSceneText(*plain, *plainSurface, dir / "plain.toml");
    const std::string text = initSceneText(*loaded, *surface, dir / "scene.toml");
    // As many lines as the plain DEM's scene: the title added none.
    EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), std::count(plainText.begin(), plainText.end(), '\n'))
        << text;
    writeFileAtomically(dir / "scene.toml", text);
    const auto back = scene::readScene(dir / "scene.toml", diags);
    ASSERT_TRUE(back) << firstWarning(diags);
    EXPECT_FALSE(diags.hasErrors()) << firstWarning(diags);
    EXPECT_EQ(back->overlay.title, kHostileTitle);
    EXPECT_EQ(back->render.width, plain->scene.render.width);
    EXPECT_EQ(back->render.height, plain->scene.render.height);
    EXPECT_EQ(back->samples.path, dir / "dem.tif");
    for (const auto& d : diags.all()) EXPECT_EQ(d.message.find("UTF-8"), std::string::npos) << d.message;
}

// A value TOML writes on one line and reads back whole, whatever it holds.
TEST(Pipeline, TomlStringHoldsAnyText) {
    EXPECT_EQ(tomlString("a'''b"), "\"a'''b\"");
    EXPECT_EQ(tomlString("x\ny"), "\"x\\ny\"");
    EXPECT_EQ(tomlString("caf\xe9"), "\"caf\xEF\xBF\xBD\"");  // TOML holds only UTF-8
    for (const std::string& s : {kHostileTitle, std::string("\"\"\""), std::string("Monta\xc3\xb1" "a")}) {
        Diagnostics diags;
        const std::string toml = "[overlay]\ntitle = " + tomlString(s) + "\n";
        EXPECT_EQ(std::count(toml.begin(), toml.end(), '\n'), 2) << toml;
        const auto spec = scene::readSceneText(toml, "t.toml", diags);  // and an error: no [samples]
        ASSERT_TRUE(spec);
        EXPECT_EQ(spec->overlay.title, s);
    }
}

// A DEM's metadata in Latin-1 (as old GeoTIFFs have it) is read as Latin-1: the title and the
// credit as they were meant, in UTF-8, and nothing to warn of.
TEST(Pipeline, LatinOneMetadataIsReadAsLatinOne) {
    const fs::path dir = freshDir("latin1-metadata");
    copyDemWith(dir / "dem.tif", {{"TIFFTAG_DOCUMENTNAME", "Monta\xf1" "a del Fr\xedo"},
                                  {"TIFFTAG_COPYRIGHT", "\xa9 Instituto Geogr\xe1" "fico"}});
    Diagnostics diags;
    const auto loaded = loadScene(dir / "dem.tif", diags);
    ASSERT_TRUE(loaded) << firstWarning(diags);
    EXPECT_EQ(loaded->scene.overlay.title, "Monta\xc3\xb1" "a del Fr\xc3\xad" "o");
    const auto surface = planSurface(*loaded, diags, 1);
    ASSERT_TRUE(surface) << firstWarning(diags);
    EXPECT_EQ(surface->net.attribution, "\xc2\xa9 Instituto Geogr\xc3\xa1" "fico");
    for (const auto& d : diags.all()) EXPECT_EQ(d.message.find("UTF-8"), std::string::npos) << d.message;
}

// A DEM whose file name is not UTF-8 (Latin-1, as a Linux name may be) is found by its bytes,
// compiles, and its records write U+FFFD for them, with one warning.
TEST(Pipeline, AFileNamedInLatinOneCompilesAndItsRecordsAreUtf8) {
    const fs::path dir = freshDir("latin1-name");
    const fs::path dem = dir / "caf\xe9.tif";
    copyDemWith(dem, {{"TIFFTAG_DOCUMENTNAME", ""}});
    SceneJob job = compileJob(dem, dir / "caf\xe9.pov");
    job.overrides = {{"render.width", "160"}, {"render.height", "100"}};
    Diagnostics diags;
    const JobOutcome outcome = runSceneJob(job, diags, nullptr);
    ASSERT_EQ(outcome.status, JobStatus::Ok) << firstWarning(diags);
    Diagnostics again;
    const auto loaded = loadScene(dem, again, job.overrides);
    ASSERT_TRUE(loaded);
    EXPECT_EQ(loaded->scene.samples.path, dem);  // the bytes, not U+FFFD
    EXPECT_EQ(loaded->scene.overlay.title, "caf\xEF\xBF\xBD");
    EXPECT_TRUE(isUtf8(loaded->scene.madeForData));
    std::vector<std::string> said;
    for (const auto& d : diags.all())
        if (d.message.find("not UTF-8") != std::string::npos) said.push_back(formatDiagnostic(d));
    ASSERT_EQ(said.size(), 1u);  // the name, the title from it, the sidecar's paths: one warning
    EXPECT_TRUE(said[0].starts_with(dem.string() + ": warning: the file's name is not UTF-8: ")) << said[0];
    const std::string text = readFile(dir / "caf\xe9.json");
    EXPECT_TRUE(isUtf8(text));
    const auto sidecar = nlohmann::json::parse(text);
    EXPECT_EQ(sidecar["inputs"]["scene"], (dir / "caf\xEF\xBF\xBD.tif").string());
    EXPECT_EQ(sidecar["outputs"]["pov"], (dir / "caf\xEF\xBF\xBD.pov").string());
    EXPECT_TRUE(fs::exists(dir / "caf\xe9.pov"));

    // relief init cannot write that name in TOML: one error saying to rename it.
    Diagnostics init;
    EXPECT_FALSE(initCanNameData(dem, dir / "scene.toml", init));
    ASSERT_EQ(init.all().size(), 1u);
    EXPECT_EQ(formatDiagnostic(init.all()[0]),
              dem.string() + ": error: the scene would say samples.path = \"caf\xe9.tif\", which is not UTF-8, and "
                             "TOML holds only UTF-8: rename the file (or its folder) to a UTF-8 name and run relief "
                             "init again (relief render reads the file as it is named)");
    // A folder's name the scene does not write is no matter.
    EXPECT_TRUE(initCanNameData(dir / "caf\xe9" / "dem.tif", dir / "caf\xe9" / "dem.toml", init));
    EXPECT_EQ(init.all().size(), 1u);
}

TEST(Pipeline, DefaultDepthIsChosenForTheStill) {
    Diagnostics diags;
    const auto thumbnail = planForStill("160", "120", diags);
    const auto poster = planForStill("3840", "2160", diags);
    ASSERT_TRUE(thumbnail && poster) << (diags.all().empty() ? "" : formatDiagnostic(diags.all().back()));
    // The raster's own 5 m cells in its own CRS: a node on each of its 174 rows either way (the
    // thumbnail's pixel, ~5.5 m, is not twice as coarse).
    EXPECT_EQ(thumbnail->net.rows(), 174);
    EXPECT_EQ(poster->net.rows(), 174);
    // A pixel of the thumbnail covers ~3.6 m where the terrain is nearest, within sqrt(2) of the 5 m
    // net: no level; the poster's ~0.20 m: five (0.156 m).
    EXPECT_EQ(thumbnail->depth, 0) << thumbnail->depthReason;
    EXPECT_EQ(poster->depth, 5) << poster->depthReason;
    EXPECT_TRUE(thumbnail->depthReason.starts_with("chosen for the still: the net's 5 m refined to 5 m, about the 3.6"))
        << thumbnail->depthReason;
    EXPECT_TRUE(thumbnail->refined.grid.points.empty());  // planned, not refined
}

TEST(Pipeline, DefaultDepthIsLoweredToTheLimitsNotRefused) {
    Diagnostics diags;
    const auto capped =
        planForStill("3840", "2160", diags, {{"geometry.kind", "\"mesh2\""}, {"limits.max_triangles", "2000000"}});
    ASSERT_TRUE(capped) << (diags.all().empty() ? "" : formatDiagnostic(diags.all().back()));
    // 169 x 115 refined 3 times is 1345 x 913 nodes, 2.45e6 triangles: over; twice, 673 x 457: within.
    EXPECT_EQ(capped->depth, 2) << capped->depthReason;
    EXPECT_NE(capped->depthReason.find("(depth 5 would be over [limits])"), std::string::npos) << capped->depthReason;
    // A depth the scene gives is the scene's: over the limits, it is refused.
    Diagnostics refused;
    EXPECT_FALSE(planForStill(
        "3840", "2160", refused,
        {{"geometry.kind", "\"mesh2\""}, {"limits.max_triangles", "2000000"}, {"subdivision.depth", "5"}}));
}

TEST(Pipeline, AFineRasterGetsANetForTheStill) {
    Diagnostics diags;
    scene::SceneOverrides o{{"render.width", "160"}, {"render.height", "120"}};
    auto loaded = loadScene(testing::kSourceDir / "scenes/data/rasters/volcano2hires.tif", diags, o);
    ASSERT_TRUE(loaded);
    const auto s = planSurface(*loaded, diags, 1);
    ASSERT_TRUE(s);
    // 708 x 708 cells of 2.03 m, 1.44 km between the outermost centres: at 160 px a pixel is ~9.0 m,
    // about 4 cells: the net is the means of blocks of 4 x 4 cells, 8.14 m apart.
    const double cell = 1440.0 / 708;  // gdalinfo's pixel size
    EXPECT_NEAR(s->net.dx, 4 * cell, 1e-3);
    EXPECT_EQ(s->net.resample, scene::Resample::Average);
    EXPECT_TRUE(s->net.spacingReason.starts_with("about one pixel of the 160 px wide still")) << s->net.spacingReason;
}

// relief info's estimate (estimateSurface) over nets too large to read in a second: the same size,
// depth, geometry and cost as the plan that reads the net, swept over the ways a scene makes a net
// that large (a spacing, rows and columns, a still wide enough for the data's own spacing) and over
// the cameras that choose the depth; a net small enough to read is read.
TEST(Pipeline, InfoEstimatesWhatThePlanThatReadsTheNetFinds) {
    struct Case {
        const char* data;
        scene::SceneOverrides sets;
    };
    const char* const hires = "scenes/data/rasters/volcano2hires.tif";
    const char* const samples = "scenes/data/volcano_samples_1000_seed20251124.csv";
    const std::vector<Case> sweep = {
        {hires, {{"net.spacing_m", "0.9"}}},
        {hires, {{"net.rows", "1500"}, {"net.cols", "1700"}}},
        {hires, {{"net.spacing_m", "0.9"}, {"camera.elevation_deg", "5"}}},
        {hires, {{"net.spacing_m", "0.9"}, {"camera.position", "[174.7620,-36.8790,120]"},
                 {"camera.look_at", "[174.7640,-36.8765,150]"}}},
        {hires, {{"net.spacing_m", "0.9"}, {"subdivision.depth", "1"}}},
        {hires, {{"net.spacing_m", "1.2"}, {"render.width", "3000"}, {"render.height", "2000"}}},
        {"", {{"render.width", "1600"}, {"render.height", "1000"}}},  // blocks of 2 x 2 cells: 1600 x 1600
        {hires, {{"net.spacing_m", "4"}}},  // 360 x 360 nodes: read
        {samples, {{"net.spacing_m", "8"}}},
        {samples, {{"net.rows", "1600"}, {"net.cols", "1500"}}},
    };
    // A still's own net over a raster of 3200 x 3200 cells (NZTM, as the test DEM's, 1 m): the means
    // of blocks of 2 x 2.
    const fs::path big = relief::testing::freshTestDir("info-estimates") / "big.tif";
    {
        geo::setUpGdal();
        GDALDatasetH ds = GDALCreate(GDALGetDriverByName("GTiff"), big.c_str(), 3200, 3200, 1, GDT_Float32, nullptr);
        const double transform[6] = {1750000, 1, 0, 5920000, 0, -1};
        GDALSetGeoTransform(ds, const_cast<double*>(transform));
        GDALDatasetH nztm = GDALOpen((testing::kSourceDir / "tests/data/rasters/maungawhau-20m.tif").c_str(), GA_ReadOnly);
        ASSERT_NE(nztm, nullptr);
        GDALSetProjection(ds, GDALGetProjectionRef(nztm));
        GDALClose(nztm);
        std::vector<float> row(3200);
        GDALRasterBandH band = GDALGetRasterBand(ds, 1);
        for (int r = 0; r < 3200; ++r) {
            for (int c = 0; c < 3200; ++c) row[c] = float(100 + 50 * std::sin(c / 300.0) * std::cos(r / 400.0));
            ASSERT_EQ(GDALRasterIO(band, GF_Write, 0, r, 3200, 1, row.data(), 3200, 1, GDT_Float32, 0, 0), CE_None);
        }
        GDALSetRasterUnitType(band, "m");
        GDALClose(ds);
    }
    for (const auto& [data, sets] : sweep) {
        std::string said = std::string(*data ? data : "big.tif") + " ";
        for (const auto& [k, v] : sets) said += k + "=" + v + " ";
        Diagnostics diags;
        const auto loaded = loadScene(*data ? testing::kSourceDir / data : big, diags, sets);
        ASSERT_TRUE(loaded) << said << firstWarning(diags);
        const auto read = planSurface(*loaded, diags, 1);
        const auto estimated = estimateSurface(*loaded, diags);
        ASSERT_TRUE(read && estimated) << said << firstWarning(diags);
        const double nodes = double(read->net.rows()) * read->net.cols();
        EXPECT_EQ(estimated->heightsReadAtM > 0, nodes > kEstimateReadNodes) << said;
        EXPECT_EQ(estimated->size.rows, read->net.rows()) << said;
        EXPECT_EQ(estimated->size.cols, read->net.cols()) << said;
        EXPECT_EQ(estimated->size.dx, read->net.dx) << said;
        EXPECT_EQ(estimated->size.x0, read->net.x0) << said;
        EXPECT_EQ(estimated->size.y0, read->net.y0) << said;
        EXPECT_EQ(estimated->depth, read->depth) << said << estimated->depthReason << " | " << read->depthReason;
        EXPECT_EQ(estimated->geometry.kind, read->geometry.kind) << said;
        EXPECT_EQ(estimated->estimate.triangles, read->estimate.triangles) << said;
        EXPECT_EQ(estimated->estimate.memoryBytes, read->estimate.memoryBytes) << said;
        EXPECT_EQ(estimated->net.spacingReason, read->net.spacingReason) << said;
        // What is read, as laid out (how it is resampled is known once it is: not the estimate's to say).
        EXPECT_TRUE(read->net.raster.starts_with(estimated->net.raster)) << said << estimated->net.raster;
        // The stand-in's heights: block means, a little inside the net's own extremes.
        const auto [zmin, zmax] = read->net.grid.zRange();
        const auto [emin, emax] = estimated->net.grid.zRange();
        EXPECT_NEAR(emin, zmin, 0.02 * (zmax - zmin)) << said;
        EXPECT_NEAR(emax, zmax, 0.02 * (zmax - zmin)) << said;
    }
}

}  // namespace
}  // namespace relief
