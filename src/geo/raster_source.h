#pragma once
// Inside geo: a raster as GDAL holds it, and the first phases of reading one
// as a DEM (the file's header and its band of heights, the geotransform, the
// CRS). warped_net.cpp composes these with the later phases.
#include <array>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <utility>

#include <gdal.h>
#include <ogr_srs_api.h>

#include "core/diagnostics.h"
#include "geo/gdal_handles.h"
#include "geo/gdal_setup.h"
#include "geo/normalize.h"
#include "scene/scene_spec.h"

namespace relief::geo {

/// The transformations from WGS84 (lon, lat) to `srs` and back; either is null
/// when PROJ has none.
std::pair<Transform, Transform> wgs84Transforms(OGRSpatialReferenceH srs);

/// A raster a scene names, opened as GDAL reads it once relief has checked it
/// (gdal_setup.h); null with `problem` saying why when GDAL must not open it
/// (null with `problem` empty: GDAL cannot read it). `siblings`: the names in
/// its folder, when the caller has them (a folder of tiles).
Dataset openRaster(const std::filesystem::path& path, std::string& problem, const FolderNames* siblings = nullptr);
/// The same for any kind of dataset: `kind` is GDAL_OF_RASTER or GDAL_OF_VECTOR;
/// `openOptions` (a null-ended list of NAME=VALUE) go to the driver.
Dataset openChecked(const std::filesystem::path& path, unsigned kind, std::string& problem,
                    const FolderNames* siblings = nullptr, const char* const* openOptions = nullptr);

/// The credit a raster's metadata carries (GeoTIFF's copyright tag, or a
/// COPYRIGHT, LICENSE, LICENCE or ATTRIBUTION item), as UTF-8 (read as
/// Latin-1 when it is not), cut to what a still can show; "" when it has none.
std::string rasterCredit(GDALDatasetH ds);

/// A CRS and its transformations to and from WGS84 lon, lat.
struct RasterCrs {
    Srs srs;
    Transform toRaster, toWgs84;
};

/// Where a raster's cells lie on the Earth: its size, its geotransform (pixel
/// and line to its CRS) and the inverse, and its CRS.
struct RasterPlace {
    int width = 0, height = 0;
    std::array<double, 6> geo{}, inverse{};
    RasterCrs crs;

    double cells() const { return double(width) * double(height); }
    /// WGS84 lon, lat (degrees) to pixel and line; false (px, py untouched) when PROJ cannot.
    bool toPixel(double lonDeg, double latDeg, double& px, double& py) const;
    /// Pixel and line of a north-up raster to WGS84 lon, lat (degrees); false when PROJ cannot.
    bool toLonLat(double px, double py, double& lonDeg, double& latDeg) const;
    /// A raster in degrees: 360 degrees in its pixels, so that a point west of
    /// the antimeridian finds the cells east of it (lon 181 = -179); 0 otherwise.
    double wrapPixels() const;
};

/// The first phases of reading `src` as a DEM: its header within what relief
/// reads and what `budget` allows at its own cell size (unless `net` gives
/// the net's size), samples.band a band of heights, at least 2 x 2 cells, a
/// north-up geotransform, and its CRS (samples.crs, else its own) carried to
/// WGS84. Nullopt after an error.
std::optional<RasterPlace> placeOfDem(GDALDatasetH src, const scene::SamplesSpec& samples,
                                      const scene::NetSpec& net, const NetBudget& budget, Diagnostics& diags);

/// The band of heights and its nodata value.
struct HeightBand {
    GDALRasterBandH band = nullptr;
    int number = 1;
    bool hasNoData = false;
    double declaredNoData = 0;
    double noData = 0;  ///< declaredNoData, or NaN when none is declared (NaN cells are no data still)
};
HeightBand heightBand(GDALDatasetH src, int number);

}  // namespace relief::geo
