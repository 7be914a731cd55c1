#pragma once
// Part of stage 2 (its front door is geo/geo.h): scattered samples
// gridded onto the net. Input: FrameSpec, NetSpec and the samples (WGS84
// lon/lat/elev, geo/samples.h). Output: ControlNet, a GeoGrid (metres,
// x = east, y = north, z = up) ready for subdivision.
#include <array>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/diagnostics.h"
#include "core/types.h"
#include "geo/samples.h"
#include "geo/geo_grid.h"
#include "scene/scene_spec.h"

namespace relief::geo {

/// A point already in the frame (metres), with the CSV line it came from.
struct FramePoint {
    Vec3 p;
    SourceLoc loc;
};

/// The control net: the samples (or a raster's cells) on a GeoGrid, and how.
struct ControlNet : GeoGrid {
    size_t sampleCount = 0;        ///< samples read, or the raster's cells
    size_t filledNodata = 0;       ///< rasters: nodes without data, filled from their neighbours
    std::string raster;            ///< rasters: what was read and how, e.g.
                         ///< "122 x 174 cells, band 1, NZGD2000 / New Zealand Transverse Mercator 2000, bilinear"
                         ///< (or "..., the cells as they are": copiedCells)
    size_t filledOutsideHull = 0;  ///< nodes set by the nearest-sample fill (linear gridding)
    std::string attribution;       ///< rasters: the credit their metadata carries (rasterCredit), if any
    std::string spacingReason;     ///< why dx, dy are what they are (netSpacingReason)
    scene::Resample resample = scene::Resample::Bilinear;  ///< rasters: how the cells were resampled onto the net
    bool copiedCells = false;  ///< rasters: every node a cell's centre, its height the cell's (not resampled)
    double metresPerUnit = 1;  ///< rasters: of the band's heights (0.3048 for feet)
    bool verticalUnitAssumed = false;  ///< rasters: the band named no length, and metres were taken (a warning)
    /// Scattered samples: the highest of them, in the frame (the peak a surface
    /// should keep); unset for a raster or a lattice (their highest node is).
    std::optional<Vec3> highestSample;
    /// net.gridding = "fit": the samples in the frame, which the fit (fit/)
    /// makes the scheme's surface pass near; the net holds the linear gridding
    /// until then.
    std::shared_ptr<const std::vector<Vec3>> fitSamples;
};

/// A geographic point in `frame`'s metres: GeographicLib's UTMUPS (z the
/// height), LocalCartesian at the frame's origin (z the height above the
/// tangent plane) or the raster's CRS through PROJ (z the height), as
/// projectSamples. nullopt where the point cannot be converted.
std::optional<Vec3> forward(const Frame& frame, const GeoPoint& point);
/// A frame point (metres) on the WGS84 ellipsoid: the inverse of forward.
std::optional<GeoPoint> reverse(const Frame& frame, const Vec3& p);

/// The meridian convergence at frame point (x, y): the bearing of the frame's
/// y axis (grid north) clockwise from true north, degrees (GeographicLib's
/// gamma). 0 in a local frame, whose y axis is true north at its origin.
double gridConvergenceDeg(const Frame& frame, double x, double y);

/// The centre of the smallest arc of the circle of longitudes that holds all
/// of `lons` (degrees, -180..180): 180 for data from 179 to -179, not 0.
double centreLongitude(std::vector<double> lons);

/// Chooses the frame for these samples (UTM zone of their centre, unless the
/// scene forces one; or the local tangent plane at their centre), the centre
/// taken on the circle of longitudes (centreLongitude).
std::optional<Frame> chooseFrame(const scene::FrameSpec& spec,
                                 const std::vector<GeoSample>& samples, Diagnostics& diags);

/// Projects samples into the frame with GeographicLib. UTM: x = easting,
/// y = northing, z = elevation. Local: GeographicLib::LocalCartesian with its
/// origin at height 0, so z is the height above the tangent plane (it includes
/// the Earth's curvature, about d^2 / 2R: 0.8 m at 3 km from the origin).
std::vector<FramePoint> projectSamples(const Frame& frame, const std::vector<GeoSample>& samples,
                                       Diagnostics& diags);

/// The largest box of `frame` inside a lon/lat window (its edges are curves
/// in the frame); nullopt when the window does not fit in the frame.
std::optional<FrameBox> frameBoxInside(const Frame& frame, const LonLatBox& window);

/// GDAL's gridding of scattered samples (its Delaunay triangulation and search
/// structures) at its peak, per sample: 989 MB for 458,845 samples, measured
/// with /usr/bin/time on relief compile of holyroodpark.tif's cells as a CSV.
inline constexpr double kGriddingBytesPerSample = 2200;

/// The most nodes a net may have, checked as soon as its size is known and
/// before anything is allocated for it: what [limits] max_memory_mb leaves
/// for it at kNetBytesPerNode, and never more than 1e9.
inline constexpr double kNetBytesPerNode = 48;  ///< the net's nodes, the warp's and the gridding's copies
struct NetBudget {
    double maxNodes = 1e9;
    std::string why = "the 1e9 a net may have";  ///< for the message: "limits.max_memory_mb = 200 (48 bytes a node)"
    /// The still's width in pixels: a net the scene does not size (no
    /// spacing_m, rows or cols) over data finer than the still can show is
    /// laid at about one pixel, the extent's longer side over this (0: the
    /// data's own spacing).
    int stillWidthPx = 0;
    /// Where the eye comes nearest the ground (a flyover's path): a pixel's
    /// footprint there, given the extent's longer side in metres; the net is
    /// laid at about that instead (at the data's own spacing while that is
    /// less than twice as fine). Empty: the still's width over the extent.
    std::function<double(double extentM)> nearestPixelM;
    /// Whether the work on the net laid out (its frame, origin, spacing, rows
    /// and cols; no heights) fits: the refinement and the geometry [limits]
    /// allow, asked before any height is read or gridded; false after an
    /// error. Empty: it fits.
    std::function<bool(const GeoGrid& laidOut, Diagnostics& diags)> fits;
    /// Told the net once it is laid out and described (its size, spacing and
    /// why; no heights), before a height is read: false stops there, with no
    /// error (relief info's estimate of a net too large to read). Empty: read on.
    std::function<bool(const ControlNet& laidOut)> beforeReading;
};

/// Why a net has the spacing it has, for the header, `relief info` and
/// `relief init`: "net.spacing_m", "the data's own spacing", or about one
/// pixel of the still.
std::string netSpacingReason(const scene::NetSpec& spec, const GeoGrid& net, double dataSpacingM, const NetBudget& budget);

/// Lays a net (origin, spacing, rows and cols; no heights) over net.extent_m,
/// else the box inside net.extent_lonlat, else `dataBox` (in net.frame,
/// which must be set): rows x cols spanning
/// it, or the largest net of net.spacing_m inside it, centred (or of
/// `defaultSpacingM` when the scene gives neither, or coarser to suit the
/// still: NetBudget::stillWidthPx; 0: rows and cols). False, with an error at
/// [net], for fewer than 4 x 4 nodes, more than `budget` or work that
/// NetBudget::fits refuses.
bool layoutNet(const scene::NetSpec& spec, FrameBox dataBox, double defaultSpacingM, GeoGrid& net, Diagnostics& diags,
               const NetBudget& budget = {});

/// How far the gridding is, 0..1 (GDAL reports it per row of the net).
using GridProgressFn = std::function<void(double fraction)>;

/// Grids the projected samples onto the rectangular net with GDAL's
/// GDALGridCreate. Linear (Delaunay) interpolation leaves nodes outside the
/// samples' convex hull empty; those are filled with the nearest sample.
/// `samplesName` names the samples in messages.
std::optional<ControlNet> gridSamples(const scene::NetSpec& spec, const std::string& samplesName,
                                      const Frame& frame, const std::vector<FramePoint>& points,
                                      Diagnostics& diags, const GridProgressFn& progress = {},
                                      const NetBudget& budget = {});

/// Whole stage: chooseFrame, projectSamples, gridSamples.
std::optional<ControlNet> normalize(const scene::FrameSpec& frame, const scene::NetSpec& net,
                                    const std::string& samplesName,
                                    const std::vector<GeoSample>& samples, Diagnostics& diags,
                                    const GridProgressFn& progress = {}, const NetBudget& budget = {});

/// A net (or the refined surface) as CSV `x,y,z` (metres in the frame, row 0 south first).
std::string netToCsv(const GeoGrid& net);
/// The net as an ESRI ASCII grid (cell-centre registration, rows north first).
/// Needs dx == dy.
std::string netToAsciiGrid(const GeoGrid& net);

}  // namespace relief::geo
