#pragma once
// Stage 2 for raster DEMs. Input: SamplesSpec naming any raster GDAL opens
// (GeoTIFF, SRTM .hgt, ESRI ASCII grid, VRT, ...), FrameSpec and NetSpec.
// Output: ControlNet, as for scattered samples. In the raster's own frame
// (crs_frame.h) nodes on the cells' centres are the cells, read; otherwise
// every net node (x, y in the scene's frame) goes to WGS84 latitude and
// longitude with GeographicLib, then to the raster's CRS with GDAL/PROJ, and is
// resampled there by GDAL's warper, which reads only the blocks the net covers. controlNet (geo.h)
// decides when a scene's samples take this path. In phases: the raster checked
// (raster_source.h), where the net goes (raster_footprint.h), the warp
// (raster_warp.h), the heights and nodata (raster_heights.h), composed in
// warped_net.cpp; lattices in lattice.cpp, drapes in image_on_grid.cpp.
#include <array>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "core/diagnostics.h"
#include "geo/normalize.h"
#include "scene/scene_spec.h"

namespace relief::geo {

class FolderNames;  // gdal_setup.h

/// Whether GDAL takes `path` for a raster (it may still fail to read it: a
/// truncated file). Text tables (GDAL's CSV and XYZ drivers) are not: a
/// `lon,lat,elev` CSV stays a CSV of scattered samples. `siblings`: the
/// names in its folder, when the caller has them.
bool isRasterDem(const std::filesystem::path& path, const FolderNames* siblings = nullptr);

/// What a scene made for a raster takes from it before any work: the title
/// its metadata gives it (TIFFTAG_DOCUMENTNAME, TITLE or DESCRIPTION, as
/// UTF-8, read as Latin-1 when it is not, cut to what a still can show; ""
/// when none), and band 1's range in metres (a
/// unit the band does not name taken as metres), approximate (GDAL's
/// overviews or a sample of its blocks); nullopt when the file is unreadable.
struct RasterSummary {
    std::string title;
    std::optional<std::array<double, 2>> range;  ///< min, max; none when every cell read is nodata
};
std::optional<RasterSummary> rasterSummary(const std::filesystem::path& path);

/// The raster resampled onto the net. The frame is the scene's (UTM: the zone
/// of the raster's centre unless given), or the raster's own CRS when the
/// scene names none (scene::FrameSpec says when); the net covers the raster's
/// footprint in the frame (the largest axis-aligned box inside it) unless
/// net.extent_m says otherwise, with the raster's own cell size on the ground
/// unless net.spacing_m or rows and cols say otherwise. Nodes without data
/// (nodata cells, outside the raster) are filled from their neighbours
/// (GDALFillNodata) or, with nodata = "error", reported. Vertical units in feet
/// are converted to metres; an unknown unit is taken as metres, with a warning.
std::optional<ControlNet> rasterNet(const scene::SamplesSpec& samples, const scene::FrameSpec& frame,
                                    const scene::NetSpec& net, Diagnostics& diags,
                                    const GridProgressFn& progress = {}, const NetBudget& budget = {});

/// An image draped on the surface ([texture] image): a georeferenced raster
/// in any CRS GDAL reads (RGB in bands 1-3, or one grey band) resampled
/// bilinearly onto `grid`'s nodes through the same chain as a DEM.
struct ImageOnGrid {
    std::string attribution;  ///< the credit the image's metadata carries (rasterCredit), if any
    int rows = 0, cols = 0;
    std::vector<std::uint8_t> rgb;      ///< 3 a node, in the grid's order (row 0 south), sRGB
    std::vector<std::uint8_t> covered;  ///< 1 where the image has data
    size_t coveredCount = 0;
};
std::optional<ImageOnGrid> imageOnGrid(const std::filesystem::path& path, const std::string& pathAsWritten,
                                       const GeoGrid& grid, Diagnostics& diags);

/// Scattered samples that are a raster in disguise: one sample on every node
/// of a regular lattice in some CRS (degrees, Web Mercator, a national grid),
/// as when a DEM was exported to lon,lat,elev. Such samples are resampled as
/// the raster they are (exact at the nodes, bilinear between) rather than
/// triangulated as scattered points.
struct SampleLattice {
    std::string crs;           ///< as GDAL reads it: "EPSG:4326", "EPSG:2193"
    int cols = 0, rows = 0;
    double xWest = 0, yNorth = 0;  ///< the north-west sample, in `crs`
    double dx = 0, dy = 0;     ///< spacing, in `crs` units
    std::vector<double> z;     ///< metres, row 0 north
};

/// The lattice the samples form in `crs`, or nullopt: every sample must sit
/// on a node (within 1 % of the spacing), one per node, every node taken.
std::optional<SampleLattice> findLattice(const std::vector<GeoSample>& samples, const std::string& crs);

/// The lattice as a raster (GDAL's MEM driver, bilinear) onto the net, as
/// rasterNet; the default extent is the samples' box.
std::optional<ControlNet> latticeNet(const SampleLattice& lattice, const scene::SamplesSpec& samples,
                                     const scene::FrameSpec& frame, const scene::NetSpec& net,
                                     Diagnostics& diags, const GridProgressFn& progress = {},
                                     const NetBudget& budget = {});

}  // namespace relief::geo
