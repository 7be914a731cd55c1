// Adjacent tiles ([samples] path = [...]) make the net the uncut raster makes.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <cpl_string.h>
#include <gdal_utils.h>

#include "core/diagnostics.h"
#include "geo/geo.h"
#include "geo/gdal_setup.h"
#include "geo/raster_mosaic.h"
#include "unit/test_dirs.h"

namespace relief::geo {
namespace {

namespace fs = std::filesystem;

const fs::path kDem = fs::path(RELIEF_SOURCE_DIR) / "scenes/data/rasters/volcano2.tif";  // 122 x 174 cells

// gdal_translate `args` from `from` to `to`, as the command line would.
void translate(const fs::path& from, const fs::path& to, std::vector<std::string> args) {
    CPLStringList list;
    for (const auto& a : args) list.AddString(a.c_str());
    GDALTranslateOptions* options = GDALTranslateOptionsNew(list.List(), nullptr);
    GDALDatasetH src = GDALOpen(from.c_str(), GA_ReadOnly);
    ASSERT_NE(src, nullptr);
    GDALDatasetH out = GDALTranslate(to.c_str(), src, options, nullptr);
    ASSERT_NE(out, nullptr);
    GDALClose(out);
    GDALClose(src);
    GDALTranslateOptionsFree(options);
}

// The DEM cut into four tiles at column 61 and row 87 (cells of the uncut raster each).
std::vector<fs::path> quarters(const fs::path& dir) {
    std::vector<fs::path> tiles;
    for (int r = 0; r < 2; ++r)
        for (int c = 0; c < 2; ++c) {
            tiles.push_back(dir / ("tile-" + std::to_string(r) + std::to_string(c) + ".tif"));
            translate(kDem, tiles.back(), {"-srcwin", std::to_string(61 * c), std::to_string(87 * r), "61", "87"});
        }
    return tiles;
}

std::optional<ControlNet> netOf(const fs::path& path, const std::vector<fs::path>& tiles, Diagnostics& diags) {
    scene::SamplesSpec samples;
    samples.path = path;
    samples.pathAsWritten = path.filename().string();
    samples.tiles = tiles;
    samples.verticalUnit = "m";
    samples.locs.keys["samples.path"] = {"scene.toml", 2, 8};
    scene::NetSpec net;
    net.spacingM = 5;
    return controlNet(samples, {}, net, NetLimits{NetBudget{}, 1000, std::nullopt}, diags);
}

TEST(Mosaic, FourTilesMakeTheNetOfTheUncutRaster) {
    setUpGdal();
    const fs::path dir = relief::testing::freshTestDir("relief-mosaic-four");
    const auto tiles = quarters(dir);
    Diagnostics diags;
    const auto whole = netOf(kDem, {}, diags);
    const auto mosaic = netOf(tiles.front(), tiles, diags);
    ASSERT_TRUE(whole && mosaic) << (diags.all().empty() ? "" : formatDiagnostic(diags.all().back()));
    EXPECT_TRUE(diags.all().empty()) << formatDiagnostic(diags.all().front());
    ASSERT_EQ(mosaic->rows(), whole->rows());
    ASSERT_EQ(mosaic->cols(), whole->cols());
    EXPECT_EQ(mosaic->x0, whole->x0);
    EXPECT_EQ(mosaic->y0, whole->y0);
    double worst = 0;
    for (size_t i = 0; i < whole->grid.points.size(); ++i)
        worst = std::max(worst, std::abs(mosaic->grid.points[i].z - whole->grid.points[i].z));
    EXPECT_LT(worst, 1e-9) << "the tiles' seams show in the net";
    EXPECT_TRUE(mosaic->masked.empty());
}

TEST(Mosaic, AMissingTileIsAGapAndSaidSo) {
    setUpGdal();
    const fs::path dir = relief::testing::freshTestDir("relief-mosaic-gap");
    auto tiles = quarters(dir);
    tiles.erase(tiles.begin() + 1);  // the north-east quarter
    Diagnostics diags;
    const auto net = netOf(tiles.front(), tiles, diags);
    ASSERT_TRUE(net);
    ASSERT_EQ(diags.all().size(), 1u);
    EXPECT_EQ(formatDiagnostic(diags.all()[0]),
              "scene.toml:2:8: warning: samples.path: the 3 tiles cover 75.0 % of their "
              "bounding box; the rest has no data (samples.nodata says what becomes of it): is a tile missing?");
    EXPECT_GT(net->maskedCount(), net->grid.points.size() / 5);  // the quarter left out
}

TEST(Mosaic, TilesInDifferentCrssAreAnErrorNamingBoth) {
    setUpGdal();
    const fs::path dir = relief::testing::freshTestDir("relief-mosaic-crs");
    auto tiles = quarters(dir);
    translate(tiles[3], dir / "utm.tif", {"-a_srs", "EPSG:32760"});
    tiles[3] = dir / "utm.tif";
    Diagnostics diags;
    EXPECT_FALSE(netOf(tiles.front(), tiles, diags));
    ASSERT_EQ(diags.all().size(), 1u);
    EXPECT_EQ(formatDiagnostic(diags.all()[0]),
              "scene.toml:2:8: error: samples.path: the tiles tile-00.tif (NZGD2000 "
              "/ New Zealand Transverse Mercator 2000) and utm.tif (WGS 84 / UTM zone 60S) are in different CRSs: "
              "reproject one into the other's (gdalwarp -t_srs) so that all are in one");
}

// A folder as samples.path: its rasters in the order of their names, not the
// other files in it, GDAL's side files (an external overview is a TIFF
// GDAL reads), hidden files or subfolders; the net is the one the list makes.
TEST(Mosaic, AFolderIsItsRasterTiles) {
    setUpGdal();
    const fs::path dir = relief::testing::freshTestDir("relief-mosaic-folder");
    const auto tiles = quarters(dir);
    translate(tiles[0], dir / "tile-00.tif.ovr", {"-of", "GTiff", "-outsize", "50%", "50%"});
    translate(tiles[0], dir / ".hidden.tif", {});
    std::ofstream(dir / "README.txt") << "LiDAR tiles, 2013\n";
    fs::create_directory(dir / "old");
    translate(tiles[0], dir / "old" / "tile-00.tif", {});
    std::string problem;
    EXPECT_EQ(rasterTilesIn(dir, problem), tiles) << problem;
    Diagnostics diags;
    const auto listed = netOf(tiles.front(), tiles, diags);
    const auto folder = netOf(dir, {}, diags);
    ASSERT_TRUE(listed && folder) << (diags.all().empty() ? "" : formatDiagnostic(diags.all().back()));
    ASSERT_EQ(folder->grid.points.size(), listed->grid.points.size());
    for (size_t i = 0; i < listed->grid.points.size(); ++i)
        ASSERT_EQ(folder->grid.points[i].z, listed->grid.points[i].z);

    const fs::path empty = dir / "old" / "empty";
    fs::create_directory(empty);
    EXPECT_TRUE(rasterTilesIn(empty, problem).empty());
    EXPECT_EQ(problem, "the folder holds no raster GDAL reads");
}

}  // namespace
}  // namespace relief::geo
