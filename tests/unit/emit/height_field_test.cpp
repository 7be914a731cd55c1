#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include <OpenImageIO/imageio.h>

#include "core/atomic_file.h"
#include "emit/geometry_kind.h"
#include "emit/height_field.h"
#include "emit/mesh.h"
#include "unit/test_dirs.h"

namespace relief::emit {
namespace {

namespace fs = std::filesystem;

// 4 x 3 nodes 100 m apart rising 10 m per column to the east, and 1 m per row to the north.
geo::GeoGrid risingPlaneNet() {
    geo::GeoGrid g;
    g.grid.rows = 3;
    g.grid.cols = 4;
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 4; ++c) g.grid.points.push_back({300000.0 + 100 * c, 5900000.0 + 100 * r, 50.0 + 10 * c + r});
    g.x0 = 300000, g.y0 = 5900000, g.dx = g.dy = 100;
    return g;
}

std::string sdlOf(const HeightField& field, const geo::GeoGrid& grid, const ScenePlacement& where) {
    char* data = nullptr;
    size_t size = 0;
    std::FILE* f = open_memstream(&data, &size);
    writeHeightFieldSdl(f, field, grid, where, "t.height.png", "t.drape.png");
    std::fclose(f);
    std::string out(data, size);
    std::free(data);
    return out;
}

// Levels: 0 at the lowest node, 65535 at the highest, row 0 of the image north.
TEST(HeightField, QuantizesNorthFirst) {
    const auto grid = risingPlaneNet();
    const HeightField field = quantizeHeights(grid, placeTerrain(grid, {}));
    ASSERT_EQ(field.levels.size(), 12u);
    EXPECT_EQ(field.zMinM, 50);
    EXPECT_EQ(field.zMaxM, 82);
    EXPECT_DOUBLE_EQ(field.stepM(), 32.0 / 65535);
    EXPECT_EQ(field.levels[8], 0);        // south-west: image row 2, column 0
    EXPECT_EQ(field.levels[3], 65535);    // north-east: image row 0, column 3
    EXPECT_EQ(field.levels[0], std::lround(2.0 / 32 * 65535));  // north-west: 52 m
}

// The PNG holds the levels exactly, 16-bit, and the same levels give the same bytes.
TEST(HeightField, PngRoundTripAndDeterminism) {
    const fs::path dir = relief::testing::freshTestDir("relief-height-field");
    const auto plane = risingPlaneNet();
    const HeightField field = quantizeHeights(plane, placeTerrain(plane, {}));
    ASSERT_NO_THROW(writeHeightFieldPng(field, dir / "a.png"));
    ASSERT_NO_THROW(writeHeightFieldPng(field, dir / "b.png"));
    EXPECT_EQ(readFile(dir / "a.png"), readFile(dir / "b.png"));
    auto in = OIIO::ImageInput::open((dir / "a.png").string());
    ASSERT_TRUE(in);
    EXPECT_EQ(in->spec().format, OIIO::TypeDesc::UINT16);
    EXPECT_EQ(in->spec().nchannels, 1);
    std::vector<std::uint16_t> back(12);
    ASSERT_TRUE(in->read_image(0, 0, 0, 1, OIIO::TypeDesc::UINT16, back.data()));
    EXPECT_EQ(back, field.levels);
}

// The drape gives each node the colour the mesh2 gives its vertex.
TEST(HeightField, DrapeColoursAreTheMeshPalette) {
    const auto grid = risingPlaneNet();
    const Mesh mesh = buildMesh(grid, scene::LookSpec{});
    const Drape drape = elevationDrape(grid, mesh);
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 4; ++c) {
            const auto& colour = mesh.paletteColors[mesh.palette(static_cast<size_t>(r) * 4 + c)];
            const std::uint16_t* px = &drape.pixels[(static_cast<size_t>(2 - r) * 4 + c) * 3];
            EXPECT_EQ(px[0], std::lround(colour.r * 65535)) << r << " " << c;
            EXPECT_EQ(px[1], std::lround(colour.g * 65535));
            EXPECT_EQ(px[2], std::lround(colour.b * 65535));
        }
}

// A height_field has no holes: masked nodes are transparent in the drape (alpha 0), and their
// filled heights do not stretch the levels' range.
TEST(HeightField, MaskedNodesAreTransparent) {
    auto grid = risingPlaneNet();
    grid.masked.assign(12, 0);
    grid.masked[2 * 4 + 3] = 1;                  // the north-east node...
    grid.grid.at(2, 3).z = 5000;                 // ...with a wild filled height
    const ScenePlacement where = placeTerrain(grid, {});
    const HeightField field = quantizeHeights(grid, where);
    EXPECT_EQ(field.zMaxM, 81);                  // the highest node with data (2, 2)
    EXPECT_EQ(field.levels[3], 65535);           // the masked node, clamped
    const Drape drape = elevationDrape(grid, where);
    ASSERT_EQ(drape.channels, 4);
    ASSERT_EQ(drape.pixels.size(), 48u);
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 4; ++c)
            EXPECT_EQ(drape.pixels[(static_cast<size_t>(2 - r) * 4 + c) * 4 + 3], r == 2 && c == 3 ? 0 : 65535)
                << r << " " << c;
    const fs::path png = relief::testing::freshTestDir("relief-hf-masked") / "d.png";
    fs::create_directories(png.parent_path());
    ASSERT_NO_THROW(writeDrapePng(drape, png));
    OIIO::ImageSpec asStored;  // not premultiplied: the colours under alpha 0 as written
    asStored.attribute("oiio:UnassociatedAlpha", 1);
    auto in = OIIO::ImageInput::open(png.string(), &asStored);
    ASSERT_TRUE(in);
    EXPECT_EQ(in->spec().nchannels, 4);
    EXPECT_EQ(in->spec().alpha_channel, 3);
    std::vector<std::uint16_t> back(48);
    ASSERT_TRUE(in->read_image(0, 0, 0, 4, OIIO::TypeDesc::UINT16, back.data()));
    EXPECT_EQ(back, drape.pixels);
}

