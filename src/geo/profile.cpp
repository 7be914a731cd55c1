#include "geo/profile.h"

#include <algorithm>
#include <cmath>

#include <GeographicLib/Geodesic.hpp>
#include <GeographicLib/GeodesicLine.hpp>

namespace relief::geo {

std::vector<ProfilePoint> geodesicProfile(const Frame& frame, double lat1, double lon1, double lat2,
                                          double lon2, int count) {
    const auto& g = GeographicLib::Geodesic::WGS84();
    const GeographicLib::GeodesicLine line = g.InverseLine(lat1, lon1, lat2, lon2);
    const double total = line.Distance();
    std::vector<GeoSample> samples;
    std::vector<ProfilePoint> out;
    for (int i = 0; i < count; ++i) {
        const double s = total * i / (count - 1);
        double lat, lon;
        line.Position(s, lat, lon);
        samples.push_back({lon, lat, 0.0, {}});
        out.push_back({s, lat, lon, 0, 0});
    }
    Diagnostics ignored;  // points came from valid coordinates; a zone failure leaves them out
    const auto projected = projectSamples(frame, samples, ignored);
    for (size_t i = 0; i < out.size() && i < projected.size(); ++i) {
        out[i].x = projected[i].p.x;
        out[i].y = projected[i].p.y;
    }
    return out;
}

std::optional<double> sampleLattice(const Grid& grid, double x0, double y0, double dx, double dy,
                                    double x, double y) {
    const double u = (x - x0) / dx, v = (y - y0) / dy;
    const double eps = 1e-9;
    if (u < -eps || v < -eps || u > grid.cols - 1 + eps || v > grid.rows - 1 + eps) return std::nullopt;
    const int c = std::clamp(static_cast<int>(std::floor(u)), 0, grid.cols - 2);
    const int r = std::clamp(static_cast<int>(std::floor(v)), 0, grid.rows - 2);
    const double fu = std::clamp(u - c, 0.0, 1.0), fv = std::clamp(v - r, 0.0, 1.0);
    const double z00 = grid.at(r, c).z, z01 = grid.at(r, c + 1).z, z10 = grid.at(r + 1, c).z,
                 z11 = grid.at(r + 1, c + 1).z;
    return (1 - fv) * ((1 - fu) * z00 + fu * z01) + fv * ((1 - fu) * z10 + fu * z11);
}

}  // namespace relief::geo
