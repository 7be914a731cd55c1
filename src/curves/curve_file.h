#pragma once
// Planar curve files (JSON), shared by `relief curve` and the Hausdorff tools:
//   {"type": "polyline" | "bezier" | "bspline3", "closed": false, "points": [[x, y], ...]}
// Documented in docs/curve-format.md.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "core/diagnostics.h"

namespace relief::curves {

struct Point2 {
    double x = 0, y = 0;
};

struct CurveFile {
    std::string type = "polyline";
    bool closed = false;
    std::vector<Point2> points;
};

/// Reads and checks a curve file: valid JSON, a known type, finite numbers,
/// enough points for the type. Errors name the file (and the point's index).
std::optional<CurveFile> readCurveFile(const std::filesystem::path& path, Diagnostics& diags);

/// The file's JSON text (numbers in shortest round-trip form).
std::string curveFileJson(const CurveFile& curve);

}  // namespace relief::curves
