#include "geo/raster.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include <GeographicLib/TransverseMercator.hpp>
#include <GeographicLib/UTMUPS.hpp>
#include <fmt/format.h>
#include <cpl_conv.h>
#include <gdal.h>
#include <ogr_srs_api.h>

#include "geo/gdal_setup.h"
#include "geo/samples.h"
#include "unit/test_dirs.h"

namespace relief::geo {
namespace {

namespace fs = std::filesystem;

fs::path freshDir(const std::string& name) {
    const fs::path dir = relief::testing::freshTestDir("relief-raster-" + name);
    return dir;
}

// New Zealand Transverse Mercator (EPSG:2193) from WGS84, independently of
// PROJ: GeographicLib's transverse Mercator with NZTM's parameters (GRS80 and
// WGS84 differ by 0.1 mm in the semi-minor axis; NZGD2000 is tied to ITRF).
void nztm(double lat, double lon, double& e, double& n) {
    static const GeographicLib::TransverseMercator tm(6378137, 1 / 298.257222101, 0.9996);
    tm.Forward(173, lat, lon, e, n);
    e += 1600000;
    n += 10000000;
}

// A tilted plane written as an ESRI ASCII grid in NZTM (cell centres at
// x0 + 10 i), with `nodataCells` of its first row set to NODATA.
constexpr double kX0 = 1757000, kY0 = 5917000, kCell = 10;
double plane(double e, double n) { return 100 + 0.1 * (e - kX0) - 0.05 * (n - kY0); }
fs::path writePlane(const fs::path& dir, int cols, int rows, int nodataCells = 0) {
    const fs::path path = dir / "plane.asc";
    std::ofstream out(path);
    out << fmt::format("ncols {}\nnrows {}\nxllcenter {}\nyllcenter {}\ncellsize {}\nNODATA_value -9999\n", cols,
                       rows, kX0, kY0, kCell);
    for (int r = rows - 1; r >= 0; --r) {
        for (int c = 0; c < cols; ++c) {
            const bool missing = r == rows - 1 && c < nodataCells;
            out << (missing ? -9999.0 : plane(kX0 + kCell * c, kY0 + kCell * r)) << (c + 1 < cols ? " " : "\n");
        }
    }
    return path;
}

// The frame a scene names: `kind = "utm"` (the zone of the data's centre) or another kind.
scene::FrameSpec namedFrame(scene::FrameKind kind = scene::FrameKind::Utm) {
    scene::FrameSpec frame;
    frame.kind = kind;
    frame.locs.keys["frame.kind"] = {"scene.toml", 2, 8};
    return frame;
}

// An ESRI ASCII grid of kCell cells, the south-west cell's centre at (x0, y0), cell(c, r) with row 0 south.
template <class CellFn>
void writeCells(const fs::path& path, int cols, int rows, double x0, double y0, CellFn cell) {
    std::ofstream out(path);
    out << fmt::format("ncols {}\nnrows {}\nxllcenter {}\nyllcenter {}\ncellsize {}\n", cols, rows, x0, y0, kCell);
    for (int r = rows - 1; r >= 0; --r)
        for (int c = 0; c < cols; ++c) out << cell(c, r) << (c + 1 < cols ? " " : "\n");
}

scene::SamplesSpec rasterSpec(const fs::path& path, const std::string& crs, const std::string& verticalUnit = "") {
    scene::SamplesSpec s;
    s.path = path;
    s.pathAsWritten = path.filename().string();
    s.crs = crs;
    s.verticalUnit = verticalUnit;
    return s;
}

// The net of the scene relief init writes (net.spacing_m and resample =
// "average" given) is the net chosen for the still, node for node.
void expectInitsNetIsTheChosen(const fs::path& path, const std::string& crs, const scene::FrameSpec& frame,
                               double spacingM, const ControlNet& chosen) {
    auto spec = rasterSpec(path, crs);
    spec.resample = scene::Resample::Average;
    spec.locs.keys["samples.resample"] = {};
    scene::NetSpec given;
    given.spacingM = spacingM;
    Diagnostics diags;
    const auto written = rasterNet(spec, frame, given, diags);
    ASSERT_TRUE(written) << (diags.all().empty() ? "" : formatDiagnostic(diags.all()[0]));
    ASSERT_EQ(written->cols(), chosen.cols());
    ASSERT_EQ(written->rows(), chosen.rows());
    EXPECT_EQ(written->x0, chosen.x0);
    EXPECT_EQ(written->y0, chosen.y0);
    for (size_t i = 0; i < chosen.grid.points.size(); ++i)
        ASSERT_EQ(written->grid.points[i].z, chosen.grid.points[i].z) << i;
}

// The whole chain: net node in UTM 60S -> WGS84 (GeographicLib) -> NZTM
// (PROJ) -> pixel, bilinear there. A plane is reproduced exactly by bilinear
// resampling, so each height equals the plane at the node's NZTM position
// computed independently: a positioning error of 0.1 m would show as 0.01 m.
TEST(Raster, PlaneInANationalGridLandsWhereItShould) {
    const fs::path dir = freshDir("plane");
    const auto spec = rasterSpec(writePlane(dir, 60, 50), "EPSG:2193");
    ASSERT_TRUE(isRasterDem(spec.path));
    scene::NetSpec net;
    net.spacingM = 7;  // not the raster's cell: nodes fall between cells
    Diagnostics diags;
    const auto result = rasterNet(spec, namedFrame(), net, diags);
    ASSERT_TRUE(result) << (diags.all().empty() ? "" : formatDiagnostic(diags.all()[0]));
    EXPECT_EQ(result->frame.describe(), "UTM zone 60S");
    EXPECT_EQ(result->filledNodata, 0u);
    EXPECT_GT(result->rows(), 50);
    int checked = 0;
    for (const Vec3& p : result->grid.points) {
        double lat, lon, gamma, k;
        GeographicLib::UTMUPS::Reverse(60, false, p.x, p.y, lat, lon, gamma, k);
        double e, n;
        nztm(lat, lon, e, n);
        // Between the outermost cell centres and the raster's edge bilinear has
        // no second cell to lean on (GDAL repeats the edge): only inside is exact.
        if (e < kX0 || e > kX0 + 59 * kCell || n < kY0 || n > kY0 + 49 * kCell) continue;
        ASSERT_NEAR(p.z, plane(e, n), 0.01) << "node at " << p.x << ", " << p.y;
        ++checked;
    }
    EXPECT_GT(checked, 0.9 * result->rows() * result->cols());
    EXPECT_EQ(diags.warningCount(), 1);  // an ESRI grid has no vertical unit: metres assumed, and said
}

// A lon/lat window: the net is the largest box of the frame inside it, and
// still lands where it should.
TEST(Raster, LonLatWindowChoosesTheNet) {
    const fs::path dir = freshDir("window");
    const auto spec = rasterSpec(writePlane(dir, 60, 50), "EPSG:2193");
    scene::NetSpec net;
    net.spacingM = 5;
    const LonLatBox window{174.7630, -36.8790, 174.7655, -36.8770};
    net.extentLonLat = window;
    Diagnostics diags;
    const auto result = rasterNet(spec, namedFrame(), net, diags);
    ASSERT_TRUE(result) << (diags.all().empty() ? "" : formatDiagnostic(diags.all()[0]));
    EXPECT_EQ(result->filledNodata, 0u);
    for (const Vec3& p : result->grid.points) {
        double lat, lon, gamma, k;
        GeographicLib::UTMUPS::Reverse(60, false, p.x, p.y, lat, lon, gamma, k);
        EXPECT_GE(lon, window.west);
        EXPECT_LE(lon, window.east);
        EXPECT_GE(lat, window.south);
        EXPECT_LE(lat, window.north);
        double e, n;
        nztm(lat, lon, e, n);
        ASSERT_NEAR(p.z, plane(e, n), 0.01);
    }
    // 0.0025 deg of longitude at 36.9 S is 223 m, 0.002 deg of latitude 222 m: a 5 m net of about 44 x 44.
    EXPECT_NEAR(result->cols(), 44, 1);
    EXPECT_NEAR(result->rows(), 44, 1);
}

// Vertical units: feet become metres, metres stay, and no warning is given
// when the raster names its unit.
TEST(Raster, FeetBecomeMetres) {
    const fs::path dir = freshDir("feet");
    setUpGdal();
    for (const char* unit : {"ft", "m"}) {
        const fs::path path = dir / (std::string(unit) + ".tif");
        {
            GDALDatasetH ds = GDALCreate(GDALGetDriverByName("GTiff"), path.c_str(), 20, 20, 1, GDT_Float32, nullptr);
            double geo[6] = {kX0 - 0.5 * kCell, kCell, 0, kY0 + 19.5 * kCell, 0, -kCell};
            GDALSetGeoTransform(ds, geo);
            GDALSetProjection(ds, "EPSG:2193");
            GDALRasterBandH band = GDALGetRasterBand(ds, 1);
            GDALSetRasterUnitType(band, unit);
            std::vector<float> values(400, 1000.0f);
            ASSERT_EQ(GDALRasterIO(band, GF_Write, 0, 0, 20, 20, values.data(), 20, 20, GDT_Float32, 0, 0), CE_None);
            GDALClose(ds);
        }
        scene::NetSpec net;
        net.spacingM = kCell;
        Diagnostics diags;
        const auto result = rasterNet(rasterSpec(path, ""), {}, net, diags);
        ASSERT_TRUE(result) << (diags.all().empty() ? "" : formatDiagnostic(diags.all()[0]));
        EXPECT_EQ(diags.warningCount(), 0) << unit;
        for (const Vec3& p : result->grid.points) EXPECT_DOUBLE_EQ(p.z, unit[0] == 'f' ? 304.8 : 1000.0) << unit;
    }
}

// A raster that does not name its unit: a warning that says how to name it,
// and none once the scene's vertical_unit does; "ft" converts.
TEST(Raster, SceneNamesTheVerticalUnit) {
    const fs::path dir = freshDir("unitless");
    auto spec = rasterSpec(writePlane(dir, 20, 20), "EPSG:2193");
    scene::NetSpec net;
    net.spacingM = kCell;
    Diagnostics unnamed;
    const auto metres = rasterNet(spec, {}, net, unnamed);
    ASSERT_TRUE(metres);
    ASSERT_EQ(unnamed.warningCount(), 1);
    EXPECT_NE(formatDiagnostic(unnamed.all()[0]).find("say so with vertical_unit = \"m\""), std::string::npos);
    spec.verticalUnit = "ft";
    Diagnostics named;
    const auto feet = rasterNet(spec, {}, net, named);
    ASSERT_TRUE(feet);
    EXPECT_EQ(named.warningCount(), 0);
    for (size_t i = 0; i < feet->grid.points.size(); ++i)
        EXPECT_NEAR(feet->grid.points[i].z, 0.3048 * metres->grid.points[i].z, 1e-9);
}

// Nodata cells: masked (the default: left out of the mesh), filled from the
// neighbours and counted, or an error that says how many and where.
TEST(Raster, NodataIsMaskedFilledOrAnError) {
    const fs::path dir = freshDir("nodata");
    auto spec = rasterSpec(writePlane(dir, 40, 30, 10), "EPSG:2193");
    scene::NetSpec net;
    net.spacingM = kCell;
    Diagnostics diags;
    const auto masked = rasterNet(spec, {}, net, diags);
    ASSERT_TRUE(masked);
    EXPECT_EQ(masked->filledNodata, 0u);
    const size_t holes = masked->maskedCount();
    EXPECT_GT(holes, 0u);
    EXPECT_LT(holes, 40u);
    for (int r = 0; r < masked->rows(); ++r)
        for (int c = 0; c < masked->cols(); ++c) {
            EXPECT_TRUE(std::isfinite(masked->grid.at(r, c).z));  // the refiner reads them all
            // The nodata cells are the first 10 of the raster's north row, so every hole is in the
            // net's north-west, within a cell or two of them.
            if (masked->isMasked(r, c)) {
                EXPECT_GE(r, masked->rows() - 3) << r << " " << c;
                EXPECT_LE(c, 12) << r << " " << c;
            }
        }

    spec.nodata = scene::NodataPolicy::Fill;
    Diagnostics fillDiags;
    const auto filled = rasterNet(spec, {}, net, fillDiags);
    ASSERT_TRUE(filled);
    EXPECT_EQ(filled->filledNodata, holes);
    EXPECT_TRUE(filled->masked.empty());
    for (const Vec3& p : filled->grid.points) EXPECT_TRUE(std::isfinite(p.z) && p.z > 0 && p.z < 200);

    spec.nodata = scene::NodataPolicy::Error;
    spec.locs.keys["samples.nodata"] = {"s.toml", 4, 10};
    Diagnostics strict;
    EXPECT_FALSE(rasterNet(spec, {}, net, strict));
    ASSERT_EQ(strict.errorCount(), 1);
    const std::string message = formatDiagnostic(strict.all().back());
    EXPECT_EQ(message.rfind("s.toml:4:10: error: ", 0), 0u) << message;
    EXPECT_NE(message.find(fmt::format("{} of the net's", holes)), std::string::npos) << message;
    EXPECT_NE(message.find("the first at lat -36.8"), std::string::npos) << message;
}

// A raster with a nodata border defaults to the box of its data, not to its
// whole footprint: the net ends where the data end.
TEST(Raster, DefaultExtentIsTheDataNotTheBorder) {
    const fs::path dir = freshDir("border");
    const fs::path path = dir / "island.asc";
    {
        std::ofstream out(path);
        out << fmt::format("ncols 60\nnrows 50\nxllcenter {}\nyllcenter {}\ncellsize {}\nNODATA_value -9999\n",
                           kX0, kY0, kCell);
        for (int r = 49; r >= 0; --r)
            for (int c = 0; c < 60; ++c) {
                const bool data = r >= 10 && r < 30 && c >= 20 && c < 50;  // 30 x 20 cells of data
                out << (data ? plane(kX0 + kCell * c, kY0 + kCell * r) : -9999.0) << (c + 1 < 60 ? " " : "\n");
            }
    }
    scene::NetSpec net;
    net.spacingM = kCell;
    Diagnostics diags;
    const auto result = rasterNet(rasterSpec(path, "EPSG:2193"), {}, net, diags);
    ASSERT_TRUE(result) << (diags.all().empty() ? "" : formatDiagnostic(diags.all()[0]));
    // 300 x 200 m of data, their cells' centres 290 x 190 m apart; the inner box in UTM (rotated by
    // grid convergence) is a little smaller.
    EXPECT_NEAR(result->xMax() - result->x0, 290, 25);
    EXPECT_NEAR(result->yMax() - result->y0, 190, 25);
    EXPECT_LT(result->maskedCount(), result->grid.points.size() / 10);

    // A net relief makes coarser for a still 10 px wide: the box of the data found from the averaged
    // cells (laid first over the whole raster, 590 m: 59 m, 5 x 5 cells averaged), then the net
    // over the data (about 29 m), not over the border.
    NetBudget still;
    still.stillWidthPx = 10;
    Diagnostics coarseDiags;
    const auto coarse = rasterNet(rasterSpec(path, "EPSG:2193"), {}, {}, coarseDiags, {}, still);
    ASSERT_TRUE(coarse) << (coarseDiags.all().empty() ? "" : formatDiagnostic(coarseDiags.all()[0]));
    EXPECT_GT(coarse->dx, 2 * kCell);
    EXPECT_GT(coarse->xMax() - coarse->x0, 290 - 2 * coarse->dx);
    EXPECT_LT(coarse->xMax() - coarse->x0, 300);  // the border's 590 m would be twice that
    EXPECT_LT(coarse->maskedCount(), coarse->grid.points.size() / 4);
}

// A raster in the frame's own CRS with no nodata, at its own spacing: a node
// on each cell's centre, holding that cell's height; none masked (on the
// cells' outer edges, the outermost ring would have no data).
TEST(Raster, OwnSpacingPutsTheNodesOnTheCellCentres) {
    const fs::path dir = freshDir("centres");
    const fs::path path = dir / "utm.asc";
    constexpr int kCols = 30, kRows = 20;
    constexpr double kEast = 300005, kNorth = 5916005;                        // UTM 60S, the first cell's centre
    auto cell = [](int c, int r) { return 100.0 + (c * 7 % 13) + 0.5 * r; };  // not a plane: centres or nothing
    writeCells(path, kCols, kRows, kEast, kNorth, cell);
    for (const double spacing : {0.0, kCell}) {  // the default, and the same spacing given
        scene::NetSpec net;
        net.spacingM = spacing;
        Diagnostics diags;
        const auto result = rasterNet(rasterSpec(path, "EPSG:32760"), namedFrame(), net, diags);
        ASSERT_TRUE(result) << (diags.all().empty() ? "" : formatDiagnostic(diags.all()[0]));
        EXPECT_EQ(result->frame.describe(), "UTM zone 60S");
        ASSERT_EQ(result->cols(), kCols);
        ASSERT_EQ(result->rows(), kRows);
        EXPECT_EQ(result->maskedCount(), 0u);
        EXPECT_NEAR(result->x0, kEast, 1e-6);
        EXPECT_NEAR(result->y0, kNorth, 1e-6);
        // Within the warper's positional tolerance (0.001 cells; neighbours differ by up to 12 m).
        for (int r = 0; r < kRows; ++r)
            for (int c = 0; c < kCols; ++c) ASSERT_NEAR(result->grid.at(r, c).z, cell(c, r), 0.02) << r << " " << c;
    }
}

// A raster in a national grid, with no frame in the scene: the frame is its
// own CRS, a node on each cell's centre holding that cell's height exactly
// (read, not resampled), and the nodes land on the Earth where NZTM puts them
// (GeographicLib's transverse Mercator, independently of PROJ).
TEST(Raster, ItsOwnCrsIsTheFrameAndItsCellsTheNet) {
    const fs::path dir = freshDir("own-crs");
    const fs::path path = dir / "nztm.asc";
    constexpr int kCols = 30, kRows = 20;
    auto cell = [](int c, int r) { return 100.0 + (c * 7 % 13) + 0.25 * r; };  // not a plane
    writeCells(path, kCols, kRows, kX0, kY0, cell);
    Diagnostics diags;
    const auto result = rasterNet(rasterSpec(path, "EPSG:2193"), {}, {}, diags);
    ASSERT_TRUE(result) << (diags.all().empty() ? "" : formatDiagnostic(diags.all()[0]));
    EXPECT_EQ(result->frame.kind, scene::FrameKind::Raster);
    EXPECT_EQ(result->frame.describe(), "NZGD2000 / New Zealand Transverse Mercator 2000 (the raster's own CRS)");
    ASSERT_EQ(result->cols(), kCols);
    ASSERT_EQ(result->rows(), kRows);
    EXPECT_TRUE(result->copiedCells);
    EXPECT_EQ(result->dx, kCell);
    EXPECT_NEAR(result->x0, kX0, 1e-9);
    EXPECT_NEAR(result->y0, kY0, 1e-9);
    for (int r = 0; r < kRows; ++r)
        for (int c = 0; c < kCols; ++c) ASSERT_EQ(result->grid.at(r, c).z, cell(c, r)) << r << " " << c;
    for (const Vec3& p : {result->grid.at(0, 0), result->grid.at(kRows - 1, kCols - 1)}) {
        const auto g = reverse(result->frame, p);
        ASSERT_TRUE(g);
        double e, n;
        nztm(g->latDeg, g->lonDeg, e, n);
        EXPECT_NEAR(e, p.x, 0.001);
        EXPECT_NEAR(n, p.y, 0.001);
        EXPECT_EQ(g->heightM, p.z);
        const auto back = forward(result->frame, *g);
        ASSERT_TRUE(back);
        EXPECT_NEAR(back->x, p.x, 1e-6);
        EXPECT_NEAR(back->y, p.y, 1e-6);
    }
    // Grid north in NZTM at 174.76 E, 36.88 S: about (174.76 - 173) sin(36.88) = 1.06 degrees west of true
    // north, as GeographicLib's transverse Mercator gives it.
    const Vec3 centre = result->grid.at(kRows / 2, kCols / 2);
    const auto g = reverse(result->frame, centre);
    ASSERT_TRUE(g);
    static const GeographicLib::TransverseMercator tm(6378137, 1 / 298.257222101, 0.9996);
    double e, n, gamma, k;
    tm.Forward(173, g->latDeg, g->lonDeg, e, n, gamma, k);
    EXPECT_NEAR(gridConvergenceDeg(result->frame, centre.x, centre.y), gamma, 1e-5);

    // The scene names UTM: the cells are reprojected into its zone, and resampled.
    Diagnostics utmDiags;
    const auto utm = rasterNet(rasterSpec(path, "EPSG:2193"), namedFrame(), {}, utmDiags);
    ASSERT_TRUE(utm);
    EXPECT_EQ(utm->frame.describe(), "UTM zone 60S");
    EXPECT_FALSE(utm->copiedCells);
}

// A net relief makes coarser for the still, in the raster's own frame: the
// centres of blocks of k x k cells (k the still's pixel in whole cells), each
// node its block's mean; a scene that gives that spacing and the average (as
// relief init writes it) reads the same blocks.
TEST(Raster, ACoarserNetInItsOwnCrsIsTheMeansOfBlocksOfCells) {
    const fs::path dir = freshDir("blocks");
    const fs::path path = dir / "nztm.asc";
    constexpr int kCols = 30, kRows = 21;
    auto cell = [](int c, int r) { return 100.0 + (c * 7 % 13) + 0.25 * r; };  // row 0 south
    writeCells(path, kCols, kRows, kX0, kY0, cell);
    NetBudget still;
    still.stillWidthPx = 7;  // 290 m across: 42 m a pixel, about 4 cells
    Diagnostics diags;
    const auto chosen = rasterNet(rasterSpec(path, "EPSG:2193"), {}, {}, diags, {}, still);
    ASSERT_TRUE(chosen) << (diags.all().empty() ? "" : formatDiagnostic(diags.all()[0]));
    EXPECT_EQ(chosen->resample, scene::Resample::Average);
    EXPECT_EQ(chosen->dx, 4 * kCell);
    // 30 columns: 7 blocks, the 2 columns left over split between the edges; 21 rows: 5 blocks, 1 left.
    ASSERT_EQ(chosen->cols(), 7);
    ASSERT_EQ(chosen->rows(), 5);
    EXPECT_NEAR(chosen->x0, kX0 + 1 * kCell + 1.5 * kCell, 1e-9);
    EXPECT_NE(chosen->raster.find("the mean of each 4 x 4 cells"), std::string::npos) << chosen->raster;
    for (int i = 0; i < 5; ++i)  // block rows from the north: cell rows (from the north) 4 i .. 4 i + 3
        for (int j = 0; j < 7; ++j) {
            double sum = 0;
            for (int a = 0; a < 4; ++a)
                for (int b = 0; b < 4; ++b) sum += cell(1 + 4 * j + b, kRows - 1 - (4 * i + a));
            ASSERT_NEAR(chosen->grid.at(4 - i, j).z, sum / 16, 1e-9) << i << " " << j;
        }

    expectInitsNetIsTheChosen(path, "EPSG:2193", namedFrame(scene::FrameKind::Raster), 4 * kCell, *chosen);
}

// Rounding the block side to the nearest whole cells may give more nodes
// than the net the still asked for; when those pass the limits, the blocks
// are one cell wider a side, never an error.
TEST(Raster, BlocksOneCellWiderWhenTheNearestPassTheLimits) {
    const fs::path path = freshDir("blocks-wider") / "nztm.asc";
    writeCells(path, 60, 40, kX0, kY0, [](int c, int r) { return 100.0 + (c * 7 % 13) + 0.25 * r; });
    NetBudget still;
    still.stillWidthPx = 14;  // 600 m across: 42.9 m a pixel, 4.3 cells, nearest 4
    Diagnostics diags;
    const auto nearest = rasterNet(rasterSpec(path, "EPSG:2193"), {}, {}, diags, {}, still);
    ASSERT_TRUE(nearest) << (diags.all().empty() ? "" : formatDiagnostic(diags.all()[0]));
    ASSERT_EQ(nearest->dx, 4 * kCell);
    const int blockNodes = nearest->rows() * nearest->cols();
    still.fits = [&](const GeoGrid& laidOut, Diagnostics& d) {
        if (laidOut.rows() * laidOut.cols() < blockNodes) return true;
        d.error({}, "over the limits");
        return false;
    };
    Diagnostics limited;
    const auto wider = rasterNet(rasterSpec(path, "EPSG:2193"), {}, {}, limited, {}, still);
    ASSERT_TRUE(wider) << (limited.all().empty() ? "" : formatDiagnostic(limited.all()[0]));
    EXPECT_FALSE(limited.hasErrors());
    EXPECT_EQ(wider->dx, 5 * kCell);
    EXPECT_LT(wider->rows() * wider->cols(), blockNodes);
    EXPECT_NE(wider->raster.find("the mean of each 5 x 5 cells"), std::string::npos) << wider->raster;
}

// Block means are exact whatever the file brings: a GeoTIFF wider than the
// data scan reads (1024 cells) and taller than one read of blocks (119 rows
// of them here), with a nodata border (-9999.1, which a Float32 cell holds as
// -9999.099609375: GDAL's GTiff driver says so, not every driver does; see
// heightBand) and gdaladdo's nearest overviews, which
// RasterIO's average would read. The net chosen for the still and the one
// relief init writes (spacing_m 4 cells, resample "average") find the same
// box among the block means.
TEST(Raster, BlockMeansAreExactWithOverviewsAndANodataBorder) {
    const fs::path path = freshDir("block-means") / "nztm.tif";
    constexpr int kCols = 1102, kRows = 602, kWest = 5, kEast = 7, kNorth = 3;  // nodata columns and rows
    constexpr int kBlockRows = 150;                                             // 602 = 4 x 150 + 2
    constexpr double kNoData = -9999.1;
    auto cell = [&](int c, int r) {  // row 0 north
        const bool data = c >= kWest && c < kCols - kEast && r >= kNorth;
        return data ? 100.0 + (c * 7 % 13) + 0.25 * (r % 40) : double(float(kNoData));
    };
    {
        setUpGdal();
        GDALDatasetH ds = GDALCreate(GDALGetDriverByName("GTiff"), path.c_str(), kCols, kRows, 1, GDT_Float32, nullptr);
        ASSERT_NE(ds, nullptr);
        double geo[6] = {kX0, kCell, 0, kY0, 0, -kCell};
        GDALSetGeoTransform(ds, geo);
        OGRSpatialReferenceH srs = OSRNewSpatialReference(nullptr);
        OSRImportFromEPSG(srs, 2193);
        GDALSetSpatialRef(ds, srs);
        OSRDestroySpatialReference(srs);
        GDALRasterBandH band = GDALGetRasterBand(ds, 1);
        GDALSetRasterNoDataValue(band, kNoData);
        std::vector<float> cells;
        for (int r = 0; r < kRows; ++r)
            for (int c = 0; c < kCols; ++c) cells.push_back(static_cast<float>(cell(c, r)));
        ASSERT_EQ(GDALRasterIO(band, GF_Write, 0, 0, kCols, kRows, cells.data(), kCols, kRows, GDT_Float32, 0, 0),
                  CE_None);
        int levels[] = {2, 4};
        ASSERT_EQ(GDALBuildOverviews(ds, "NEAREST", 2, levels, 0, nullptr, nullptr, nullptr), CE_None);
        GDALClose(ds);
    }
    NetBudget still;
    still.stillWidthPx = 275;  // 40 m a pixel: 4 cells
    Diagnostics diags;
    const auto chosen = rasterNet(rasterSpec(path, ""), {}, {}, diags, {}, still);
    ASSERT_TRUE(chosen) << (diags.all().empty() ? "" : formatDiagnostic(diags.all()[0]));
    ASSERT_EQ(chosen->dx, 4 * kCell);
    // Blocks from column 1 and row 1 (1102 = 4 x 275 + 2); the first and last blocks of columns
    // are nodata, the first block of rows half data.
    ASSERT_EQ(chosen->cols(), 273);
    ASSERT_EQ(chosen->rows(), kBlockRows);
    EXPECT_EQ(chosen->maskedCount(), 0u);
    EXPECT_NEAR(chosen->x0, kX0 + (5 + 2) * kCell, 1e-6);
    EXPECT_NEAR(chosen->y0, kY0 - (1 + 4 * (kBlockRows - 1) + 2) * kCell, 1e-6);
    for (int i = 0; i < chosen->rows(); ++i)  // net row i from the south: block row kBlockRows - 1 - i from the north
        for (int j = 0; j < chosen->cols(); ++j) {
            const int r0 = 1 + 4 * (kBlockRows - 1 - i), c0 = 5 + 4 * j;
            double sum = 0;
            int n = 0;
            for (int a = 0; a < 4; ++a)
                for (int b = 0; b < 4; ++b)
                    if (const double v = cell(c0 + b, r0 + a); v != double(float(kNoData))) sum += v, ++n;
            ASSERT_GT(n, 0);
            ASSERT_NEAR(chosen->grid.at(i, j).z, sum / n, 1e-9) << i << " " << j;
        }

    expectInitsNetIsTheChosen(path, "", {}, 4 * kCell, *chosen);
}

// At its own cells, a net over the data of a raster wider than the data scan
// lies on the cells' centres (the scan's box, a few cells wide of the data,
// moved out to them): the cells read, none warped.
TEST(Raster, AnOwnCellNetOverAWideRastersDataIsItsCells) {
    const fs::path path = freshDir("wide-own-cells") / "nztm.asc";
    constexpr int kCols = 1500, kRows = 12;
    auto cell = [&](int c, int r) { return c < 301 ? -9999.0 : 50.0 + c % 17 + r; };  // row 0 south
    {
        std::ofstream out(path);
        out << fmt::format("ncols {}\nnrows {}\nxllcenter {}\nyllcenter {}\ncellsize {}\nNODATA_value -9999\n", kCols,
                           kRows, kX0, kY0, kCell);
        for (int r = kRows - 1; r >= 0; --r)
            for (int c = 0; c < kCols; ++c) out << cell(c, r) << (c + 1 < kCols ? " " : "\n");
    }
    Diagnostics diags;
    const auto net = rasterNet(rasterSpec(path, "EPSG:2193"), {}, {}, diags);
    ASSERT_TRUE(net) << (diags.all().empty() ? "" : formatDiagnostic(diags.all()[0]));
    EXPECT_EQ(net->frame.kind, scene::FrameKind::Raster);
    EXPECT_TRUE(net->copiedCells) << net->raster;
    EXPECT_LE(net->maskedCount(), 3u * kRows);
    ASSERT_EQ(net->rows(), kRows);
    const double firstColumn = (net->x0 - kX0) / kCell;
    ASSERT_NEAR(firstColumn, std::round(firstColumn), 1e-9);
    for (int r = 0; r < kRows; ++r)
        for (int j = 0; j < net->cols(); ++j) {
            const double v = cell(static_cast<int>(std::round(firstColumn)) + j, r);
            if (v != -9999.0) {
                ASSERT_EQ(net->grid.at(r, j).z, v) << r << " " << j;
            }
        }
}

// The raster's CRS is the frame by default only when it is true to scale
// (Web Mercator here, at 47 N, is 32 % off: UTM then, and a warning when asked for) and in metres (degrees: UTM);
// asked for, a CRS in degrees is an error at the key, and so is the raster
// frame for scattered samples.
TEST(Raster, ItsOwnCrsOnlyWhenTrueToScaleAndInMetres) {
    const fs::path dir = freshDir("own-crs-not");
    const fs::path path = writePlane(dir, 20, 10);
    Diagnostics diags;
    const auto mercator = rasterNet(rasterSpec(path, "EPSG:3857"), {}, {}, diags);
    ASSERT_TRUE(mercator) << (diags.all().empty() ? "" : formatDiagnostic(diags.all()[0]));
    EXPECT_EQ(mercator->frame.kind, scene::FrameKind::Utm);
    Diagnostics askedDiags;
    const auto asked = rasterNet(rasterSpec(path, "EPSG:3857"), namedFrame(scene::FrameKind::Raster), {}, askedDiags);
    ASSERT_TRUE(asked);
    EXPECT_EQ(asked->frame.describe(), "WGS 84 / Pseudo-Mercator (the raster's own CRS)");
    ASSERT_GE(askedDiags.warningCount(), 1);  // these metres in Web Mercator lie at 47 N: cos 47 = 0.68
    EXPECT_EQ(formatDiagnostic(askedDiags.all()[0]),
              "scene.toml:2:8: warning: WGS 84 / Pseudo-Mercator is 31.7 % off true scale over the data: lengths, the "
              "scale bar and the slopes are off by as much; \"utm\" is true to scale");

    const fs::path degrees = dir / "degrees.asc";
    {
        std::ofstream out(degrees);
        out << "ncols 10\nnrows 10\nxllcenter 174.76\nyllcenter -36.88\ncellsize 0.0005\n";
        for (int r = 0; r < 10; ++r) out << "100 101 102 103 104 105 106 107 108 109\n";
    }
    Diagnostics geographic;
    const auto utm = rasterNet(rasterSpec(degrees, "EPSG:4326"), {}, {}, geographic);
    ASSERT_TRUE(utm) << (geographic.all().empty() ? "" : formatDiagnostic(geographic.all()[0]));
    EXPECT_EQ(utm->frame.describe(), "UTM zone 60S");
    Diagnostics refused;
    EXPECT_FALSE(rasterNet(rasterSpec(degrees, "EPSG:4326"), namedFrame(scene::FrameKind::Raster), {}, refused));
    ASSERT_EQ(refused.errorCount(), 1);
    EXPECT_EQ(formatDiagnostic(refused.all()[0]),
              "scene.toml:2:8: error: frame.kind = \"raster\" needs a raster in a projected CRS in metres, and WGS 84 "
              "is not one: use \"utm\" or \"local\"");

    Diagnostics scattered;
    EXPECT_FALSE(chooseFrame(namedFrame(scene::FrameKind::Raster), {{174.76, -36.88, 100, {}}}, scattered));
    ASSERT_EQ(scattered.errorCount(), 1);
    EXPECT_NE(formatDiagnostic(scattered.all()[0]).find("scattered points"), std::string::npos);
}

// Samples that are one per node of a regular lattice are found as such, in
// the CRS they are regular in; a missing, doubled or displaced sample, or an
// uneven spacing, makes them scattered samples again.
TEST(Lattice, FoundInItsCrsAndNotOtherwise) {
    // 30 x 20 nodes 10 m apart in NZTM, written as lon/lat to 8 decimals (as a CSV would).
    std::vector<GeoSample> samples;
    static const GeographicLib::TransverseMercator tm(6378137, 1 / 298.257222101, 0.9996);
    for (int r = 0; r < 20; ++r)
        for (int c = 0; c < 30; ++c) {
            double lat = 0, lon = 0;
            tm.Reverse(173, kX0 - 1600000 + 10.0 * c, kY0 - 10000000 + 10.0 * r, lat, lon);
            samples.push_back({std::round(lon * 1e8) / 1e8, std::round(lat * 1e8) / 1e8,
                               plane(kX0 + 10.0 * c, kY0 + 10.0 * r), {}});
        }
    std::swap(samples[3], samples[400]);  // order does not matter
    const auto lattice = findLattice(samples, "EPSG:2193");
    ASSERT_TRUE(lattice);
    EXPECT_EQ(lattice->cols, 30);
    EXPECT_EQ(lattice->rows, 20);
    EXPECT_NEAR(lattice->dx, 10, 1e-3);
    EXPECT_NEAR(lattice->dy, 10, 1e-3);
    EXPECT_NEAR(lattice->xWest, kX0, 1e-2);
    EXPECT_NEAR(lattice->yNorth, kY0 + 190, 1e-2);
    EXPECT_DOUBLE_EQ(lattice->z[0], plane(kX0, kY0 + 190));  // row 0 is north
    EXPECT_DOUBLE_EQ(lattice->z[20 * 30 - 1], plane(kX0 + 290, kY0));

    EXPECT_FALSE(findLattice(samples, "EPSG:4326"));  // not regular in degrees (2 km from NZTM's meridian)
    auto missing = samples;
    missing.pop_back();
    EXPECT_FALSE(findLattice(missing, "EPSG:2193"));
    auto displaced = samples;
    displaced[100].lonDeg += 2e-6;  // about 0.18 m: 1.8 % of the spacing
    EXPECT_FALSE(findLattice(displaced, "EPSG:2193"));
    auto doubled = samples;
    doubled[100] = doubled[101];
    EXPECT_FALSE(findLattice(doubled, "EPSG:2193"));
}

// A lattice goes the raster way: bilinear between its samples, exact at them.
TEST(Lattice, ResampledAsARaster) {
    std::vector<GeoSample> samples;
    for (int r = 0; r < 40; ++r)
        for (int c = 0; c < 50; ++c)
            samples.push_back({174.7 + 0.0001 * c, -36.9 + 0.0001 * r, 100 + 2.0 * c - 1.0 * r, {}});
    const auto lattice = findLattice(samples, "EPSG:4326");
    ASSERT_TRUE(lattice);
    scene::SamplesSpec spec;
    spec.pathAsWritten = "lattice.csv";
    scene::NetSpec net;
    net.spacingM = 5;
    Diagnostics diags;
    const auto result = latticeNet(*lattice, spec, {}, net, diags);
    ASSERT_TRUE(result) << (diags.all().empty() ? "" : formatDiagnostic(diags.all()[0]));
    EXPECT_EQ(diags.warningCount(), 0);  // the CSV's elevations are metres
    EXPECT_TRUE(result->masked.empty());
    EXPECT_NE(result->raster.find("lattice of 50 x 40 samples in EPSG:4326"), std::string::npos) << result->raster;
    // A plane in lon/lat is reproduced by bilinear resampling: each node's height is the plane at its
    // lon/lat, up to the warper's positional tolerance (0.001 cells; the plane rises 2 m per cell).
    for (const Vec3& p : result->grid.points) {
        const auto g = reverse(result->frame, {p.x, p.y, 0});
        ASSERT_TRUE(g);
        EXPECT_NEAR(p.z, 100 + 2.0 * (g->lonDeg - 174.7) / 0.0001 - 1.0 * (g->latDeg + 36.9) / 0.0001, 2.5e-3);
    }
}

// Crafted rasters: what GDAL returns that relief must not trust (sizes, geotransforms, cells).
TEST(Raster, CraftedRastersAreErrorsOrHandled) {
    const fs::path dir = freshDir("crafted");
    setUpGdal();
    scene::NetSpec net;
    net.spacingM = kCell;
    auto first = [&](const scene::SamplesSpec& spec, const scene::NetSpec& n) {
        Diagnostics diags;
        const bool ok = rasterNet(spec, {}, n, diags).has_value();
        return std::make_pair(ok, diags.all().empty() ? std::string() : formatDiagnostic(diags.all()[0]));
    };
    auto tiff = [&](const std::string& name, double pixelX, double pixelY, std::vector<float> cells) {
        const fs::path path = dir / name;
        GDALDatasetH ds = GDALCreate(GDALGetDriverByName("GTiff"), path.c_str(), 4, 4, 1, GDT_Float32, nullptr);
        double geo[6] = {kX0, pixelX, 0, kY0, 0, pixelY};
        GDALSetGeoTransform(ds, geo);
        GDALSetProjection(ds, "EPSG:2193");
        EXPECT_EQ(GDALRasterIO(GDALGetRasterBand(ds, 1), GF_Write, 0, 0, 4, 4, cells.data(), 4, 4, GDT_Float32, 0, 0),
                  CE_None);
        GDALClose(ds);
        return rasterSpec(path, "", "m");
    };
    const std::vector<float> plain(16, 100.0f);
    // A cell of size 0 (a VRT keeps the geotransform as written): it cannot be inverted.
    std::ofstream(dir / "zero.vrt") << "<VRTDataset rasterXSize=\"4\" rasterYSize=\"4\"><SRS>EPSG:2193</SRS>"
                                       "<GeoTransform>1757000, 0, 0, 5917000, 0, -10</GeoTransform>"
                                       "<VRTRasterBand dataType=\"Float32\" band=\"1\"/></VRTDataset>";
    EXPECT_EQ(first(rasterSpec(dir / "zero.vrt", ""), net).second,
              "zero.vrt: error: the raster's geotransform cannot be inverted (a cell of size 0?)");
    // 4 x 4 cells, their centres 30 m apart, turned by the grid convergence in UTM: a net at half
    // their spacing (at their own, 3 x 3 nodes fit, fewer than a net needs).
    scene::NetSpec half;
    half.spacingM = kCell / 2;
    const auto southUp = first(tiff("south-up.tif", kCell, kCell, plain), half);
    EXPECT_TRUE(southUp.first) << southUp.second;
    // An infinite cell is beyond the Earth's elevations, named by its cell; NaN is no data (masked).
    std::vector<float> odd = plain;
    odd[5] = std::numeric_limits<float>::infinity();
    const auto inf = first(tiff("inf.tif", kCell, -kCell, odd), half);
    EXPECT_EQ(inf.second.rfind("inf.tif: error: the cell at column 1, row 1", 0), 0u) << inf.second;
    odd[5] = std::numeric_limits<float>::quiet_NaN();
    EXPECT_TRUE(first(tiff("nan.tif", kCell, -kCell, odd), half).first);
    // A declared size of 2^32 cells (a VRT with no source: GDAL reads it as zeros) is refused
    // from its header before anything is read or allocated for it.
    std::ofstream(dir / "huge.vrt") << "<VRTDataset rasterXSize=\"65536\" rasterYSize=\"65536\">"
                                       "<SRS>EPSG:2193</SRS><GeoTransform>1757000, 0.01, 0, 5917000, 0, -0.01"
                                       "</GeoTransform><VRTRasterBand dataType=\"Float32\" band=\"1\"/></VRTDataset>";
    const auto huge = first(rasterSpec(dir / "huge.vrt", ""), {});
    EXPECT_FALSE(huge.first);
    EXPECT_EQ(huge.second, "huge.vrt: error: the raster is 65536 x 65536 cells (4.29e+09), more than the 2e+09 "
                           "relief reads from a raster without overviews: add overviews (gdaladdo) or cut a window "
                           "(gdal_translate -projwin)");
}

// Each way a raster can be unusable is an error naming the file or key and the fix.
TEST(Raster, UnusableRastersAreErrors) {
    const fs::path dir = freshDir("bad");
    const fs::path path = writePlane(dir, 20, 20);
    scene::NetSpec net;
    auto message = [&](const scene::SamplesSpec& spec) {
        Diagnostics diags;
        EXPECT_FALSE(rasterNet(spec, {}, net, diags));
        return diags.all().empty() ? std::string() : formatDiagnostic(diags.all()[0]);
    };
    EXPECT_EQ(message(rasterSpec(path, "")),
              "plane.asc: error: the raster has no coordinate reference system: give it in the scene, e.g. "
              "crs = \"EPSG:2193\" in [samples]");
    auto band = rasterSpec(path, "EPSG:2193");
    band.band = 2;
    band.locs.keys["samples.band"] = {"s.toml", 3, 8};
    EXPECT_EQ(message(band), "s.toml:3:8: error: samples.band = 2, but plane.asc has 1 band: give a band from 1 to 1");
    EXPECT_EQ(message(rasterSpec(path, "EPSG:999999")).rfind("error: samples.crs = \"EPSG:999999\" is not a CRS", 0), 0u);
    std::ofstream(dir / "one.asc") << "ncols 1\nnrows 1\nxllcenter 0\nyllcenter 0\ncellsize 1\n5\n";
    EXPECT_EQ(message(rasterSpec(dir / "one.asc", "EPSG:2193")),
              "one.asc: error: the raster is 1 x 1 cells; a surface needs at least 2 x 2");
    // A rotated geotransform.
    setUpGdal();
    {
        const fs::path rotated = dir / "rotated.tif";
        GDALDatasetH ds = GDALCreate(GDALGetDriverByName("GTiff"), rotated.c_str(), 4, 4, 1, GDT_Float32, nullptr);
        double geo[6] = {kX0, kCell, 2, kY0, 2, -kCell};
        GDALSetGeoTransform(ds, geo);
        GDALSetProjection(ds, "EPSG:2193");
        GDALClose(ds);
        EXPECT_EQ(message(rasterSpec(rotated, "")),
                  "rotated.tif: error: the raster's geotransform is rotated; relief reads north-up rasters: "
                  "warp it first (gdalwarp)");
    }
    // A CSV of samples is not a raster, even one GDAL could read as a table.
    std::ofstream(dir / "s.csv") << "lon,lat,elev\n174.76,-36.87,100\n174.77,-36.87,101\n";
    EXPECT_FALSE(isRasterDem(dir / "s.csv"));
    // A truncated GeoTIFF is a raster GDAL cannot read, not a CSV.
    std::ofstream(dir / "cut.tif", std::ios::binary) << std::string("II*\0\x08\0\0\0", 8);
    EXPECT_TRUE(isRasterDem(dir / "cut.tif"));
    EXPECT_EQ(message(rasterSpec(dir / "cut.tif", "")),
              "cut.tif: error: GDAL cannot read this raster (a truncated or damaged file?)");
}

}  // namespace
}  // namespace relief::geo

