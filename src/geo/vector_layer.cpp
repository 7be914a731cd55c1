// A [[layer]]'s features: opened as relief opens any file a scene names
// (checked first, its checked siblings only), the layer found, every geometry
// flattened to points, lines and polygon rings in WGS84.
#include "geo/vector_layer.h"

#include <cmath>
#include <memory>

#include <fmt/format.h>
#include <gdal.h>
#include <ogr_api.h>
#include <ogr_srs_api.h>

#include "core/number_format.h"
#include "core/text_escape.h"
#include "geo/gdal_crs.h"
#include "geo/gdal_handles.h"
#include "geo/gdal_setup.h"
#include "geo/raster_source.h"
#include "geo/vector_file.h"

namespace relief::geo {

namespace {

// A CSV's points are in columns GDAL must be told of; a WKT column it finds itself.
constexpr const char* kOpenOptions[] = {"X_POSSIBLE_NAMES=lon,long,longitude,x,easting",
                                        "Y_POSSIBLE_NAMES=lat,latitude,y,northing", "KEEP_GEOM_COLUMNS=NO", nullptr};

std::string quotedList(std::vector<std::string> names) {
    std::string out;
    for (const auto& n : names) out += fmt::format("{}\"{}\"", out.empty() ? "" : ", ", printableExcerpt(n, 60));
    return out.empty() ? "none" : out;
}

// The layer asked for, or the first with a feature (a GPX's waypoints before its empty routes).
OGRLayerH findLayer(GDALDatasetH ds, const std::string& name) {
    for (int i = 0; i < GDALDatasetGetLayerCount(ds); ++i) {
        OGRLayerH layer = GDALDatasetGetLayer(ds, i);
        if (!name.empty() ? name == OGR_L_GetName(layer) : OGR_L_GetFeatureCount(layer, TRUE) > 0) return layer;
    }
    return name.empty() && GDALDatasetGetLayerCount(ds) > 0 ? GDALDatasetGetLayer(ds, 0) : nullptr;
}

// A layer's coordinates carried to WGS84 lon, lat; `geocentric`: its CRS's
// X, Y, Z are from the Earth's centre, so a vertex needs all three to be a place.
struct LayerCrs {
    Transform toWgs84;
    bool geocentric = false;
};

// A layer lies on the surface: its heights are never used. In a geocentric
// CRS, though, the Z of a vertex is a third of its place, not a height: it is
// used to place it, and the warning says its height is not.
void warnGeocentric(const scene::LayerSpec& spec, Diagnostics& diags) {
    diags.warning(spec.locs.at("layer.path"),
                  fmt::format("layer {} ({}): its CRS is geocentric (X, Y, Z from the Earth's centre): each vertex is "
                              "placed from all three, and its height is not used (a layer lies on the surface)",
                              spec.number, printableExcerpt(spec.pathAsWritten, 200)));
}

// Whose coordinates: the file's own CRS, else the scene's `crs`, else WGS84
// lon, lat (nullptr: no transformation). Sets `problem` when it cannot be placed.
LayerCrs toWgs84Of(OGRLayerH layer, const scene::LayerSpec& spec, Diagnostics& diags, std::string& problem) {
    OGRSpatialReferenceH own = OGR_L_GetSpatialRef(layer);
    Srs srs;
    if (own) {
        srs.reset(OSRClone(own));
        if (!spec.crs.empty())
            diags.warning(spec.locs.at("layer.crs"), fmt::format("layer.crs is not used: {} declares its own CRS",
                                                                 printableExcerpt(spec.pathAsWritten, 200)));
    } else if (!spec.crs.empty()) {
        srs.reset(OSRNewSpatialReference(nullptr));
        if (!crsFromText(static_cast<OGRSpatialReferenceH>(srs.get()), spec.crs, problem)) return {};
    } else {
        return {};
    }
    const auto h = static_cast<OGRSpatialReferenceH>(srs.get());
    OSRSetAxisMappingStrategy(h, OAMS_TRADITIONAL_GIS_ORDER);
    LayerCrs crs{std::move(wgs84Transforms(h).second), OSRIsGeocentric(h) != 0};
    if (!crs.toWgs84) problem = "its CRS has no transformation to WGS84";
    else if (crs.geocentric) warnGeocentric(spec, diags);
    return crs;
}

// Reads every feature's geometry and label into `out`, within the limit.
class FeatureReader {
public:
    FeatureReader(const LayerCrs& crs, int labelField, long long maxVertices)
        : toWgs84_(static_cast<OGRCoordinateTransformationH>(crs.toWgs84.get())),
          geocentric_(crs.geocentric),
          labelField_(labelField),
          maxVertices_(maxVertices) {}

