#pragma once
// Inside geo: where a raster DEM's net goes. The cells the net covers by
// default (those with data), the frame chosen for them, the largest box of
// the frame inside their footprint, and the raster's cell on the ground, the
// net's default spacing.
#include <array>
#include <optional>

#include "core/diagnostics.h"
#include "core/types.h"
#include "geo/geo_grid.h"
#include "geo/raster_source.h"
#include "scene/scene_spec.h"

namespace relief::geo {

/// The box (in pixels) whose footprint is the net's default extent:
/// `footprint` when given (a lattice of samples: the nodes' centres), else
/// the centres of the cells with data when finding them costs little and the
/// scene gives no window (net.extent_m, net.extent_lonlat), else the centres
/// of every cell. Nullopt, after an error, when no cell has data.
std::optional<PixelBox> defaultPixelBox(const HeightBand& band, const RasterPlace& place,
                                        std::optional<PixelBox> footprint, const scene::NetSpec& net,
                                        const SourceLoc& fileLoc, Diagnostics& diags);

/// Whether defaultPixelBox is the box of the cells with data (a scan of them).
bool defaultIsDataBox(const HeightBand& band, const RasterPlace& place, std::optional<PixelBox> footprint,
                      const scene::NetSpec& net);

/// The box of the centres of all the raster's cells.
PixelBox allCellCentres(const RasterPlace& place);

/// The centres of the cells with data in `cells`, the raster's band or its
/// cells averaged (`scale` of the raster's cells each way, the first average
/// `offset` cells from its corner), in the raster's pixels. Nullopt, after an
/// error naming `band`, when none has data.
std::optional<PixelBox> centresWithData(GDALRasterBandH cells, double scaleX, double scaleY, double offsetX,
                                        double offsetY, const HeightBand& band, const SourceLoc& fileLoc,
                                        Diagnostics& diags);

/// The most a raster's own CRS may stray from true scale (|k - 1|) over the
/// raster to be the frame by default: twice UTM's worst within its zone.
inline constexpr double kOwnCrsScaleError = 0.002;

/// Where the net goes: the frame (the scene's, for the raster's footprint or
/// the scene's lon/lat window; the raster's own CRS when the scene asks, or
/// names none and `ownCrsByDefault`: scene::FrameSpec says when), the box
/// inside the footprint of `box` (0, 0, 1, 1 with a window: layoutNet
/// places the net there), and the raster's cell on the ground (metres), at
/// its centre or the window's.
struct NetExtent {
    Frame frame;
    FrameBox box;
    double cellM = 0;
};
std::optional<NetExtent> netExtent(const RasterPlace& place, const PixelBox& box, const scene::FrameSpec& frameSpec,
                                   const scene::NetSpec& net, bool ownCrsByDefault, const SourceLoc& fileLoc,
                                   Diagnostics& diags);

}  // namespace relief::geo
