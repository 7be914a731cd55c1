#include "measure/auto_depth.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>
#include <omp.h>

#include "core/stopwatch.h"
#include "curves/hausdorff.h"
#include "subdiv/refine.h"

namespace relief::measure {

namespace {

// A net row (along x) or column (along y) as a planar control polygon:
// (position along the line, elevation), packed into Vec3 for the refiner.
struct NetCurve {
    std::string name;
    bool isRow;
    int index;
    std::vector<Vec3> points;
};

std::vector<NetCurve> netCurves(const geo::GeoGrid& net) {
    std::vector<NetCurve> curves;
    for (int r = 0; r < net.grid.rows; ++r) {
        NetCurve c{fmt::format("row {}", r), true, r, {}};
        for (int k = 0; k < net.grid.cols; ++k) c.points.push_back({net.x0 + k * net.dx, net.grid.at(r, k).z, 0});
        curves.push_back(std::move(c));
    }
    for (int k = 0; k < net.grid.cols; ++k) {
        NetCurve c{fmt::format("column {}", k), false, k, {}};
        for (int r = 0; r < net.grid.rows; ++r) c.points.push_back({net.y0 + r * net.dy, net.grid.at(r, k).z, 0});
        curves.push_back(std::move(c));
    }
    return curves;
}

curves::PiecewiseBezier polyline(const std::vector<Vec3>& points) {
    curves::CurveFile line{"polyline", false, {}};
    for (const Vec3& p : points) line.points.push_back({p.x, p.y});
    return curves::toBezier(line);
}

}  // namespace

DepthChoice chooseDepth(const subdiv::Scheme& scheme, const geo::GeoGrid& net, double toleranceM,
                        int maxDepth, int threads) {
    DepthChoice choice;
    std::vector<NetCurve> curves = netCurves(net);
    const int n = static_cast<int>(curves.size());
    const int nThreads = threads > 0 ? threads : omp_get_max_threads();
    // Each step's distances need far less precision than the tolerance, but
    // the rates between levels are worth seeing well below it.
    const double hausdorffTolerance = 1e-4 * toleranceM;
    for (int level = 1; level <= maxDepth; ++level) {
        const auto t0 = Clock::now();
        std::vector<curves::OneSided> witness(curves.size());
        std::vector<double> distance(curves.size());
        std::vector<std::vector<Vec3>> finer(curves.size());
        std::vector<curves::PiecewiseBezier> coarseLine(curves.size()), fineLine(curves.size());
        // Only the largest distance matters: the vertex-only distances (exact
        // lower bounds, cheap) give every curve's exact search a floor to beat.
        std::vector<double> lowerBound(curves.size());
#pragma omp parallel for num_threads(nThreads) schedule(dynamic, 1)
        for (int i = 0; i < n; ++i) {
            finer[i] = subdiv::refineCurve(scheme, curves[i].points);
            coarseLine[i] = polyline(curves[i].points);
            fineLine[i] = polyline(finer[i]);
            lowerBound[i] = curves::vertexHausdorff({&coarseLine[i], 1}, {&fineLine[i], 1});
        }
        const double floor = *std::max_element(lowerBound.begin(), lowerBound.end());
#pragma omp parallel for num_threads(nThreads) schedule(dynamic, 1)
        for (int i = 0; i < n; ++i) {
            const auto h = curves::hausdorff(coarseLine[i], fineLine[i], {hausdorffTolerance, floor});
            // The witness on the finer curve: where the new level put a point
            // farthest from the old one (or the old point farthest from the new).
            witness[i] = h.ba.value >= h.ab.value ? h.ba : h.ab;
            if (h.ba.value < h.ab.value) witness[i].a = h.ab.foot.point;
            distance[i] = h.H;
        }
        for (int i = 0; i < n; ++i) curves[i].points = std::move(finer[i]);
        LevelChange change;
        change.level = level;
        size_t worst = 0;
        for (size_t i = 1; i < curves.size(); ++i)
            if (distance[i] > distance[worst]) worst = i;  // first of equals: independent of threads
        change.distanceM = distance[worst];
        change.curve = curves[worst].name;
        const curves::Point2 w = witness[worst].a;
        change.x = curves[worst].isRow ? w.x : net.x0 + curves[worst].index * net.dx;
        change.y = curves[worst].isRow ? net.y0 + curves[worst].index * net.dy : w.x;
        change.z = w.y;
        change.seconds = secondsSince(t0);
        choice.levels.push_back(change);
        choice.depth = level;
        if (change.distanceM <= toleranceM) {
            choice.reached = true;
            break;
        }
    }
    return choice;
}

double observedRate(const DepthChoice& choice, size_t index, int arity) {
    if (index == 0 || index >= choice.levels.size()) return std::numeric_limits<double>::quiet_NaN();
    const double prev = choice.levels[index - 1].distanceM, cur = choice.levels[index].distanceM;
    if (!(prev > 0 && cur > 0)) return std::numeric_limits<double>::quiet_NaN();
    return std::log(prev / cur) / std::log(arity);
}

}  // namespace relief::measure