namespace relief::geo {
namespace {

// An image in Web Mercator whose red and green grow by 8 a column and a row
// (bilinear resampling keeps them exact), draped on a UTM grid: each node's
// colour says which pixel it landed on, computed here with the spherical
// Mercator's own formulas; nodes off the image are not covered.
TEST(DrapeImage, AWebMercatorImageLandsOnTheUtmNodes) {
    using namespace relief;
    const fs::path dir = freshDir("drape-image");
    const fs::path path = dir / "gradient.tif";
    constexpr int kCols = 30, kRows = 25;
    constexpr double kR = 6378137, kPi = 3.14159265358979323846;
    const double x0 = kR * (-3.8 * kPi / 180), y0 = kR * std::log(std::tan(kPi / 4 + 40.5 * kPi / 360));
    constexpr double kCell = 2000;  // metres of the projection
    {
        geo::setUpGdal();
        GDALDatasetH ds = GDALCreate(GDALGetDriverByName("GTiff"), path.c_str(), kCols, kRows, 3, GDT_Byte, nullptr);
        double gt[6] = {x0, kCell, 0, y0, 0, -kCell};
        GDALSetGeoTransform(ds, gt);
        OGRSpatialReferenceH srs = OSRNewSpatialReference(nullptr);
        OSRImportFromEPSG(srs, 3857);
        char* wkt = nullptr;
        OSRExportToWkt(srs, &wkt);
        GDALSetProjection(ds, wkt);
        CPLFree(wkt);
        OSRDestroySpatialReference(srs);
        std::vector<std::uint8_t> band(kCols * kRows);
        for (int b = 0; b < 3; ++b) {
            for (int r = 0; r < kRows; ++r)
                for (int c = 0; c < kCols; ++c) band[r * kCols + c] = b == 0 ? 8 * c : b == 1 ? 8 * r : 77;
            ASSERT_EQ(GDALRasterIO(GDALGetRasterBand(ds, b + 1), GF_Write, 0, 0, kCols, kRows, band.data(), kCols,
                                   kRows, GDT_Byte, 0, 0),
                      CE_None);
        }
        GDALClose(ds);
    }
    // A UTM 30N grid around (-3.6, 40.2), partly off the image south edge (40.16).
    geo::GeoGrid grid;
    grid.frame.kind = scene::FrameKind::Utm;
    grid.frame.utmZone = 30;
    grid.frame.northp = true;
    const Vec3 centre = geo::forward(grid.frame, {-3.6, 40.2, 0}).value();
    grid.grid.rows = 12;
    grid.grid.cols = 15;
    grid.dx = grid.dy = 1500;
    grid.x0 = centre.x - 7 * 1500;
    grid.y0 = centre.y - 8 * 1500;
    for (int r = 0; r < grid.grid.rows; ++r)
        for (int c = 0; c < grid.grid.cols; ++c) grid.grid.points.push_back({grid.x0 + c * 1500.0, grid.y0 + r * 1500.0, 0});
    Diagnostics diags;
    const auto image = geo::imageOnGrid(path, "gradient.tif", grid, diags);
    ASSERT_TRUE(image) << (diags.all().empty() ? "" : formatDiagnostic(diags.all()[0]));
    int inside = 0, outside = 0;
    for (int r = 0; r < grid.grid.rows; ++r)
        for (int c = 0; c < grid.grid.cols; ++c) {
            const size_t node = size_t(r) * grid.grid.cols + c;
            const auto g = geo::reverse(grid.frame, grid.grid.points[node]);
            ASSERT_TRUE(g);
            const double lat = g->latDeg, lon = g->lonDeg;
            const double px = (kR * lon * kPi / 180 - x0) / kCell;
            const double py = (y0 - kR * std::log(std::tan(kPi / 4 + lat * kPi / 360))) / kCell;
            // Bilinear between pixel centres: value 8 * (p - 0.5), within the image's centres.
            if (px > 0.5 && px < kCols - 0.5 && py > 0.5 && py < kRows - 0.5) {
                ++inside;
                ASSERT_TRUE(image->covered[node]) << r << "," << c;
                EXPECT_NEAR(image->rgb[3 * node], 8 * (px - 0.5), 1.0) << r << "," << c;
                EXPECT_NEAR(image->rgb[3 * node + 1], 8 * (py - 0.5), 1.0) << r << "," << c;
                EXPECT_EQ(image->rgb[3 * node + 2], 77);
            } else if (py > kRows + 1) {
                ++outside;
                EXPECT_FALSE(image->covered[node]) << r << "," << c;
            }
        }
    EXPECT_GT(inside, 60);
    EXPECT_GT(outside, 10);
}

}  // namespace
}  // namespace relief::geo
