#include "geo/sky_view.h"

#include <algorithm>
#include <cmath>

#include <omp.h>

namespace relief::geo {

namespace {

// One place the horizon search looks at: its offset in node units and its
// distance in metres.
struct Probe {
    double du, dv, distanceM;
};

// The probes of every azimuth, one list after the other, `perDirection` each.
std::vector<Probe> probesOf(const GeoGrid& grid, int directions, double radiusM, int& perDirection) {
    const double step = std::min(grid.dx, grid.dy);
    std::vector<double> distances;
    for (double d = step; d <= radiusM; d = distances.size() < 8 ? d + step : d * 1.2) distances.push_back(d);
    perDirection = static_cast<int>(distances.size());
    std::vector<Probe> probes;
    probes.reserve(static_cast<size_t>(directions) * distances.size());
    for (int k = 0; k < directions; ++k) {
        const double azimuth = 2 * 3.14159265358979323846 * k / directions;
        for (double d : distances)
            probes.push_back({d * std::cos(azimuth) / grid.dx, d * std::sin(azimuth) / grid.dy, d});
    }
    return probes;
}

// The height at fractional node (u, v), or NaN off the grid or where a node
// without data would weigh in.
double heightAt(const GeoGrid& grid, double u, double v) {
    if (u < 0 || v < 0 || u > grid.cols() - 1 || v > grid.rows() - 1) return std::nan("");
    const int c = std::min(static_cast<int>(u), grid.cols() - 2), r = std::min(static_cast<int>(v), grid.rows() - 2);
    if (grid.isMasked(r, c) || grid.isMasked(r, c + 1) || grid.isMasked(r + 1, c) || grid.isMasked(r + 1, c + 1))
        return std::nan("");
    const double fu = u - c, fv = v - r;
    const Grid& g = grid.grid;
    return (1 - fv) * ((1 - fu) * g.at(r, c).z + fu * g.at(r, c + 1).z) +
           fv * ((1 - fu) * g.at(r + 1, c).z + fu * g.at(r + 1, c + 1).z);
}

}  // namespace

double skyViewRadiusM(const GeoGrid& grid, const SkyViewOptions& options) {
    const double side = std::max((grid.cols() - 1) * grid.dx, (grid.rows() - 1) * grid.dy);
    const double radius = options.radiusM > 0 ? options.radiusM : kDefaultRadiusShare * side;
    return std::max(radius, 4 * std::min(grid.dx, grid.dy));
}

std::vector<float> skyViewFactor(const GeoGrid& grid, const SkyViewOptions& options) {
    const int rows = grid.rows(), cols = grid.cols();
    std::vector<float> svf(static_cast<size_t>(rows) * cols, 1.0f);
    if (rows < 2 || cols < 2) return svf;
    int perDirection = 0;
    const std::vector<Probe> probes = probesOf(grid, options.directions, skyViewRadiusM(grid, options), perDirection);
    const int threads = options.threads > 0 ? options.threads : omp_get_num_procs();
#pragma omp parallel for schedule(static) num_threads(threads)
    for (int r = 0; r < rows; ++r)
        for (int c = 0; c < cols; ++c) {
            if (grid.isMasked(r, c)) continue;
            const double z0 = grid.grid.at(r, c).z;
            double hidden = 0;  // sum of the horizons' sines
            for (int k = 0; k < options.directions; ++k) {
                double steepest = 0;  // tan of the horizon's elevation angle, at least level
                for (int j = 0; j < perDirection; ++j) {
                    const Probe& p = probes[static_cast<size_t>(k) * perDirection + j];
                    const double z = heightAt(grid, c + p.du, r + p.dv);
                    if (std::isnan(z)) {
                        if (c + p.du < 0 || r + p.dv < 0 || c + p.du > cols - 1 || r + p.dv > rows - 1) break;
                        continue;
                    }
                    steepest = std::max(steepest, (z - z0) / p.distanceM);
                }
                hidden += steepest / std::sqrt(1 + steepest * steepest);
            }
            svf[static_cast<size_t>(r) * cols + c] = static_cast<float>(1 - hidden / options.directions);
        }
    return svf;
}

}  // namespace relief::geo
