#include "measure/peak_loss.h"

#include <algorithm>
#include <cmath>

namespace relief::measure {

PeakLoss peakLoss(const Vec3& peak, const geo::GeoGrid& refined, double radiusM) {
    PeakLoss out;
    out.peak = peak;
    out.surfaceHighest = {peak.x, peak.y, -1e300};
    const int rows = refined.rows(), cols = refined.cols();
    auto at = [](double v, int n) { return geo::GeoGrid::indexWithin(v, n); };
    const int c0 = std::max(0, at(std::floor((peak.x - radiusM - refined.x0) / refined.dx), cols));
    const int c1 = std::min(cols - 1, at(std::ceil((peak.x + radiusM - refined.x0) / refined.dx), cols));
    const int r0 = std::max(0, at(std::floor((peak.y - radiusM - refined.y0) / refined.dy), rows));
    const int r1 = std::min(rows - 1, at(std::ceil((peak.y + radiusM - refined.y0) / refined.dy), rows));
    for (int r = r0; r <= r1; ++r)
        for (int c = c0; c <= c1; ++c) {
            const Vec3& p = refined.grid.at(r, c);
            if (refined.isMasked(r, c) || std::hypot(p.x - peak.x, p.y - peak.y) > radiusM) continue;
            if (p.z > out.surfaceHighest.z) out.surfaceHighest = p;
        }
    if (out.surfaceHighest.z < -1e299) out.surfaceHighest.z = peak.z;  // no surface near it: nothing to lose there
    out.lossM = peak.z - out.surfaceHighest.z;
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