// The height field lands where the mesh2 puts the nodes: 10 m per unit, centred; its image map's
// pixel centres on the nodes.
TEST(HeightField, SdlPlacesItWhereTheMeshIs) {
    const auto grid = risingPlaneNet();
    const ScenePlacement where = placeTerrain(grid, {});
    const std::string sdl = sdlOf(quantizeHeights(grid, where), grid, where);
    EXPECT_NE(sdl.find("png \"t.height.png\"\n  smooth"), std::string::npos) << sdl;
    EXPECT_NE(sdl.find("image_map { png \"t.drape.png\" gamma 1.0 map_type 0 interpolate 2 }"), std::string::npos);
    EXPECT_NE(sdl.find("scale <1.333333, 1, 1.500000>\n      translate <-0.166667, 0, -0.250000>"), std::string::npos)
        << sdl;
    EXPECT_NE(sdl.find("  scale <30.000000, 3.200000, 20.000000>\n  translate <-15.000000, 5.000000, -10.000000>"),
              std::string::npos)
        << sdl;
}

// Names that stand in SDL strings as they are.
TEST(HeightField, SiblingNamesAreSafe) {
    EXPECT_EQ(siblingPngName("out/default.pov", "height"), "default.height.png");
    EXPECT_EQ(siblingPngName("out/a b\"c\\d\n.pov", "drape"), "a_b_c_d_.drape.png");
}

TEST(GeometryKind, AutoAndExplicitChoices) {
    GeometryFacts big;
    big.triangles = 6e6;
    big.zRangeM = 840;
    big.extentM = 36000;
    big.widthPx = 1280;
    Diagnostics diags;
    EXPECT_EQ(chooseGeometry({}, big, diags)->kind, scene::GeometryKind::HeightField);
    GeometryFacts small = big;
    small.triangles = 2e5;  // 0.8 s of parsing
    EXPECT_EQ(chooseGeometry({}, small, diags)->kind, scene::GeometryKind::Mesh2);
    GeometryFacts holes = big;  // holes in the drape: still a height field
    holes.masked = true;
    EXPECT_EQ(chooseGeometry({}, holes, diags)->kind, scene::GeometryKind::HeightField);
    GeometryFacts roughHoles = holes;  // no height field: the mesh with holes and fewer triangles
    roughHoles.rough = true;
    EXPECT_EQ(chooseGeometry({}, roughHoles, diags)->kind, scene::GeometryKind::Adaptive);
    GeometryFacts smallHoles = small;
    smallHoles.masked = true;
    EXPECT_EQ(chooseGeometry({}, smallHoles, diags)->kind, scene::GeometryKind::Mesh2);
    GeometryFacts rough = big;
    rough.rough = true;
    EXPECT_EQ(chooseGeometry({}, rough, diags)->kind, scene::GeometryKind::Mesh2);
    GeometryFacts coarse = big;  // 100 km of relief on a 1 km square: 1.5 m levels, 0.4 m half pixels
    coarse.zRangeM = 1e5;
    coarse.extentM = 1000;
    EXPECT_EQ(chooseGeometry({}, coarse, diags)->kind, scene::GeometryKind::Mesh2);
    EXPECT_EQ(diags.errorCount(), 0);

    scene::GeometrySpec asked;
    asked.kind = scene::GeometryKind::HeightField;
    asked.locs.keys["geometry.kind"] = {"s.toml", 2, 8};
    EXPECT_EQ(chooseGeometry(asked, small, diags)->kind, scene::GeometryKind::HeightField);
    // Holes are transparent pixels of the drape (HeightField.MaskedNodesAreTransparent).
    EXPECT_EQ(chooseGeometry(asked, holes, diags)->kind, scene::GeometryKind::HeightField);
    EXPECT_EQ(diags.errorCount(), 0);
    EXPECT_FALSE(chooseGeometry(asked, coarse, diags));
    EXPECT_EQ(diags.errorCount(), 1);
    asked.kind = scene::GeometryKind::Adaptive;
    EXPECT_EQ(chooseGeometry(asked, holes, diags)->kind, scene::GeometryKind::Adaptive);
}

}  // namespace
}  // namespace relief::emit
