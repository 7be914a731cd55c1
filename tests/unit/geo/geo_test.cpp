#include "geo/geo.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <utility>
#include <vector>

#include <fmt/format.h>

#include "unit/test_dirs.h"

namespace relief::geo {
namespace {

namespace fs = std::filesystem;

scene::SamplesSpec samplesAt(const fs::path& path) {
    scene::SamplesSpec s;
    s.path = path;
    s.pathAsWritten = path.filename().string();
    return s;
}

// A tilted plane as an ESRI ASCII grid in NZTM (EPSG:2193), 20 x 20 cells of 10 m.
fs::path writeGrid(const fs::path& dir) {
    const fs::path path = dir / "plane.asc";
    std::ofstream out(path);
    out << "ncols 20\nnrows 20\nxllcenter 1757000\nyllcenter 5917000\ncellsize 10\nNODATA_value -9999\n";
    for (int r = 0; r < 20; ++r)
        for (int c = 0; c < 20; ++c) out << 100 + c - 0.5 * r << (c + 1 < 20 ? " " : "\n");
    return path;
}

// Samples off any lattice: a spiral near Auckland.
fs::path writeScattered(const fs::path& dir, int count) {
    const fs::path path = dir / "spiral.csv";
    std::ofstream out(path);
    out << "lon,lat,elev\n";
    for (int i = 0; i < count; ++i) {
        const double a = 0.7 * i, r = 0.0002 * (1 + i);
        out << fmt::format("{:.7f},{:.7f},{}\n", 174.76 + r * std::cos(a), -36.87 + r * std::sin(a), 50 + i);
    }
    return path;
}

using Events = std::vector<std::pair<std::string, int>>;
NetProgressFn recordInto(Events& events) {
    return [&events](const std::string& task, int percent) { events.emplace_back(task, percent); };
}

const NetLimits kRoomy{NetBudget{}, 1000, std::nullopt};

TEST(ControlNet, TheLastSourceTakesAnyFile) {
    ASSERT_GE(sampleSources().size(), 2u);
    EXPECT_TRUE(sampleSources().back().recognises("no-such-file.csv"));
    EXPECT_EQ(sampleSources().back().name, "a CSV of samples");
    EXPECT_FALSE(sampleSources().back().raster);
}

// One table answers what a file is, for controlNet and for a DEM named in place of a scene.
TEST(ControlNet, TheSourceOfAFileIsTheTablesFirstThatTakesIt) {
    const fs::path dir = relief::testing::freshTestDir("relief-control-net-recognised");
    const fs::path grid = writeGrid(dir);
    EXPECT_EQ(recognisedSource(grid).name, "a raster DEM");
    EXPECT_TRUE(recognisedSource(grid).raster);
    EXPECT_EQ(recognisedSource(dir).name, "a folder of raster tiles");
    EXPECT_TRUE(recognisedSource(dir).raster);
    EXPECT_EQ(recognisedSource(dir / "no-such-file.csv").name, "a CSV of samples");
}

TEST(ControlNet, ARasterIsResampledTellingItsPercent) {
    const fs::path dir = relief::testing::freshTestDir("relief-control-net-raster");
    auto samples = samplesAt(writeGrid(dir));
    samples.crs = "EPSG:2193";
    Events events;
    Diagnostics diags;
    const auto net = controlNet(samples, {}, {}, kRoomy, diags, recordInto(events));
    ASSERT_TRUE(net) << (diags.all().empty() ? "" : formatDiagnostic(diags.all()[0]));
    EXPECT_NE(net->raster.find("20 x 20 cells, band 1"), std::string::npos) << net->raster;
    ASSERT_FALSE(events.empty());
    for (const auto& [task, percent] : events) EXPECT_EQ(task, "resampling the raster");
    EXPECT_EQ(events.back().second, 100);
}

TEST(ControlNet, ScatteredSamplesAreGriddedAfterALineSayingSo) {
    const fs::path dir = relief::testing::freshTestDir("relief-control-net-scattered");
    Events events;
    Diagnostics diags;
    const auto net = controlNet(samplesAt(writeScattered(dir, 40)), {}, {}, kRoomy, diags, recordInto(events));
    ASSERT_TRUE(net) << (diags.all().empty() ? "" : formatDiagnostic(diags.all()[0]));
    EXPECT_EQ(net->sampleCount, 40u);
    EXPECT_TRUE(net->raster.empty());
    ASSERT_FALSE(events.empty());
    EXPECT_EQ(events.front(), std::make_pair(std::string("gridding 40 samples"), -1));
    EXPECT_EQ(events.back().second, 100);
}

TEST(ControlNet, RasterKeysOnScatteredSamplesAreErrorsAtTheKeys) {
    const fs::path dir = relief::testing::freshTestDir("relief-control-net-keys");
    auto samples = samplesAt(writeScattered(dir, 40));
    samples.locs.keys["samples.band"] = {"scene.toml", 4, 8};
    Diagnostics diags;
    EXPECT_FALSE(controlNet(samples, {}, {}, kRoomy, diags));
    ASSERT_EQ(diags.errorCount(), 1);
    EXPECT_EQ(diags.all()[0].loc.line, 4);
    EXPECT_EQ(diags.all()[0].message,
              "samples.band is only used with a raster DEM, and GDAL does not read spiral.csv as a raster "
              "(relief takes it for a CSV of samples): remove it");
}

// Memory errors name the limit where the scene sets it, else the samples file.
TEST(ControlNet, GriddingOverTheMemoryIsRefusedAtTheLimit) {
    const fs::path dir = relief::testing::freshTestDir("relief-control-net-memory");
    const auto samples = samplesAt(writeScattered(dir, 1000));
    const NetLimits tight{NetBudget{}, 1, SourceLoc{"scene.toml", 9, 17}};
    Diagnostics diags;
    EXPECT_FALSE(controlNet(samples, {}, {}, tight, diags));
    ASSERT_EQ(diags.errorCount(), 1);
    EXPECT_EQ(diags.all()[0].loc.line, 9);
    EXPECT_NE(diags.all()[0].message.find("gridding 1000 samples needs about 2 MB"), std::string::npos);
    Diagnostics unset;
    EXPECT_FALSE(controlNet(samples, {}, {}, NetLimits{NetBudget{}, 1, std::nullopt}, unset));
    ASSERT_EQ(unset.errorCount(), 1);
    EXPECT_EQ(unset.all()[0].loc.file, "spiral.csv");
}

}  // namespace
}  // namespace relief::geo
