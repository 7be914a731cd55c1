#include "geo/profile.h"

#include <algorithm>
#include <cmath>

#include <GeographicLib/Geodesic.hpp>
#include <GeographicLib/GeodesicLine.hpp>

namespace relief::geo {

std::vector<ProfilePoint> geodesicProfile(const Frame& frame, const GeoPoint& from, const GeoPoint& to, int count) {
    const auto& g = GeographicLib::Geodesic::WGS84();
    const GeographicLib::GeodesicLine line = g.InverseLine(from.latDeg, from.lonDeg, to.latDeg, to.lonDeg);
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

std::optional<std::vector<double>> heightsAlong(const GeoGrid& grid,
                                                const std::vector<ProfilePoint>& profile,
                                                size_t& outside) {
    std::vector<double> z;
    z.reserve(profile.size());
    for (size_t i = 0; i < profile.size(); ++i) {
        const auto h = grid.sample(profile[i].x, profile[i].y);
        if (!h) {
            outside = i;
            return std::nullopt;
        }
        z.push_back(*h);
    }
    return z;
}

}  // namespace relief::geo