    // False, with `problem` set, at the first vertex that cannot be placed or past the limit.
    bool read(OGRFeatureH f, const std::string& fixedLabel, VectorLayer& out, std::string& problem) {
        OGRGeometryH g = OGR_F_GetGeometryRef(f);
        if (!g || OGR_G_IsEmpty(g)) {
            ++out.withoutGeometry;
            return true;
        }
        Geometry linear;
        if (OGR_GT_IsNonLinear(OGR_G_GetGeometryType(g))) {
            linear.reset(OGR_G_GetLinearGeometry(g, 0, nullptr));
            g = static_cast<OGRGeometryH>(linear.get());
        }
        std::string label = fixedLabel;
        if (labelField_ >= 0 && OGR_F_IsFieldSetAndNotNull(f, labelField_)) label = OGR_F_GetFieldAsString(f, labelField_);
        return add(g, OGR_F_GetFID(f), label, out, problem);
    }

private:
    bool add(OGRGeometryH g, long long fid, const std::string& label, VectorLayer& out, std::string& problem) {
        switch (wkbFlatten(OGR_G_GetGeometryType(g))) {
            case wkbPoint:
            case wkbLineString:
            case wkbPolygon: {
                VectorFeature f;
                f.fid = fid;
                f.label = label;
                if (!shape(g, f, out, problem)) return false;
                out.features.push_back(std::move(f));
                return true;
            }
            default:  // multi-geometries and collections: each part a feature of its own
                for (int i = 0; i < OGR_G_GetGeometryCount(g); ++i)
                    if (!add(OGR_G_GetGeometryRef(g, i), fid, label, out, problem)) return false;
                return true;
        }
    }

    bool shape(OGRGeometryH g, VectorFeature& f, VectorLayer& out, std::string& problem) {
        const auto type = wkbFlatten(OGR_G_GetGeometryType(g));
        f.kind = type == wkbPoint ? FeatureKind::Point : type == wkbLineString ? FeatureKind::Line : FeatureKind::Polygon;
        if (f.kind != FeatureKind::Polygon) return ring(g, f, out, problem);
        for (int i = 0; i < OGR_G_GetGeometryCount(g); ++i)
            if (!ring(OGR_G_GetGeometryRef(g, i), f, out, problem)) return false;
        return true;
    }

    bool ring(OGRGeometryH g, VectorFeature& f, VectorLayer& out, std::string& problem) {
        const int n = OGR_G_GetPointCount(g);
        if ((out.vertices += n) > maxVertices_) {
            overLimit_ = true;
            return false;
        }
        if (geocentric_ && !OGR_G_Is3D(g)) {
            problem = fmt::format("feature {} has no Z: in a geocentric CRS (X, Y, Z from the Earth's centre) a "
                                  "vertex needs all three to be a place; give the layer with its Z or in longitude "
                                  "and latitude",
                                  f.fid);
            return false;
        }
        std::vector<GeoPoint>& part = f.parts.emplace_back();
        part.reserve(static_cast<size_t>(n));
        for (int i = 0; i < n; ++i) {
            double x = OGR_G_GetX(g, i), y = OGR_G_GetY(g, i), z = OGR_G_GetZ(g, i);
            if (toWgs84_ && !OCTTransform(toWgs84_, 1, &x, &y, &z)) x = NAN;
            if (!(std::isfinite(x) && std::isfinite(y) && std::fabs(x) <= 180 && std::fabs(y) <= 90)) {
                problem = fmt::format("feature {} has a vertex ({}, {}) that is not a longitude and latitude{}",
                                      f.fid, formatShortest(OGR_G_GetX(g, i)), formatShortest(OGR_G_GetY(g, i)),
                                      toWgs84_ ? " in its CRS" : ": the file declares no CRS; give it as layer.crs");
                return false;
            }
            part.push_back({x, y, 0});
        }
        return true;
    }

