#include "geo/geo_grid.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "core/number_format.h"

namespace relief::geo {

std::string Frame::describe() const {
    if (kind == scene::FrameKind::Utm)
        return utmZone == 0 ? fmt::format("UPS {}", northp ? "north" : "south")
                            : fmt::format("UTM zone {}{}", utmZone, northp ? "N" : "S");
    if (kind == scene::FrameKind::Raster) return fmt::format("{} (the raster's own CRS)", crsName);
    return fmt::format("local tangent plane at lat {} lon {}", formatShortest(originLatDeg),
                       formatShortest(originLonDeg));
}

size_t GeoGrid::maskedCount() const {
    return static_cast<size_t>(std::count(masked.begin(), masked.end(), std::uint8_t{1}));
}

std::optional<double> GeoGrid::sample(double x, double y) const {
    const double u = (x - x0) / dx, v = (y - y0) / dy;
    const double eps = 1e-9;  // points on the edge, up to rounding, are inside
    if (u < -eps || v < -eps || u > grid.cols - 1 + eps || v > grid.rows - 1 + eps) return std::nullopt;
    const int c = std::clamp(static_cast<int>(std::floor(u)), 0, grid.cols - 2);
    const int r = std::clamp(static_cast<int>(std::floor(v)), 0, grid.rows - 2);
    const double fu = std::clamp(u - c, 0.0, 1.0), fv = std::clamp(v - r, 0.0, 1.0);
    if ((fu < 1 && fv < 1 && isMasked(r, c)) || (fu > 0 && fv < 1 && isMasked(r, c + 1)) ||
        (fu < 1 && fv > 0 && isMasked(r + 1, c)) || (fu > 0 && fv > 0 && isMasked(r + 1, c + 1)))
        return std::nullopt;  // a node without data would weigh in
    const double z00 = grid.at(r, c).z, z01 = grid.at(r, c + 1).z, z10 = grid.at(r + 1, c).z,
                 z11 = grid.at(r + 1, c + 1).z;
    return (1 - fv) * ((1 - fu) * z00 + fu * z01) + fv * ((1 - fu) * z10 + fu * z11);
}

GeoGrid GeoGrid::refined(Grid nodes, double factor) const {
    GeoGrid out;
    out.frame = frame;
    out.grid = std::move(nodes);
    out.x0 = x0;
    out.y0 = y0;
    out.dx = dx / factor;
    out.dy = dy / factor;
    if (!masked.empty()) {
        // Node i of the refined lattice lies at control coordinate i / f,
        // between control nodes floor(i / f) and ceil(i / f).
        const int f = static_cast<int>(std::lround(factor));
        const int R = out.grid.rows, C = out.grid.cols;
        out.masked.assign(static_cast<size_t>(R) * C, 0);
        for (int r = 0; r < R; ++r) {
            const int r0 = r / f, r1 = std::min((r + f - 1) / f, rows() - 1);
            for (int c = 0; c < C; ++c) {
                const int c0 = c / f, c1 = std::min((c + f - 1) / f, cols() - 1);
                out.masked[static_cast<size_t>(r) * C + c] =
                    isMasked(r0, c0) || isMasked(r0, c1) || isMasked(r1, c0) || isMasked(r1, c1);
            }
        }
    }
    return out;
}

}  // namespace relief::geo
