#pragma once
// Inside geo: GDAL's warper resampling a raster onto a net (a DEM's heights,
// a drape's colours). The net is a raster of its own to the warper, pixel
// centres on the nodes, row 0 north; the chain below carries its pixels to
// the source raster's.
#include <vector>

#include <gdalwarper.h>

#include "geo/geo_grid.h"
#include "geo/normalize.h"
#include "geo/raster_source.h"
#include "scene/scene_spec.h"

namespace relief::geo {

/// The chain from a net node to a raster pixel and back: frame <-> WGS84
/// (GeographicLib) <-> the raster's CRS (PROJ, through GDAL) <-> pixel and
/// line (the geotransform); the geotransform alone when the frame is the
/// raster's own CRS. Both must outlive the warp.
struct NetToRaster {
    const GeoGrid* net = nullptr;
    const RasterPlace* raster = nullptr;
    double wrapPixels = 0;  ///< raster->wrapPixels(), once
    bool inRasterCrs = false;  ///< the net's frame is the raster's own CRS (FrameKind::Raster)
    /// The warp's source pixels per pixel of `raster`: below 1 for a copy of
    /// the raster averaged to coarser cells (warped_net.cpp), else 1.
    double scaleX = 1, scaleY = 1;
};
NetToRaster netToRaster(const GeoGrid& net, const RasterPlace& raster);

/// An empty raster in memory (GDAL's MEM driver); null when there is no memory for it.
Dataset memRaster(int cols, int rows, int bands, GDALDataType type);

/// Warp options from `src`'s bands `srcBands` to `dst`'s bands 1, 2, ...
GDALWarpOptions* warpOptions(GDALDatasetH src, GDALDatasetH dst, const std::vector<int>& srcBands);

/// Runs the warp `wo` describes onto the whole net through `chain`,
/// approximated within maxErrorPixels of the source (GDAL's approximating
/// transformer, as gdalwarp uses by default), quietly; takes `wo` and frees it.
CPLErr warpOntoNet(GDALWarpOptions* wo, const NetToRaster& chain, double maxErrorPixels,
                   const GridProgressFn& progress);

/// GDAL's resampling for the scene's [samples] resample.
GDALResampleAlg gdalResampling(scene::Resample r);

}  // namespace relief::geo
