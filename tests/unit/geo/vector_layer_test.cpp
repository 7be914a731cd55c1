// A [[layer]]'s file read by GDAL/OGR: a layer in NZTM (EPSG:2193) lands
// where GDAL's own transformation puts it, a file in EPSG:4326 is read lon,
// lat whatever the authority's axis order; a polygon keeps its hole; a CSV's
// points come from its lon and lat columns with their labels as written
// (markup, SDL, bad UTF-8 and all); a label attribute the layer does not have,
// a layer the file does not have and a file GDAL cannot read are errors that
// list what there is; an empty layer is a warning.
#include <gtest/gtest.h>

#include <fstream>

#include <fmt/format.h>
#include <gdal.h>
#include <ogr_api.h>
#include <ogr_srs_api.h>

#include "geo/gdal_setup.h"
#include "geo/vector_layer.h"
#include "unit/test_dirs.h"

namespace relief::geo {
namespace {

namespace fs = std::filesystem;

scene::LayerSpec specOf(const fs::path& path, const std::string& label = "") {
    scene::LayerSpec s;
    s.number = 1;
    s.path = path;
    s.pathAsWritten = path.filename().string();
    s.labelField = label;
    return s;
}

// A GeoPackage in EPSG:`epsg` holding one point at (x, y) named "summit" and
// a square polygon around it with a square hole.
void writeGeoPackage(const fs::path& path, int epsg, double x, double y, double half) {
    setUpGdal();
    GDALDriverH driver = GDALGetDriverByName("GPKG");
    GDALDatasetH ds = GDALCreate(driver, path.c_str(), 0, 0, 0, GDT_Unknown, nullptr);
    ASSERT_NE(ds, nullptr);
    OGRSpatialReferenceH srs = OSRNewSpatialReference(nullptr);
    OSRImportFromEPSG(srs, epsg);
    OGRLayerH layer = GDALDatasetCreateLayer(ds, "features", srs, wkbUnknown, nullptr);
    OGRFieldDefnH field = OGR_Fld_Create("name", OFTString);
    OGR_L_CreateField(layer, field, TRUE);
    OGR_Fld_Destroy(field);
    const auto add = [&](const char* wkt, const char* name) {
        OGRGeometryH g = nullptr;
        char* text = const_cast<char*>(wkt);
        OGR_G_CreateFromWkt(&text, nullptr, &g);
        OGRFeatureH f = OGR_F_Create(OGR_L_GetLayerDefn(layer));
        OGR_F_SetFieldString(f, 0, name);
        OGR_F_SetGeometryDirectly(f, g);
        EXPECT_EQ(OGR_L_CreateFeature(layer, f), OGRERR_NONE);
        OGR_F_Destroy(f);
    };
    // x east, y north, as a GeoPackage stores them whatever the CRS's authority says of its axes.
    const auto xy = [&](double a, double b) { return fmt::format("{:.10f} {:.10f}", a, b); };
    add(("POINT (" + xy(x, y) + ")").c_str(), "summit");
    const std::string outer = xy(x - half, y - half) + "," + xy(x + half, y - half) + "," + xy(x + half, y + half) +
                              "," + xy(x - half, y + half) + "," + xy(x - half, y - half);
    const double h = half / 4;
    const std::string inner = xy(x - h, y - h) + "," + xy(x + h, y - h) + "," + xy(x + h, y + h) + "," +
                              xy(x - h, y + h) + "," + xy(x - h, y - h);
    add(("POLYGON ((" + outer + "),(" + inner + "))").c_str(), "cone");
    OSRDestroySpatialReference(srs);
    GDALClose(ds);
}

TEST(VectorLayer, ALayerInNztmLandsWhereGdalPutsIt) {
    const auto dir = testing::freshTestDir("vector-layer-nztm");
    const double e = 1757475, n = 5917625;  // Maungawhau's summit in NZTM2000, about
    writeGeoPackage(dir / "f.gpkg", 2193, e, n, 200);
    Diagnostics diags;
    const auto layer = readVectorLayer(specOf(dir / "f.gpkg", "name"), 1000, diags);
    ASSERT_TRUE(layer) << (diags.all().empty() ? "" : diags.all().front().message);
    ASSERT_EQ(layer->features.size(), 2u);
    // GDAL's own transformation of the same coordinates, in lon, lat order.
    OGRSpatialReferenceH from = OSRNewSpatialReference(nullptr), to = OSRNewSpatialReference(nullptr);
    OSRImportFromEPSG(from, 2193);
    OSRImportFromEPSG(to, 4326);
    OSRSetAxisMappingStrategy(from, OAMS_TRADITIONAL_GIS_ORDER);
    OSRSetAxisMappingStrategy(to, OAMS_TRADITIONAL_GIS_ORDER);
    OGRCoordinateTransformationH t = OCTNewCoordinateTransformation(from, to);
    double x = e, y = n;
    ASSERT_TRUE(OCTTransform(t, 1, &x, &y, nullptr));
    const VectorFeature& summit = layer->features[0];
    EXPECT_EQ(summit.kind, FeatureKind::Point);
    EXPECT_EQ(summit.label, "summit");
    EXPECT_NEAR(summit.parts[0][0].lonDeg, x, 1e-9);
    EXPECT_NEAR(summit.parts[0][0].latDeg, y, 1e-9);
    EXPECT_NEAR(x, 174.7644, 0.01);  // and that is Auckland
    EXPECT_NEAR(y, -36.8767, 0.01);
    const VectorFeature& cone = layer->features[1];
    EXPECT_EQ(cone.kind, FeatureKind::Polygon);
    ASSERT_EQ(cone.parts.size(), 2u);  // the outer ring and its hole
    EXPECT_EQ(cone.parts[0].size(), 5u);
    EXPECT_EQ(layer->vertices, 11);
    OCTDestroyCoordinateTransformation(t);
    OSRDestroySpatialReference(from);
    OSRDestroySpatialReference(to);
}

// EPSG:4326's authority puts latitude first; the file's x is longitude, as
// every vector format stores it, and must be read so (OAMS_TRADITIONAL_GIS_ORDER).
TEST(VectorLayer, AFileInEpsg4326IsReadLonLat) {
    const auto dir = testing::freshTestDir("vector-layer-4326");
    writeGeoPackage(dir / "f.gpkg", 4326, 174.7644, -36.8767, 0.001);
    Diagnostics diags;
    const auto layer = readVectorLayer(specOf(dir / "f.gpkg"), 1000, diags);
    ASSERT_TRUE(layer);
    EXPECT_NEAR(layer->features[0].parts[0][0].lonDeg, 174.7644, 1e-12);
    EXPECT_NEAR(layer->features[0].parts[0][0].latDeg, -36.8767, 1e-12);
}

TEST(VectorLayer, ACsvsPointsKeepTheirLabelsAsWritten) {
    const auto dir = testing::freshTestDir("vector-layer-csv");
    const std::string hostile = "</svg> #fopen(\"x\") {{terrain}} \xff end";
    std::ofstream(dir / "p.csv") << "lon,lat,name\n174.7644,-36.8767,\"</svg> #fopen(\"\"x\"\") {{terrain}} \xff end\"\n"
                                 << "174.765,-36.877,plain\n";
    Diagnostics diags;
    const auto layer = readVectorLayer(specOf(dir / "p.csv", "name"), 1000, diags);
    ASSERT_TRUE(layer) << (diags.all().empty() ? "" : diags.all().front().message);
    ASSERT_EQ(layer->features.size(), 2u);
    EXPECT_EQ(layer->features[0].label, hostile);
    EXPECT_NEAR(layer->features[1].parts[0][0].lonDeg, 174.765, 1e-12);
}

TEST(VectorLayer, WhatTheFileDoesNotHaveIsNamedWithWhatItHas) {
    const auto dir = testing::freshTestDir("vector-layer-bad");
    writeGeoPackage(dir / "f.gpkg", 2193, 1757475, 5917625, 200);
    Diagnostics attribute;
    EXPECT_FALSE(readVectorLayer(specOf(dir / "f.gpkg", "nmae"), 1000, attribute));
    ASSERT_EQ(attribute.errorCount(), 1);
    EXPECT_NE(attribute.all().front().message.find("has no attribute \"nmae\"; its attributes: \"name\""),
              std::string::npos)
        << attribute.all().front().message;

    scene::LayerSpec missingLayer = specOf(dir / "f.gpkg");
    missingLayer.layer = "roads";
    Diagnostics layer;
    EXPECT_FALSE(readVectorLayer(missingLayer, 1000, layer));
    EXPECT_NE(layer.all().front().message.find("has no layer \"roads\"; its layers: \"features\""), std::string::npos)
        << layer.all().front().message;

    Diagnostics limit;
    EXPECT_FALSE(readVectorLayer(specOf(dir / "f.gpkg"), 5, limit));
    EXPECT_NE(limit.all().front().message.find("over limits.max_layer_vertices = 5"), std::string::npos)
        << limit.all().front().message;

    std::ofstream(dir / "not.geojson") << "this is not GeoJSON";
    Diagnostics unreadable;
    EXPECT_FALSE(readVectorLayer(specOf(dir / "not.geojson"), 1000, unreadable));
    EXPECT_NE(unreadable.all().front().message.find("GDAL reads no vector data in it"), std::string::npos)
        << unreadable.all().front().message;

    std::ofstream(dir / "empty.geojson") << R"({"type": "FeatureCollection", "features": []})";
    Diagnostics empty;
    const auto none = readVectorLayer(specOf(dir / "empty.geojson"), 1000, empty);
    ASSERT_TRUE(none);
    EXPECT_TRUE(none->features.empty());
    ASSERT_EQ(empty.warningCount(), 1);
    EXPECT_NE(empty.all().front().message.find("holds no feature to draw"), std::string::npos);
}

}  // namespace
}  // namespace relief::geo
