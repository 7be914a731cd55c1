#include "geo/crs_frame.h"

#include <cmath>
#include <string>
#include <tuple>
#include <vector>

#include <cpl_conv.h>

#include "core/text_escape.h"
#include "geo/raster_source.h"

namespace relief::geo {

namespace {

// A CRS's transformations to and from WGS84 (lon, lat), made from its WKT.
struct CrsTransforms {
    std::string wkt;
    Transform toCrs, toWgs84;
};

// This thread's transformations for `wkt`: a scene has one such frame (two
// when compare-geometry sets two rasters side by side), so a short list
// searched by text serves.
const CrsTransforms& transformsFor(const std::string& wkt) {
    thread_local std::vector<CrsTransforms> made;
    for (const auto& t : made)
        if (t.wkt == wkt) return t;
    Srs srs(OSRNewSpatialReference(nullptr));
    const char* text = wkt.c_str();
    OSRSetAxisMappingStrategy(srs.get(), OAMS_TRADITIONAL_GIS_ORDER);
    CrsTransforms t{wkt, nullptr, nullptr};
    if (OSRImportFromWkt(srs.get(), const_cast<char**>(&text)) == OGRERR_NONE)
        std::tie(t.toCrs, t.toWgs84) = wgs84Transforms(srs.get());
    if (made.size() >= 4) made.erase(made.begin());
    made.push_back(std::move(t));
    return made.back();
}

bool transformed(OGRCoordinateTransformationH t, double inX, double inY, double& outX, double& outY) {
    double x = inX, y = inY, z = 0;
    if (!t || !OCTTransform(t, 1, &x, &y, &z) || !std::isfinite(x) || !std::isfinite(y)) return false;
    outX = x, outY = y;
    return true;
}

}  // namespace

bool projectedInMetres(OGRSpatialReferenceH srs) {
    return OSRIsProjected(srs) && std::fabs(OSRGetLinearUnits(srs, nullptr) - 1.0) < 1e-12;
}

std::string crsNameOf(OGRSpatialReferenceH srs, std::string_view unnamed) {
    const char* name = srs ? OSRGetName(srs) : nullptr;
    return name && *name ? oneLineText(name) : std::string(unnamed);
}

Frame crsFrame(OGRSpatialReferenceH srs) {
    Frame f;
    f.kind = scene::FrameKind::Raster;
    char* wkt = nullptr;
    const char* options[] = {"FORMAT=WKT2_2019", nullptr};
    if (OSRExportToWktEx(srs, &wkt, options) == OGRERR_NONE && wkt) f.crsWkt = wkt;
    CPLFree(wkt);
    f.crsName = crsNameOf(srs, "unnamed projected CRS");
    return f;
}

bool crsFrameToLonLat(const Frame& frame, double x, double y, double& lonDeg, double& latDeg) {
    return transformed(static_cast<OGRCoordinateTransformationH>(transformsFor(frame.crsWkt).toWgs84.get()), x, y,
                       lonDeg, latDeg);
}

bool lonLatToCrsFrame(const Frame& frame, double lonDeg, double latDeg, double& x, double& y) {
    return transformed(static_cast<OGRCoordinateTransformationH>(transformsFor(frame.crsWkt).toCrs.get()), lonDeg,
                       latDeg, x, y);
}

}  // namespace relief::geo
