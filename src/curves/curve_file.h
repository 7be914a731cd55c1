#pragma once
// Planar curve files (JSON), shared by `relief curve` and the Hausdorff tools:
//   {"type": "polyline" | "bezier" | "bspline3", "closed": false, "points": [[x, y], ...]}
// Documented in docs/curve-format.md.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "core/diagnostics.h"

namespace relief::curves {

struct Point2 {
    double x = 0, y = 0;
};

/// An axis-aligned bounding box, grown point by point; empty until the first.
struct Bounds2 {
    double xmin = 1e300, ymin = 1e300, xmax = -1e300, ymax = -1e300;

    void add(Point2 p) {
        xmin = std::min(xmin, p.x), xmax = std::max(xmax, p.x);
        ymin = std::min(ymin, p.y), ymax = std::max(ymax, p.y);
    }
    void add(const Bounds2& b) {
        xmin = std::min(xmin, b.xmin), xmax = std::max(xmax, b.xmax);
        ymin = std::min(ymin, b.ymin), ymax = std::max(ymax, b.ymax);
    }
    bool empty() const { return xmin > xmax; }
    /// The diagonal's length (0 when empty): a curve's size, for relative tolerances.
    double diagonal() const { return empty() ? 0.0 : std::hypot(xmax - xmin, ymax - ymin); }
    /// Distance from p to the box (0 inside).
    double distance(Point2 p) const {
        const double dx = std::max({xmin - p.x, 0.0, p.x - xmax});
        const double dy = std::max({ymin - p.y, 0.0, p.y - ymax});
        return std::sqrt(dx * dx + dy * dy);
    }
};

struct CurveFile {
    std::string type = "polyline";
    bool closed = false;
    std::vector<Point2> points;
};

/// The largest coordinate a curve file may hold, and the highest degree of a
/// Bézier: what keeps the exact Hausdorff distance's polynomials finite and
/// its root finding short.
inline constexpr double kMaxCoordinate = 1e15;
inline constexpr size_t kMaxBezierDegree = 20;

/// What is wrong with a list of points, if anything.
enum class PointsFault { None, NotPoints, BeyondRange };

/// Reads `points`, a JSON array [[x, y], ...], into `out` as a curve file
/// holds them: two finite numbers each, within kMaxCoordinate. Otherwise the
/// fault, and `problem` naming the point by `name`, the array's name in the
/// file ("points" gives "points[3] = [1e+300, 0] is beyond the 1e+15 ...").
/// Shared with every file of curves relief reads (relief test's kept geometry).
PointsFault readPoints(const nlohmann::json& points, const std::string& name, std::vector<Point2>& out,
                       std::string& problem);

/// Reads and checks a curve file: valid JSON, a known type, finite numbers
/// within kMaxCoordinate, enough points for the type, a Bézier of at most
/// kMaxBezierDegree. Errors name the file (and the point's index).
std::optional<CurveFile> readCurveFile(const std::filesystem::path& path, Diagnostics& diags);

/// The file's JSON text (numbers in shortest round-trip form).
std::string curveFileJson(const CurveFile& curve);

}  // namespace relief::curves
