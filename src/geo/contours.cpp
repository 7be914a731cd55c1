#include "geo/contours.h"

#include <algorithm>
#include <cmath>
#include <memory>

#include <fmt/format.h>
#include <gdal.h>
#include <gdal_alg.h>
#include <ogr_api.h>

#include "geo/gdal_handles.h"
#include "geo/gdal_setup.h"

namespace relief::geo {

std::vector<curves::CurveSet> contourLines(const geo::GeoGrid& lat, const std::vector<double>& levels,
                                           std::string& error) {
    std::vector<curves::CurveSet> out(levels.size());
    if (levels.empty()) return out;
    geo::setUpGdal();
    const Grid& g = lat.grid;
    // The raster: GDAL's row 0 is north, so rows are flipped; the pixel
    // centres are the nodes.
    geo::Dataset raster(GDALCreate(GDALGetDriverByName("MEM"), "", g.cols, g.rows, 1, GDT_Float64, nullptr));
    geo::Dataset vector(GDALCreate(GDALGetDriverByName("Memory"), "", 0, 0, 0, GDT_Unknown, nullptr));
    if (!raster || !vector) {
        error = "GDAL's MEM or Memory driver is missing";
        return out;
    }
    double transform[6] = {lat.x0 - 0.5 * lat.dx, lat.dx, 0, lat.y0 + (g.rows - 0.5) * lat.dy, 0, -lat.dy};
    GDALSetGeoTransform(raster.get(), transform);
    // Masked nodes (no data) are GDAL's nodata: no contour crosses them.
    constexpr double kMaskedHeight = -1.0e30;
    std::vector<double> row(static_cast<size_t>(g.cols));
    GDALRasterBandH band = GDALGetRasterBand(raster.get(), 1);
    for (int r = 0; r < g.rows; ++r) {
        for (int c = 0; c < g.cols; ++c)
            row[c] = lat.isMasked(g.rows - 1 - r, c) ? kMaskedHeight : g.at(g.rows - 1 - r, c).z;
        if (GDALRasterIO(band, GF_Write, 0, r, g.cols, 1, row.data(), g.cols, 1, GDT_Float64, 0, 0) != CE_None) {
            error = CPLGetLastErrorMsg();
            return out;
        }
    }
    OGRLayerH layer = GDALDatasetCreateLayer(vector.get(), "contours", nullptr, wkbLineString, nullptr);
    OGRFieldDefnH id = OGR_Fld_Create("id", OFTInteger), elev = OGR_Fld_Create("elev", OFTReal);
    OGR_L_CreateField(layer, id, TRUE);
    OGR_L_CreateField(layer, elev, TRUE);
    OGR_Fld_Destroy(id);
    OGR_Fld_Destroy(elev);
    std::vector<double> fixed = levels;
    if (GDALContourGenerate(band, 0, 0, static_cast<int>(fixed.size()), fixed.data(), !lat.masked.empty(),
                            kMaskedHeight, layer, 0, 1,
                            nullptr, nullptr) != CE_None) {
        error = fmt::format("GDALContourGenerate failed: {}", CPLGetLastErrorMsg());
        return out;
    }
    // Features in GDAL's order, which depends only on the raster: deterministic.
    OGR_L_ResetReading(layer);
    while (const geo::Feature feature{OGR_L_GetNextFeature(layer)}) {
        OGRFeatureH f = feature.get();
        const double level = OGR_F_GetFieldAsDouble(f, 1);
        const auto it = std::find(levels.begin(), levels.end(), level);
        OGRGeometryH geom = OGR_F_GetGeometryRef(f);
        const int n = geom ? OGR_G_GetPointCount(geom) : 0;
        if (it != levels.end() && n >= 2) {
            std::vector<curves::Point2> pts;
            for (int i = 0; i < n; ++i) pts.push_back({OGR_G_GetX(geom, i), OGR_G_GetY(geom, i)});
            const bool closed = pts.front().x == pts.back().x && pts.front().y == pts.back().y;
            if (closed) pts.pop_back();
            out[static_cast<size_t>(it - levels.begin())].push_back(
                curves::toBezier(curves::CurveFile{"polyline", closed && pts.size() >= 3, pts}));
        }
    }
    return out;
}

curves::CurveSet clipToBox(const curves::CurveSet& lines, double xmin, double ymin, double xmax,
                           double ymax) {
    curves::CurveSet out;
    auto inside = [&](curves::Point2 p) { return p.x >= xmin && p.x <= xmax && p.y >= ymin && p.y <= ymax; };
    for (const auto& line : lines) {
        const bool whole = std::all_of(line.segments.begin(), line.segments.end(), [&](const auto& s) {
            return std::all_of(s.control.begin(), s.control.end(), inside);
        });
        if (whole) {
            out.push_back(line);
            continue;
        }
        std::vector<curves::Point2> run;  // the line being built
        auto flush = [&] {
            if (run.size() >= 2) out.push_back(curves::toBezier(curves::CurveFile{"polyline", false, run}));
            run.clear();
        };
        for (const auto& seg : line.segments) {
            if (seg.control.size() != 2) continue;  // contour lines are polylines
            const curves::Point2 p = seg.control[0], q = seg.control[1];
            // Liang–Barsky: the parameter range of the segment inside the box.
            double t0 = 0, t1 = 1;
            const double dx = q.x - p.x, dy = q.y - p.y;
            bool visible = true;
            for (const auto& [num, den] : {std::pair{p.x - xmin, -dx}, std::pair{xmax - p.x, dx},
                                           std::pair{p.y - ymin, -dy}, std::pair{ymax - p.y, dy}}) {
                if (den == 0) {
                    if (num < 0) visible = false;
                    continue;
                }
                const double t = num / den;  // den * t <= num inside: where it crosses this side
                if (den < 0) t0 = std::max(t0, t);
                else t1 = std::min(t1, t);
            }
            if (!visible || t0 > t1) {
                flush();
                continue;
            }
            const curves::Point2 a{p.x + t0 * dx, p.y + t0 * dy}, b{p.x + t1 * dx, p.y + t1 * dy};
            if (run.empty() || t0 > 0) {
                flush();
                run.push_back(a);
            }
            run.push_back(b);
            if (t1 < 1) flush();
        }
        flush();
    }
    return out;
}

std::vector<double> niceLevels(double lo, double hi, int count) {
    std::vector<double> out;
    if (!(hi > lo) || count < 1) return out;
    const double raw = (hi - lo) / (count + 1);
    const double p = std::pow(10.0, std::floor(std::log10(raw)));
    double step = p;
    for (double m : {1.0, 2.0, 5.0, 10.0})
        if (m * p >= raw) {
            step = m * p;
            break;
        }
    for (double v = std::floor(lo / step + 1) * step; v < hi; v += step)
        if (v > lo) out.push_back(std::round(v / step) * step);
    return out;
}

}  // namespace relief::geo
