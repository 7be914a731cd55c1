// A vector file's first line: opened as relief opens any file a scene names
// (checked first, its checked siblings only), its layers searched in order.
#include "geo/vector_file.h"

#include <cmath>

#include <fmt/format.h>
#include <gdal.h>
#include <ogr_api.h>

#include "core/text_escape.h"
#include "geo/gdal_handles.h"
#include "geo/gdal_setup.h"
#include "geo/raster_source.h"

namespace relief::geo {

namespace {

constexpr int kMaxLineVertices = 1'000'000;

// The first line of a layer's features: a LineString, or a MultiLineString's first part with two vertices or more.
OGRGeometryH firstLineIn(OGRLayerH layer, Feature& holder) {
    OGR_L_ResetReading(layer);
    while (OGRFeatureH f = OGR_L_GetNextFeature(layer)) {
        holder.reset(f);
        OGRGeometryH g = OGR_F_GetGeometryRef(f);
        if (!g) continue;
        const auto type = wkbFlatten(OGR_G_GetGeometryType(g));
        if (type == wkbLineString && OGR_G_GetPointCount(g) >= 2) return g;
        if (type != wkbMultiLineString) continue;
        for (int i = 0; i < OGR_G_GetGeometryCount(g); ++i)
            if (OGRGeometryH part = OGR_G_GetGeometryRef(g, i); OGR_G_GetPointCount(part) >= 2) return part;
    }
    return nullptr;
}

// The line's vertices in WGS84 lon, lat; false when a vertex cannot be transformed.
bool verticesInWgs84(OGRLayerH layer, OGRGeometryH line, std::vector<GeoPoint>& out) {
    OGRSpatialReferenceH srs = OGR_L_GetSpatialRef(layer);
    Transform toWgs84;
    if (srs) {
        const Srs own(OSRClone(srs));
        OSRSetAxisMappingStrategy(static_cast<OGRSpatialReferenceH>(own.get()), OAMS_TRADITIONAL_GIS_ORDER);
        toWgs84 = std::move(wgs84Transforms(static_cast<OGRSpatialReferenceH>(own.get())).second);
        if (!toWgs84) return false;
    }
    const int n = OGR_G_GetPointCount(line);
    for (int i = 0; i < n; ++i) {
        double x = OGR_G_GetX(line, i), y = OGR_G_GetY(line, i), z = OGR_G_GetZ(line, i);
        const auto t = static_cast<OGRCoordinateTransformationH>(toWgs84.get());
        // With its z: in a geocentric CRS (X, Y, Z from the Earth's centre) a vertex's place needs all three.
        if (t && !OCTTransform(t, 1, &x, &y, &z)) return false;
        if (!(std::isfinite(x) && std::isfinite(y) && std::fabs(x) <= 180 && std::fabs(y) <= 90)) return false;
        out.push_back({x, y, std::isfinite(z) ? z : 0.0});
    }
    return true;
}

}  // namespace

std::string layerNamesOf(GDALDatasetH ds) {
    std::string names;
    for (int i = 0; i < GDALDatasetGetLayerCount(ds); ++i)
        names += fmt::format("{}\"{}\"", names.empty() ? "" : ", ",
                             printableExcerpt(OGR_L_GetName(GDALDatasetGetLayer(ds, i)), 60));
    return names.empty() ? "none" : names;
}

Dataset openVectorFile(const std::filesystem::path& path, const std::string& shown, const SourceLoc& at,
                       Diagnostics& diags, const char* const* openOptions) {
    std::string problem;
    setUpGdal();
    Dataset ds = openChecked(path, GDAL_OF_VECTOR, problem, nullptr, openOptions);
    if (!ds)
        diags.error(at, fmt::format("{}: {}", shown,
                                    problem.empty() ? "GDAL reads no vector data in it (give a GeoJSON, GPX, KML, "
                                                      "Shapefile, GeoPackage, FlatGeobuf or CSV file)"
                                                    : problem));
    return ds;
}

std::optional<std::vector<GeoPoint>> firstLineOf(const std::filesystem::path& path, const std::string& layerName,
                                                 const SourceLoc& at, Diagnostics& diags) {
    const std::string shown = printableExcerpt(path.string(), 200);
    const Dataset ds = openVectorFile(path, shown, at, diags);
    if (!ds) return std::nullopt;
    Feature holder;
    for (int i = 0; i < GDALDatasetGetLayerCount(ds.get()); ++i) {
        OGRLayerH layer = GDALDatasetGetLayer(ds.get(), i);
        if (!layerName.empty() && layerName != OGR_L_GetName(layer)) continue;
        OGRGeometryH line = firstLineIn(layer, holder);
        if (!line) continue;
        if (OGR_G_GetPointCount(line) > kMaxLineVertices) {
            diags.error(at, fmt::format("{}: its line has {} vertices; at most {} are read (simplify it, e.g. "
                                        "ogr2ogr -simplify)",
                                        shown, OGR_G_GetPointCount(line), kMaxLineVertices));
            return std::nullopt;
        }
        std::vector<GeoPoint> points;
        if (!verticesInWgs84(layer, line, points)) {
            diags.error(at, fmt::format("{}: the line in layer \"{}\" cannot be placed in longitude and latitude "
                                        "(its CRS has no transformation to WGS84, or a vertex is off the Earth)",
                                        shown, printableExcerpt(OGR_L_GetName(layer), 60)));
            return std::nullopt;
        }
        return points;
    }
    const bool named = !layerName.empty();
    bool found = !named;
    for (int i = 0; named && i < GDALDatasetGetLayerCount(ds.get()); ++i)
        found = found || layerName == OGR_L_GetName(GDALDatasetGetLayer(ds.get(), i));
    if (!found)
        diags.error(at, fmt::format("{} has no layer \"{}\"; its layers: {}", shown, printableExcerpt(layerName, 60),
                                    layerNamesOf(ds.get())));
    else
        diags.error(at, fmt::format("{} holds no line (a LineString or MultiLineString with two vertices or more) "
                                    "in {}; its layers: {}",
                                    shown,
                                    named ? fmt::format("layer \"{}\"", printableExcerpt(layerName, 60))
                                          : std::string("any layer"),
                                    layerNamesOf(ds.get())));
    return std::nullopt;
}

}  // namespace relief::geo