    OGRCoordinateTransformationH toWgs84_;
    bool geocentric_;
    int labelField_;
    long long maxVertices_;
    bool overLimit_ = false;

public:
    bool overLimit() const { return overLimit_; }
};

std::vector<std::string> fieldNames(OGRLayerH layer) {
    std::vector<std::string> names;
    OGRFeatureDefnH defn = OGR_L_GetLayerDefn(layer);
    for (int i = 0; i < OGR_FD_GetFieldCount(defn); ++i) names.emplace_back(OGR_Fld_GetNameRef(OGR_FD_GetFieldDefn(defn, i)));
    return names;
}

// The label attribute's index, -1 without one; nullopt (and an error listing them) when the layer has no such attribute.
std::optional<int> labelFieldOf(OGRLayerH layer, const scene::LayerSpec& spec, Diagnostics& diags) {
    if (spec.labelField.empty()) return -1;
    const int i = OGR_FD_GetFieldIndex(OGR_L_GetLayerDefn(layer), spec.labelField.c_str());
    if (i >= 0) return i;
    diags.error(spec.locs.at("layer.label"),
                fmt::format("layer.label: layer \"{}\" of {} has no attribute \"{}\"; its attributes: {}",
                            printableExcerpt(OGR_L_GetName(layer), 60), printableExcerpt(spec.pathAsWritten, 200),
                            printableExcerpt(spec.labelField, 60), quotedList(fieldNames(layer))));
    return std::nullopt;
}

}  // namespace

std::optional<VectorLayer> readVectorLayer(const scene::LayerSpec& spec, long long maxVertices, Diagnostics& diags) {
    const std::string shown = printableExcerpt(spec.pathAsWritten, 200);
    const SourceLoc at = spec.locs.at("layer.path");
    const Dataset ds = openVectorFile(spec.path, "layer.path: " + shown, at, diags, kOpenOptions);
    if (!ds) return std::nullopt;
    OGRLayerH layer = findLayer(ds.get(), spec.layer);
    if (!layer) {
        diags.error(spec.locs.at(spec.layer.empty() ? "layer.path" : "layer.layer"),
                    fmt::format("{} has no layer{}; its layers: {}", shown,
                                spec.layer.empty() ? "" : fmt::format(" \"{}\"", printableExcerpt(spec.layer, 60)),
                                layerNamesOf(ds.get())));
        return std::nullopt;
    }
    const auto labelField = labelFieldOf(layer, spec, diags);
    if (!labelField) return std::nullopt;
    std::string problem;
    const LayerCrs crs = toWgs84Of(layer, spec, diags, problem);
    if (!problem.empty()) {
        diags.error(spec.locs.at("layer.crs"), fmt::format("{}: {}", shown, problem));
        return std::nullopt;
    }
    VectorLayer out;
    out.name = OGR_L_GetName(layer);
    FeatureReader reader(crs, *labelField, maxVertices);
    OGR_L_ResetReading(layer);
    while (Feature f{OGR_L_GetNextFeature(layer)}) {
        if (reader.read(static_cast<OGRFeatureH>(f.get()), spec.labelText, out, problem)) continue;
        if (reader.overLimit())
            diags.error(spec.locs.at("layer.path"),
                        fmt::format("layer {} ({}): more than {} vertices, over limits.max_layer_vertices = {}: "
                                    "simplify it first (ogr2ogr -simplify) or raise the limit",
                                    spec.number, shown, maxVertices, maxVertices));
        else
            diags.error(spec.locs.at(spec.crs.empty() ? "layer.path" : "layer.crs"), fmt::format("{}: {}", shown, problem));
        return std::nullopt;
    }
    if (out.features.empty())
        diags.warning(at, fmt::format("layer {} ({}, layer \"{}\") holds no feature to draw", spec.number, shown,
                                      printableExcerpt(out.name, 60)));
    return out;
}

}  // namespace relief::geo
