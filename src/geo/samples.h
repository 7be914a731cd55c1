#pragma once
// Reading georeferenced samples (part of stage 2, geo).
#include <cstdint>
#include <filesystem>
#include <vector>

#include "core/diagnostics.h"
#include "scene/scene_spec.h"
#include "core/source_loc.h"

namespace relief::geo {

/// One sample as read from the CSV: WGS84 degrees and metres, with its line.
struct GeoSample {
    double lonDeg;
    double latDeg;
    double elevM;
    SourceLoc loc;
};

/// Reads a CSV with a header naming the columns lon, lat and elev (any order,
/// further columns are an error). Reports every bad line (missing or
/// non-numeric fields, NaN or infinite values, |lat| > 90, |lon| > 180, the
/// same lon/lat twice with different elevations, with `earthElevations` an
/// elevation beyond the Earth's) with its line and column. Exact duplicates
/// are merged. Fewer than 4 distinct points, or all of them on one line, is
/// an error too. `displayPath` is the path used in messages. A file that is
/// not a regular file, or longer than `maxBytes` (0: any length), is an error
/// before anything is read.
std::vector<GeoSample> readSamples(const std::filesystem::path& path, const std::string& displayPath,
                                   Diagnostics& diags, bool earthElevations = true, std::uintmax_t maxBytes = 0);

/// The samples a scene's [samples] names.
inline std::vector<GeoSample> readSamples(const scene::SamplesSpec& spec, Diagnostics& diags,
                                          std::uintmax_t maxBytes = 0) {
    return readSamples(spec.path, spec.pathAsWritten, diags, spec.earthElevations, maxBytes);
}

}  // namespace relief::geo
