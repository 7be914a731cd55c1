// geo's front door: the table of sample sources, and the net made by the
// first that recognises the scene's samples file.
#include "geo/geo.h"

#include <fmt/format.h>

#include "core/text_escape.h"
#include "geo/raster.h"
#include "geo/raster_mosaic.h"

namespace relief::geo {

namespace {

std::optional<ControlNet> resampledRaster(const NetRequest& request, Diagnostics& diags) {
    return rasterNet(
        request.samples, request.frame, request.net, diags,
        [&](double fraction) {
            if (request.progress) request.progress("resampling the raster", static_cast<int>(100 * fraction));
        },
        request.limits.nodes);
}

bool anyFile(const std::filesystem::path&) { return true; }

bool isFolder(const std::filesystem::path& path) {
    std::error_code ec;
    return std::filesystem::is_directory(path, ec);
}

// A folder of tiles: the rasters in it, mosaicked as a list of them is.
std::optional<ControlNet> folderOfTiles(const NetRequest& request, Diagnostics& diags) {
    std::string problem;
    scene::SamplesSpec samples = request.samples;
    samples.tiles = rasterTilesIn(samples.path, problem);
    if (samples.tiles.empty()) {
        diags.error(samples.locs.at("samples.path"),
                    fmt::format("samples.path = \"{}\": {}; give a folder of raster tiles (GeoTIFF, SRTM .hgt, ...), "
                                "a raster, or a CSV of samples",
                                printableExcerpt(samples.pathAsWritten, 200), problem));
        return std::nullopt;
    }
    samples.path = samples.tiles.front();
    if (samples.tiles.size() == 1) samples.tiles.clear();
    return resampledRaster({request.source, samples, request.frame, request.net, request.limits, request.progress},
                           diags);
}

// In the order they are tried: a raster is told by what GDAL makes of the
// file, and what is not one is taken for scattered samples.
constexpr SampleSource kSampleSources[] = {
    {"a folder of raster tiles", isFolder, folderOfTiles, true},
    {"a raster DEM", [](const std::filesystem::path& path) { return isRasterDem(path); }, resampledRaster, true},
    {"a CSV of samples", anyFile,
     [](const NetRequest& request, Diagnostics& diags) { return scatteredNet(request, readSamples, diags); }, false},
};

}  // namespace

std::span<const SampleSource> sampleSources() { return kSampleSources; }

const SampleSource& recognisedSource(const std::filesystem::path& path) {
    for (const SampleSource& source : sampleSources())
        if (source.recognises(path)) return source;
    return sampleSources().back();  // it recognises any file
}

std::optional<ControlNet> controlNet(const scene::SamplesSpec& samples, const scene::FrameSpec& frame,
                                     const scene::NetSpec& net, const NetLimits& limits, Diagnostics& diags,
                                     const NetProgressFn& progress) {
    const SampleSource& source = recognisedSource(samples.path);
    return source.read({source.name, samples, frame, net, limits, progress}, diags);
}

}  // namespace relief::geo
