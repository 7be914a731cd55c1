#include "fit/basis.h"

#include <algorithm>
#include <map>

#include "subdiv/refine.h"

namespace relief::fit {

bool AxisBasis::locate(double u, int& k, double& f) const {
    if (position.size() < 2 || !(u >= position.front() && u <= position.back())) return false;
    k = static_cast<int>(std::upper_bound(position.begin(), position.end(), u) - position.begin()) - 1;
    k = std::clamp(k, 0, static_cast<int>(position.size()) - 2);
    const double width = position[k + 1] - position[k];
    f = width > 0 ? (u - position[k]) / width : 0;
    return true;
}

AxisBasis axisBasis(const subdiv::Scheme& scheme, int nodes, int depth) {
    AxisBasis b;
    b.nodes = nodes;
    // Positions: the nodes' own indices refined (a symmetric scheme keeps them on the lattice).
    std::vector<Vec3> line(static_cast<size_t>(nodes));
    for (int j = 0; j < nodes; ++j) line[j] = {double(j), 0, 0};
    const std::vector<Vec3> positions = subdiv::refineCurveLevels(scheme, line, false, depth);
    b.position.reserve(positions.size());
    for (const Vec3& p : positions) b.position.push_back(p.x);
    b.weights.resize(positions.size());
    for (int j = 0; j < nodes; ++j) {
        for (int i = 0; i < nodes; ++i) line[i] = {0, 0, i == j ? 1.0 : 0.0};
        const std::vector<Vec3> impulse = subdiv::refineCurveLevels(scheme, line, false, depth);
        for (size_t k = 0; k < impulse.size(); ++k)
            if (impulse[k].z != 0) b.weights[k].emplace_back(j, impulse[k].z);
    }
    for (size_t k = 0; k + 1 < b.weights.size(); ++k) {  // nodes come in order: first and last bound them
        const auto &w0 = b.weights[k], &w1 = b.weights[k + 1];
        if (w0.empty() && w1.empty()) continue;
        const int first = std::min(w0.empty() ? nodes : w0.front().first, w1.empty() ? nodes : w1.front().first);
        const int last = std::max(w0.empty() ? -1 : w0.back().first, w1.empty() ? -1 : w1.back().first);
        b.span = std::max(b.span, last - first + 1);
    }
    return b;
}

namespace {

// (1 - f) times refined index k's weights plus f times k + 1's, merged by node.
void blend(const AxisBasis& b, int k, double f, std::vector<std::pair<int, double>>& out) {
    out.clear();
    for (const auto& [node, w] : b.weights[static_cast<size_t>(k)]) out.emplace_back(node, (1 - f) * w);
    for (const auto& [node, w] : b.weights[static_cast<size_t>(k) + 1]) {
        auto at = std::find_if(out.begin(), out.end(), [n = node](const auto& e) { return e.first == n; });
        if (at != out.end()) at->second += f * w;
        else out.emplace_back(node, f * w);
    }
    std::sort(out.begin(), out.end());
}

}  // namespace

bool surfaceRow(const AxisBasis& bx, const AxisBasis& by, const geo::GeoGrid& net, double x, double y, SurfaceRow& row) {
    int kx = 0, ky = 0;
    double fx = 0, fy = 0;
    if (!bx.locate((x - net.x0) / net.dx, kx, fx) || !by.locate((y - net.y0) / net.dy, ky, fy)) return false;
    blend(bx, kx, fx, row.x);
    blend(by, ky, fy, row.y);
    return true;
}

}  // namespace relief::fit
