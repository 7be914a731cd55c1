#pragma once
// Stage 2 of 6, geo's front door. Input: the scene's SamplesSpec, FrameSpec
// and NetSpec, and what [limits] allow. Output: ControlNet (normalize.h), a
// GeoGrid in the scene's frame (metres, x = east, y = north, z = up), ready
// for subdivision.
//
// What the samples file is decides how it becomes a net, by the first row of
// sampleSources() that recognises it:
//  - a folder is the raster tiles in it, mosaicked (raster_mosaic.h);
//  - a raster GDAL reads (GeoTIFF, SRTM .hgt, ASCII grid, VRT, ...) is
//    resampled onto the net by GDAL's warper (raster.h: rasterNet);
//  - anything else is scattered samples (a CSV of lon, lat, elev; samples.h),
//    resampled as a raster when they sit one per node of a regular lattice in
//    some CRS (raster.h: findLattice, latticeNet), else gridded by
//    triangulation or a search (normalize.h: normalize).
// A new kind of scattered data is a reader and its row (geo.cpp);
// docs/architecture.md, "An input format".
#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "core/diagnostics.h"
#include "core/source_loc.h"
#include "geo/normalize.h"
#include "geo/samples.h"
#include "scene/scene_spec.h"

namespace relief::geo {

/// What [limits] allow stage 2.
struct NetLimits {
    NetBudget nodes;     ///< the most nodes the net may have
    double memoryMB = 0; ///< the memory relief may use: a samples file over a quarter of it, or
                         ///< gridding that needs more, is refused before the work
    std::optional<SourceLoc> memoryKey;  ///< limits.max_memory_mb, when the scene gives it (else
                                         ///< memory errors name the samples file)
};

/// What stage 2 is doing, for the caller to show: a task ("gridding 5307
/// samples", "resampling the raster") and how far it is, 0..100, or -1 for a
/// line saying the task begins.
using NetProgressFn = std::function<void(const std::string& task, int percent)>;

/// The control net the scene's samples make: the first source of
/// sampleSources() that recognises samples.path reads it. Nullopt after an
/// error (every one found reported in `diags`; warnings as well).
std::optional<ControlNet> controlNet(const scene::SamplesSpec& samples, const scene::FrameSpec& frame,
                                     const scene::NetSpec& net, const NetLimits& limits, Diagnostics& diags,
                                     const NetProgressFn& progress = {});

/// What a source reads from: the scene's specs, the limits, and whom to tell
/// how far it is (may be empty). Valid for one call.
struct NetRequest {
    std::string_view source;  ///< the name of the source's row
    const scene::SamplesSpec& samples;
    const scene::FrameSpec& frame;
    const scene::NetSpec& net;
    const NetLimits& limits;
    const NetProgressFn& progress;
};

/// One kind of samples file. `recognises` looks at what the file is, not at
/// its name; `read` makes the net from it, reporting every problem.
struct SampleSource {
    std::string_view name;  ///< what relief takes such a file for, in messages: "a CSV of samples"
    bool (*recognises)(const std::filesystem::path& path);
    std::optional<ControlNet> (*read)(const NetRequest& request, Diagnostics& diags);
    bool raster = false;    ///< read as a raster (a raster DEM, a folder of them); else scattered samples
};

/// The sources in the order controlNet tries them; the last recognises any file.
std::span<const SampleSource> sampleSources();

/// The source that reads `path`: the first of sampleSources() that
/// recognises it. What controlNet reads a scene's samples with, and what
/// tells `relief render dem.tif` that a file named in place of a scene is
/// data: one table answers both.
const SampleSource& recognisedSource(const std::filesystem::path& path);

/// A reader of scattered samples: the samples of the file `spec` names, WGS84
/// lon, lat (degrees) and elevation (metres) with their locations, every bad
/// one reported; a file longer than `maxBytes` is an error before it is read.
using ScatteredReader = std::vector<GeoSample> (*)(const scene::SamplesSpec& spec, Diagnostics& diags,
                                                   std::uintmax_t maxBytes);

/// Scattered samples, read by `read`, made into the net: the keys only a
/// raster takes refused (the message says relief takes the file for
/// request.source), the file's size and the gridding's memory checked
/// against limits.memoryMB, then resampled as a lattice when they are one
/// (tried in samples.crs, else degrees, Web Mercator and the UTM zone of the
/// first sample), else gridded. The `read` of a scattered source's row.
std::optional<ControlNet> scatteredNet(const NetRequest& request, ScatteredReader read, Diagnostics& diags);

}  // namespace relief::geo
