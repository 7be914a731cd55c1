#include "measure/peak_loss.h"

#include <algorithm>
#include <cmath>

namespace relief::measure {

PeakLoss peakLoss(const Vec3& peak, const geo::GeoGrid& refined, double radiusM) {
    PeakLoss out;
    out.peak = peak;
    out.surfaceHighest = {peak.x, peak.y, -1e300};
    const int c0 = std::max(0, static_cast<int>(std::floor((peak.x - radiusM - refined.x0) / refined.dx)));
    const int c1 = std::min(refined.cols() - 1, static_cast<int>(std::ceil((peak.x + radiusM - refined.x0) / refined.dx)));
    const int r0 = std::max(0, static_cast<int>(std::floor((peak.y - radiusM - refined.y0) / refined.dy)));
    const int r1 = std::min(refined.rows() - 1, static_cast<int>(std::ceil((peak.y + radiusM - refined.y0) / refined.dy)));
    for (int r = r0; r <= r1; ++r)
        for (int c = c0; c <= c1; ++c) {
            const Vec3& p = refined.grid.at(r, c);
            if (refined.isMasked(r, c) || std::hypot(p.x - peak.x, p.y - peak.y) > radiusM) continue;
            if (p.z > out.surfaceHighest.z) out.surfaceHighest = p;
        }
    out.lossM = out.surfaceHighest.z > -1e299 ? peak.z - out.surfaceHighest.z : 0;
    return out;
}

Vec3 highestNode(const geo::GeoGrid& net) {
    Vec3 best{0, 0, -1e300};
    for (int r = 0; r < net.rows(); ++r)
        for (int c = 0; c < net.cols(); ++c)
            if (!net.isMasked(r, c) && net.grid.at(r, c).z > best.z) best = net.grid.at(r, c);
    return best;
}

}  // namespace relief::measure
