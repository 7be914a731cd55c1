#include "film/flyover.h"

#include <algorithm>
#include <cmath>
#include <deque>

namespace relief::film {

namespace {

constexpr size_t kMaxPathSamples = 2'000'000;

double groundDistance(const Vec3& a, const Vec3& b) {
    return std::hypot(b.x - a.x, b.y - a.y);
}

// One segment P1 -> P2 of the spline with neighbours P0, P3 (the Barry-Goldman pyramid), at u in [0, 1).
Vec3 catmullRomAt(const Vec3 (&p)[4], const double (&t)[4], double u) {
    const double s = t[1] + (t[2] - t[1]) * u;
    const auto lerp = [](const Vec3& a, const Vec3& b, double ta, double tb, double x) {
        return (tb - x) / (tb - ta) * a + (x - ta) / (tb - ta) * b;
    };
    const Vec3 a1 = lerp(p[0], p[1], t[0], t[1], s), a2 = lerp(p[1], p[2], t[1], t[2], s),
               a3 = lerp(p[2], p[3], t[2], t[3], s);
    const Vec3 b1 = lerp(a1, a2, t[0], t[2], s), b2 = lerp(a2, a3, t[1], t[3], s);
    return lerp(b1, b2, t[1], t[2], s);
}

// A dense polyline along the path, and each sample's ground distance from the start.
struct DensePath {
    std::vector<Vec3> points;
    std::vector<double> along;
    double length() const { return along.back(); }
    Vec3 at(double s) const;  ///< the point at ground distance s (past the ends: straight on)
};

Vec3 DensePath::at(double s) const {
    const size_t n = points.size();
    if (s >= along.back()) {
        const Vec3 &a = points[n - 2], &b = points[n - 1];
        const double d = groundDistance(a, b);
        return d > 0 ? b + ((s - along.back()) / d) * (b - a) : b;
    }
    if (s <= 0) return points.front();
    const size_t j = std::upper_bound(along.begin(), along.end(), s) - along.begin();
    const double span = along[j] - along[j - 1];
    const double f = span > 0 ? (s - along[j - 1]) / span : 0;
    return points[j - 1] + f * (points[j] - points[j - 1]);
}

DensePath densePath(const std::vector<Vec3>& points, double spacing) {
    double total = 0;
    for (size_t i = 1; i < points.size(); ++i) total += groundDistance(points[i - 1], points[i]);
    // About one sample a ground cell, fewer on a long path.
    const double step = std::max(spacing, total / double(kMaxPathSamples));
    // At least a few a segment, so that short ones stay curved, unless that alone passes the cap.
    const int fewest = (points.size() - 1) * 8 <= kMaxPathSamples ? 8 : 1;
    std::vector<int> perSegment;
    for (size_t i = 1; i < points.size(); ++i)
        perSegment.push_back(
            std::max(fewest, static_cast<int>(std::ceil(groundDistance(points[i - 1], points[i]) / step))));
    DensePath d;
    d.points = centripetalCatmullRom(points, perSegment);
    d.along.assign(d.points.size(), 0.0);
    for (size_t i = 1; i < d.points.size(); ++i)
        d.along[i] = d.along[i - 1] + groundDistance(d.points[i - 1], d.points[i]);
    return d;
}

// The highest ground within `reach` along the path of each of `stations` (increasing ground distances).
std::vector<double> highestGroundNear(const DensePath& path, const std::vector<double>& stations, double reach,
                                      const Ground& ground) {
    std::vector<double> heights(path.points.size());
    for (size_t i = 0; i < heights.size(); ++i) heights[i] = ground.highestAt(path.points[i].x, path.points[i].y);
    // A sliding window's maximum: a deque of samples in decreasing height.
    std::vector<double> out;
    std::deque<size_t> window;
    size_t next = 0;
    for (const double s : stations) {
        while (next < heights.size() && path.along[next] <= s + reach) {
            while (!window.empty() && heights[window.back()] <= heights[next]) window.pop_back();
            window.push_back(next++);
        }
        while (!window.empty() && path.along[window.front()] < s - reach) window.pop_front();
        const Vec3 here = path.at(s);
        out.push_back(std::max(window.empty() ? -1e300 : heights[window.front()], ground.highestAt(here.x, here.y)));
    }
    return out;
}

}  // namespace

std::vector<Vec3> centripetalCatmullRom(std::span<const Vec3> points, std::span<const int> perSegment) {
    const size_t n = points.size();
    std::vector<Vec3> out;
    for (size_t i = 0; i + 1 < n; ++i) {
        const Vec3 p1 = points[i], p2 = points[i + 1];
        const Vec3 p0 = i > 0 ? points[i - 1] : p1 + (p1 - p2);
        const Vec3 p3 = i + 2 < n ? points[i + 2] : p2 + (p2 - p1);
        const Vec3 p[4] = {p0, p1, p2, p3};
        double t[4] = {0, 0, 0, 0};
        for (int k = 1; k < 4; ++k) t[k] = t[k - 1] + std::max(std::sqrt(length(p[k] - p[k - 1])), 1e-9);
        const int steps = std::max(1, perSegment[i]);
        for (int k = 0; k < steps; ++k) out.push_back(catmullRomAt(p, t, double(k) / steps));
    }
    out.push_back(points[n - 1]);
    return out;
}

Ground::Cell Ground::cellAt(double x, double y) const {
    const double u = std::clamp((x - grid_.x0) / grid_.dx, 0.0, double(grid_.cols() - 1));
    const double v = std::clamp((y - grid_.y0) / grid_.dy, 0.0, double(grid_.rows() - 1));
    const int c = std::min(static_cast<int>(u), grid_.cols() - 2), r = std::min(static_cast<int>(v), grid_.rows() - 2);
    return {r, c, u - c, v - r};
}

bool Ground::covers(double x, double y) const {
    return x >= grid_.x0 && x <= grid_.xMax() && y >= grid_.y0 && y <= grid_.yMax();
}

double Ground::heightAt(double x, double y) const {
    const Cell k = cellAt(x, y);
    const auto z = [&](int dr, int dc) { return grid_.grid.at(k.r + dr, k.c + dc).z; };
    return (1 - k.fy) * ((1 - k.fx) * z(0, 0) + k.fx * z(0, 1)) + k.fy * ((1 - k.fx) * z(1, 0) + k.fx * z(1, 1));
}

double Ground::highestAt(double x, double y) const {
    const Cell k = cellAt(x, y);
    const auto z = [&](int dr, int dc) { return grid_.grid.at(k.r + dr, k.c + dc).z; };
    return std::max({z(0, 0), z(0, 1), z(1, 0), z(1, 1)});
}

double Ground::diagonal() const {
    return std::hypot(grid_.xMax() - grid_.x0, grid_.yMax() - grid_.y0);
}

std::vector<FlyoverCamera> flyoverCameras(const FlyoverPath& path, int frames, const Ground& ground) {
    const DensePath dense = densePath(path.points, ground.spacing());
    std::vector<double> stations;
    for (int k = 0; k < frames; ++k) stations.push_back(frames > 1 ? dense.length() * k / (frames - 1) : 0.0);
    std::vector<Vec3> eyes;
    for (const double s : stations) eyes.push_back(dense.at(s));
    if (path.aboveGroundM) {
        const auto highest = highestGroundNear(dense, stations, *path.aboveGroundM, ground);
        for (size_t k = 0; k < eyes.size(); ++k) eyes[k].z = highest[k] + *path.aboveGroundM;
    }
    double meanAbove = 0;
    for (const Vec3& e : eyes) meanAbove += (e.z - ground.heightAt(e.x, e.y)) / double(eyes.size());
    const double ahead = path.lookAheadM.value_or(std::max(dense.length() / 10, 4 * std::max(meanAbove, 0.0)));
    std::vector<FlyoverCamera> cameras;
    for (size_t k = 0; k < eyes.size(); ++k) {
        Vec3 target = path.lookAtM ? *path.lookAtM : dense.at(stations[k] + ahead);
        if (!path.lookAtM) target.z = ground.heightAt(target.x, target.y);
        cameras.push_back({eyes[k], target});
    }
    return cameras;
}

}  // namespace relief::film
