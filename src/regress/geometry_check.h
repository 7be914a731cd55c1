#pragma once
// Geometry checks of a `relief test` case: its surface's profiles and contour
// lines against the curves kept beside its reference images
// (<references>/geometry.json), by the exact Hausdorff distance within
// `tolerance_m`, and its peak loss within its own tolerance. A still can pass
// by its pixels and fail by its geometry: a change too small to see can still
// move the terrain by more than a report allows. Internal to regress/.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <toml++/toml.h>

#include "core/diagnostics.h"
#include "measure/compare_geometry.h"

namespace relief::regress {

struct GeometryChecks {
    std::vector<measure::ProfileLine> profiles;  ///< name: "LON,LAT:LON,LAT", as written
    std::vector<double> levels;
    double toleranceM = 0.01;
    std::optional<double> peakLossToleranceM;
    bool any() const { return !profiles.empty() || !levels.empty() || peakLossToleranceM; }
};

/// One check's outcome.
struct GeometryResult {
    std::string name;            ///< "profile 174.76,-36.87:174.77,-36.88", "contours at 120 m", "peak loss"
    bool kept = false;           ///< a kept curve to compare with
    double distanceM = 0;        ///< the Hausdorff distance (or the peak loss's change)
    double toleranceM = 0;
    bool pass = false;
    std::string where;           ///< where the distance is reached
    std::filesystem::path plot;  ///< an SVG of both curves and the witness, in the report
};

/// The file beside a case's references that keeps its curves.
inline constexpr const char* kGeometryFile = "geometry.json";

/// Where a manifest's key or table `r` begins in `file`.
SourceLoc locOf(const std::string& file, const toml::source_region& r);

/// Reads a case's `profile` (a string or strings "LON,LAT:LON,LAT"), `levels`,
/// `tolerance_m` and `peak_loss_tolerance_m`; errors at their keys.
GeometryChecks readGeometryChecks(const toml::table& t, const std::string& file, Diagnostics& diags);

/// The case's surface (the scene, with the case's size) measured and held to
/// the kept curves in `referenceDir`; the new curves written to `newCurves`
/// (what --update keeps) and a plot a check into `plotDir`. "" or why the
/// surface could not be measured, or why the kept curves cannot be read (a
/// geometry.json that is damaged, a FIFO, too big, or holds a coordinate
/// beyond curves::kMaxCoordinate: read as curve files are).
std::string checkGeometry(const std::filesystem::path& scene, const std::vector<std::pair<std::string, std::string>>& overrides,
                          const GeometryChecks& checks, const std::filesystem::path& referenceDir,
                          const std::filesystem::path& newCurves, const std::filesystem::path& plotDir,
                          const std::string& caseName, std::vector<GeometryResult>& results);

}  // namespace relief::regress
