// Scattered samples made into the net (geo.h: scatteredNet): read
// within the memory budget, resampled as the raster they are when they form
// a lattice, else gridded.
#include <algorithm>
#include <cmath>
#include <mutex>

#include <fmt/format.h>

#include "core/input_file.h"
#include "core/text_escape.h"
#include "geo/geo.h"
#include "geo/raster.h"

namespace relief::geo {

namespace {

// Keys a raster takes and samples cannot: a scene that gives them expects a
// raster, so the file is not what the scene's author thinks it is.
bool refuseRasterKeys(const NetRequest& request, Diagnostics& diags) {
    const scene::SamplesSpec& samples = request.samples;
    for (const char* key : {"samples.band", "samples.resample", "samples.nodata", "samples.vertical_unit"})
        if (samples.locs.has(key))
            diags.error(samples.locs.at(key),
                        fmt::format("{} is only used with a raster DEM, and GDAL does not read {} as a "
                                    "raster (relief takes it for {}): remove it",
                                    key, printableExcerpt(samples.pathAsWritten, 200), request.source));
    return !diags.hasErrors();
}

SourceLoc memoryLoc(const NetRequest& request) {
    return request.limits.memoryKey ? *request.limits.memoryKey : SourceLoc{request.samples.pathAsWritten, 0, 0};
}

// The samples held in memory take several times the file's bytes: a file
// over a quarter of the memory budget is refused before it is read. The most
// bytes the reader may read, or nullopt after an error.
std::optional<std::uintmax_t> samplesFileLimit(const NetRequest& request, Diagnostics& diags) {
    const double budgetMB = request.limits.memoryMB;
    const auto maxBytes = static_cast<std::uintmax_t>(budgetMB * 1e6 / 4);
    std::error_code ec;
    const auto bytes = std::filesystem::file_size(request.samples.path, ec);
    if (ec || bytes <= maxBytes) return maxBytes;
    diags.error(memoryLoc(request),
                fmt::format("the samples file is {}, more than a quarter of limits.max_memory_mb = {:.0f} "
                            "(the samples in memory take several times the file): thin the samples, give them "
                            "as a raster, or raise the limit",
                            byteSize(bytes), budgetMB));
    return std::nullopt;
}

// A DEM exported as lon,lat,elev is a lattice in its own CRS. Tried: the
// scene's samples.crs, else degrees, Web Mercator and the UTM zone of the
// samples' first point.
std::vector<std::string> latticeCrsCandidates(const scene::SamplesSpec& spec, const std::vector<GeoSample>& samples) {
    if (!spec.crs.empty()) return {spec.crs};
    if (samples.empty()) return {};
    const auto& s0 = samples.front();
    const int zone = std::clamp(static_cast<int>(std::floor((s0.lonDeg + 180) / 6)) + 1, 1, 60);
    return {"EPSG:4326", "EPSG:3857", fmt::format("EPSG:{}", (s0.latDeg >= 0 ? 32600 : 32700) + zone)};
}

std::optional<ControlNet> resampledLattice(const NetRequest& request, const SampleLattice& lattice,
                                           Diagnostics& diags) {
    const std::string task = fmt::format("resampling the {} x {} lattice of samples in {}", lattice.cols,
                                         lattice.rows, lattice.crs);
    return latticeNet(
        lattice, request.samples, request.frame, request.net, diags,
        [&](double fraction) {
            if (request.progress) request.progress(task, static_cast<int>(100 * fraction));
        },
        request.limits.nodes);
}

// Gridded, telling each percent of the gridding (what takes long on real data).
std::optional<ControlNet> griddedSamples(const NetRequest& request, const std::vector<GeoSample>& samples,
                                         Diagnostics& diags) {
    const double budgetMB = request.limits.memoryMB;
    // The triangulation's memory; a fit triangulates nothing (its own need is checked by the net's size).
    const double griddingMB = samples.size() * kGriddingBytesPerSample / 1e6;
    const bool triangulated = request.net.gridding != scene::Gridding::Fit || request.net.linearBeforeFit;
    if (triangulated && griddingMB > budgetMB) {
        diags.error(memoryLoc(request),
                    fmt::format("gridding {} samples needs about {:.0f} MB of memory (2.2 kB each), more than "
                                "limits.max_memory_mb = {:.0f}: thin the samples, or give them as a raster",
                                samples.size(), griddingMB, budgetMB));
        return std::nullopt;
    }
    GridProgressFn gridding;
    int lastPercent = -1;
    std::mutex reporting;  // GDAL reports from its main thread; a guard costs nothing if not
    const std::string task = fmt::format("gridding {} samples", samples.size());
    if (request.progress) {
        request.progress(task, -1);  // before GDAL's triangulation, which tells nothing
        gridding = [&](double fraction) {
            const int percent = static_cast<int>(100 * fraction);
            const std::lock_guard<std::mutex> lock(reporting);
            if (percent == lastPercent) return;
            lastPercent = percent;
            request.progress(task, percent);
        };
    }
    return normalize(request.frame, request.net, request.samples.pathAsWritten, samples, diags, gridding,
                     request.limits.nodes);
}

}  // namespace

std::optional<ControlNet> scatteredNet(const NetRequest& request, ScatteredReader read, Diagnostics& diags) {
    if (!request.samples.tiles.empty()) {
        diags.error(request.samples.locs.at("samples.path"),
                    fmt::format("samples.path: a list is of raster tiles, and {} is not a raster GDAL reads (it "
                                "is taken for {}): give it alone",
                                request.samples.path.filename().string(), request.source));
        return std::nullopt;
    }
    if (!refuseRasterKeys(request, diags)) return std::nullopt;
    const auto maxBytes = samplesFileLimit(request, diags);
    if (!maxBytes) return std::nullopt;
    const auto samples = read(request.samples, diags, *maxBytes);
    if (diags.hasErrors()) return std::nullopt;
    // A lattice is resampled as the raster it is, unless the surface is to be fitted to its samples.
    for (const auto& crs : latticeCrsCandidates(request.samples, samples))
        if (const auto lattice = request.net.gridding == scene::Gridding::Fit ? std::nullopt : findLattice(samples, crs))
            return resampledLattice(request, *lattice, diags);
    if (!request.samples.crs.empty())
        diags.warning(request.samples.locs.at("samples.crs"),
                      fmt::format("the {} samples are not one per node of a regular lattice in {}: gridded as "
                                  "scattered samples",
                                  samples.size(), request.samples.crs));
    return griddedSamples(request, samples, diags);
}

}  // namespace relief::geo
