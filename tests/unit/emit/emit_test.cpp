#include <gtest/gtest.h>

#include <cstdio>
#include <string>

#include "emit/mesh.h"
#include "geo/normalize.h"
#include "emit/template.h"
#include "core/text_escape.h"
#include "emit/write_scene.h"

namespace relief::emit {
namespace {

std::string render(const Template& t, const Bindings& b) {
    char* data = nullptr;
    size_t size = 0;
    std::FILE* f = open_memstream(&data, &size);
    renderTemplate(t, b, f);
    std::fclose(f);
    std::string out(data, size);
    std::free(data);
    return out;
}

TEST(Template, SubstitutesAndStreams) {
    Template t{"t.in", "a {{x}} b\n{{big}}!"};
    Bindings b;
    b["x"].text = std::string("1");
    b["big"].writer = [](std::FILE* f) { std::fputs("streamed", f); };
    Diagnostics d;
    EXPECT_TRUE(checkTemplate(t, b, d));
    EXPECT_EQ(render(t, b), "a 1 b\nstreamed!");
}

// One pass: a value holding a placeholder (an attribution "{{big}}", from a
// scene file) is written as it is, never expanded.
TEST(Template, ValuesAreNotExpandedAgain) {
    Template t{"t.in", "// {{x}}\n{{big}}"};
    Bindings b;
    b["x"].text = std::string("{{big}} {{x}} #declare X = 1;");
    b["big"].text = std::string("mesh");
    Diagnostics d;
    EXPECT_TRUE(checkTemplate(t, b, d));
    EXPECT_EQ(render(t, b), "// {{big}} {{x}} #declare X = 1;\nmesh");
}

TEST(Template, UnboundAndUnusedAreErrorsWithLocation) {
    Template t{"scene.pov.in", "line one\n  camera {{camera_locaton}}\n"};
    Bindings b;
    b["camera_location"].text = "<0,0,0>";
    Diagnostics d;
    EXPECT_FALSE(checkTemplate(t, b, d));
    ASSERT_EQ(d.errorCount(), 2);
    EXPECT_EQ(formatDiagnostic(d.all()[0]),
              "scene.pov.in:2:10: error: template placeholder {{camera_locaton}} has no value");
    EXPECT_EQ(formatDiagnostic(d.all()[1]),
              "scene.pov.in: error: template does not use {{camera_location}}; add it to the "
              "template");
}

Grid tiltedPlane() {
    Grid g;
    g.rows = 3;
    g.cols = 4;
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 4; ++c)
            g.points.push_back({300000.0 + 100 * c, 5900000.0 + 100 * r, 50.0 + 10.0 * c});
    return g;
}

TEST(Mesh, NormalsOfATiltedPlaneAndSceneUnits) {
    scene::LookSpec look;
    look.vertical.exaggeration = 2;
    const geo::GeoGrid grid{{}, tiltedPlane(), 300000, 5900000, 100, 100, {}};
    const Mesh m = buildMesh(grid, look);
    EXPECT_EQ(m.metresPerUnit, 10.0);  // 300 m extent -> 10 m per unit
    // Height rises 20 (exaggerated) per 100 m east: normal ~ (-0.2, 1, 0) normalised.
    const double n = std::sqrt(1 + 0.04);
    for (size_t i = 0; i < m.vertices; ++i) {
        const SceneVec3 v = m.normal(i);
        EXPECT_NEAR(v.x, -0.2 / n, 1e-12);
        EXPECT_NEAR(v.y, 1.0 / n, 1e-12);
        EXPECT_NEAR(v.z, 0.0, 1e-12);
    }
    EXPECT_NEAR(m.position(0).x, -15.0, 1e-9);  // centred: x from -150 m to +150 m
    EXPECT_NEAR(m.position(0).y, 10.0, 1e-9);   // 50 m * 2 / 10 m per unit
    EXPECT_EQ(m.palette(0), 0);
    EXPECT_EQ(m.palette(m.vertices - 1), 255);
}

// A string from a scene or a data file cannot leave the header's comments:
// a line break would let POV-Ray run what follows (#fopen, #write, ...).
TEST(SceneHeader, UntrustedTextStaysInItsComment) {
    EXPECT_EQ(oneLineText("data/dem.tif"), "data/dem.tif");
    EXPECT_EQ(oneLineText("a\n#fopen F \"/tmp/x\" write\r\x7f"), "a\\x0a#fopen F \"/tmp/x\" write\\x0d\\x7f");
    const geo::GeoGrid grid{{}, tiltedPlane(), 300000, 5900000, 100, 100, {}};
    const Mesh m = buildMesh(grid, scene::LookSpec{});
    const Bindings b = sceneBindings(m, placeCamera(m, scene::LookSpec{}, scene::RenderSpec{}), {}, {}, {}, {},
                                     {{"samples.path", "x.csv\n#declare Evil = 1;"}});
    const std::string head = b.at("header").text;
    EXPECT_EQ(head, "// samples.path: x.csv\\x0a#declare Evil = 1;\n");
}

TEST(Mesh2, WriterOutputShape) {
    const geo::GeoGrid grid{{}, tiltedPlane(), 300000, 5900000, 100, 100, {}};
    const Mesh m = buildMesh(grid, scene::LookSpec{});
    char* data = nullptr;
    size_t size = 0;
    std::FILE* f = open_memstream(&data, &size);
    const size_t written = writeMesh2(m, f);
    std::fclose(f);
    const std::string out(data, size);
    std::free(data);
    EXPECT_EQ(written, out.size());
    EXPECT_EQ(out.rfind("mesh2 {\n  vertex_vectors {\n    12,\n<-15.00000,5.00000,-10.00000>", 0), 0u);
    // Each quad cut from south-east to north-west, as POV-Ray cuts a height_field's cells.
    EXPECT_NE(out.find("face_indices {\n    12,\n<0,1,4>,0,85,0,\n<1,5,4>,85,85,0"), std::string::npos);
    EXPECT_NE(out.find("texture_list {\n    256,\n    texture { pigment { rgb <"), std::string::npos);
}

// Masked nodes (no data) are left out with every triangle that touches one;
// the rest are renumbered, and bounds and palette come from the nodes with data.
TEST(Mesh2, MaskedNodesLeaveAHole) {
    geo::GeoGrid grid{{}, tiltedPlane(), 300000, 5900000, 100, 100, {}};
    grid.masked.assign(12, 0);
    grid.masked[0] = 1;                  // the south-west corner
    grid.grid.points[0].z = -1000;       // a filled height that nothing may show
    const Mesh m = buildMesh(grid, scene::LookSpec{});
    EXPECT_EQ(m.vertices, 11u);
    EXPECT_EQ(m.triangles, 12 - 1);      // the corner cell's south-west triangle
    EXPECT_EQ(m.zMinM, 50.0);
    ASSERT_EQ(m.vertexOfNode.size(), 12u);
    EXPECT_EQ(m.vertexOfNode[0], Mesh::kNoVertex);
    EXPECT_EQ(m.vertexOfNode[1], 0u);
    char* data = nullptr;
    size_t size = 0;
    std::FILE* f = open_memstream(&data, &size);
    writeMesh2(m, f);
    std::fclose(f);
    const std::string out(data, size);
    std::free(data);
    EXPECT_EQ(out.rfind("mesh2 {\n  vertex_vectors {\n    11,\n<-5.00000,6.00000,-10.00000>", 0), 0u);
    // The first cell keeps its north-east triangle: nodes 1, 5, 4 -> vertices 0, 4, 3; then the
    // second cell: nodes 1, 2, 5 and 2, 6, 5 -> vertices 0, 1, 4 and 1, 5, 4.
    EXPECT_NE(out.find("face_indices {\n    11,\n<0,4,3>,85,85,0,\n<0,1,4>,85,170,85,\n<1,5,4>,170,170,85"),
              std::string::npos);
}

// In a local frame a grid's heights include the Earth's fall below the tangent plane (20 km at
// 500 km). Drawn, the elevation is exaggerated and the fall is not, and colours follow elevation:
// a region 400 km across whose elevation rises eastward only (100 m to 500 m) has one colour
// down each column, and is not domed by the exaggeration.
TEST(Mesh, LocalFrameExaggeratesElevationNotCurvature) {
    geo::GeoGrid grid;
    grid.frame.kind = scene::FrameKind::Local;
    grid.frame.originLatDeg = 1.5;
    grid.frame.originLonDeg = 114;
    grid.grid.rows = grid.grid.cols = 41;
    grid.x0 = grid.y0 = -200000;
    grid.dx = grid.dy = 10000;
    for (int r = 0; r < 41; ++r)
        for (int c = 0; c < 41; ++c) {
            const double x = -200000 + 10000.0 * c, y = -200000 + 10000.0 * r;
            const auto g = geo::reverse(grid.frame, {x, y, 0});
            ASSERT_TRUE(g);
            const auto above = geo::forward(grid.frame, {g->lonDeg, g->latDeg, 300 + x / 1000});  // above the ellipsoid
            ASSERT_TRUE(above);
            grid.grid.points.push_back({x, y, above->z});
        }
    EXPECT_LT(grid.grid.at(0, 0).z, -6000);  // the fall at the corner, 283 km out: about 6.3 km
    scene::LookSpec look;
    look.vertical.exaggeration = 10;
    const Mesh m = buildMesh(grid, look);
    EXPECT_NEAR(m.zMinM, 100, 0.5);
    EXPECT_NEAR(m.zMaxM, 500, 0.5);
    for (int c = 0; c < 41; ++c)
        for (int r = 0; r < 41; ++r) EXPECT_NEAR(m.palette(r * 41 + c), m.palette(20 * 41 + c), 1) << r << " " << c;
    // Drawn: 10 x 100 m above the fall, not 10 x (100 m + the fall).
    const Vec3& corner = grid.grid.at(0, 0);
    const double fall = m.fallAt(corner);
    EXPECT_NEAR(fall, corner.z - 100, 0.5);
    EXPECT_NEAR(m.position(0).y * m.metresPerUnit, 10 * 100 + fall, 5);
    EXPECT_NEAR(m.position(20 * 41 + 20).y * m.metresPerUnit, 10 * 300, 1);  // the tangent point: no fall
}

}  // namespace
}  // namespace relief::emit
