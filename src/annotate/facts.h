#pragma once
// The overlays' facts: the numbers the overlays say (the legend's ramp and
// range, the scale, true north, where the terrain lies on the still, the
// labels and the layers' legend), made from the scene, its placement and its
// camera when the scene is compiled, and stored in a render plan (plan/) so
// that any process can finish the still. Nothing here draws.
#include <algorithm>
#include <array>
#include <optional>
#include <string>
#include <vector>

#include "core/types.h"
#include "emit/camera.h"
#include "scene/scene_spec.h"

namespace relief::annotate {

/// Where the terrain lies on a still, column by column: in each band of
/// `bandPx` pixels, from its highest point on the image to its lowest (a
/// terrain seen from above covers what lies between). Made from the terrain's
/// outline (the surface's and the block floor's nodes on a coarse lattice)
/// projected into the image; bands between two covered ones are filled in.
struct TerrainOnImage {
    double bandPx = 4;
    std::vector<double> top, bottom;  ///< per band, pixels (y down); top > bottom: nothing there
    static TerrainOnImage fromPoints(const std::vector<std::array<double, 2>>& points, int widthPx);
    bool covers(double x, double y) const;
};

/// A label the overlays place on the still: a [[layer]] point's, beside its
/// marker (placeLabels, annotate/layout.h), or a graticule line's, where it
/// leaves the terrain.
struct LabelFact {
    std::string text;       ///< as the file has it: drawn as text (drawnText), never markup
    PixelPoint anchor;      ///< the marker's top, the line's end
    double markerPx = 0;    ///< the marker's half width; 0: no marker
    double groundY = 0;     ///< the marker's foot: its box runs from the anchor down to here
    double sizePx = 13;
    int layer = 0;          ///< the [[layer]]'s number; 0: the graticule
};

/// A [[layer]]'s entry in the legend, its swatch drawn as the layer is.
struct LegendEntry {
    enum class Kind { Point, Line, Polygon };
    std::string text;
    Kind kind = Kind::Point;
    LinearRgb colour;
    std::optional<LinearRgb> fill;
    double fillOpacity = 0;
    double widthPx = 2;
    bool dashed = false;
};

/// [overlay] frame: a map's frame around a still from straight above, as
/// GMT's -Baf draws one: the neat line (the terrain's edge), ticks out of it
/// at every frame interval, and an annotation outside at every annotation
/// interval, on all four sides.
struct MapFrame {
    enum class Side { Bottom, Right, Top, Left };
    static bool alongX(Side side) { return side == Side::Bottom || side == Side::Top; }
    static const char* nameOf(Side side) {
        static const char* const kNames[] = {"bottom", "right", "top", "left"};
        return kNames[static_cast<int>(side)];
    }
    struct Tick {
        Side side = Side::Bottom;
        double px = 0;      ///< along its side: x for bottom and top, y for left and right
        std::string label;  ///< the annotation ("174°46′E", "1757000"); empty: a frame tick
    };
    PixelBox map{};  ///< the neat line, pixels
    std::vector<Tick> ticks;
};

/// A map frame's annotations' size and its ticks' length, in furniture units.
inline constexpr double kFrameTextSize = 1.5, kFrameTickUnits = 0.9;
/// No text is drawn smaller than this, pixels, whatever the still's size.
inline constexpr double kMinTextPx = 10;
/// DejaVu Sans's digits are this wide and its lines this high, in its size.
inline constexpr double kDigitWidthEm = 0.64, kLineHeightEm = 1.25;
/// A map frame's annotations' size on a still of furniture unit `unitPx`, pixels.
inline double frameTextPx(double unitPx) { return std::max(kFrameTextSize * unitPx, kMinTextPx); }

/// The pixels the furniture's sizes and margins scale with on a still W x H.
double furnitureUnitPx(const scene::OverlaySpec& spec, int widthPx, int heightPx);

/// What a framed map leaves of the still on each side for its annotations
/// (the widest `widestLabelChars` long) and, outside them, the furniture the
/// spec draws: the title above, the legend to the right, the scale bar and
/// credits below. Left, top, right, bottom, pixels.
std::array<double, 4> mapFrameInset(const scene::OverlaySpec& spec, int widthPx, int heightPx, size_t widestLabelChars);

/// The legend's title when it shows elevations in metres.
inline constexpr const char* kElevationTitle = "Elevation (m)";

/// What the overlays say, computed from the scene, its placement and its
/// camera (overlayFacts, below): the numbers, not how to draw them.
struct OverlayFacts {
    std::string credits;  ///< the scene's, or the samples' attribution
    /// The legend, scale bar, north arrow, labels and layers' legend mean
    /// something on the still: not on a panorama or a sphere (title and credits only).
    bool mapFurniture = true;
    // The legend: the ramp as drawn (linear RGB), over true elevations.
    std::vector<LinearRgb> palette;
    double zMinM = 0, zMaxM = 0;
    std::string legendTitle = kElevationTitle;  ///< slope colouring: "Slope (°)", its range 0-60
    std::string legendNote;                     ///< a line under the bar, e.g. where rock begins
    double exaggeration = 1;
    // The scale bar: ground metres one pixel spans, along the image's x, at
    // the centre of the view (exact everywhere for an orthographic view).
    double metresPerPixel = 0;
    bool perspective = true;
    // The north arrow: true north's direction in the image, degrees clockwise
    // from straight up, at the terrain's centre.
    double northDeg = 0;
    // Where the terrain is on the still, for the overlays to keep off it.
    TerrainOnImage terrain;
    // [[layer]]s and the graticule: the labels to place (in order), the legend's entries.
    std::vector<LabelFact> labels;
    std::vector<LegendEntry> layerLegend;
    std::optional<MapFrame> mapFrame;  ///< [overlay] frame
};

/// The facts of the overlays from the still's view: the legend (the ramp over
/// elevation, a blend's first layer; the slope palette over degrees; none for
/// a draped image), the scale, true north (`convergenceDeg`: grid north's
/// bearing from true north at the terrain's centre), and where the terrain
/// lies on the still. The credits are the caller's to say.
OverlayFacts overlayFacts(const scene::LookSpec& look, const emit::ScenePlacement& where, const emit::CameraView& view,
                          const scene::RenderSpec& render, double convergenceDeg);

/// A scale bar: the length the spec gives, or a round one (1, 2 or 5 x 10^k
/// m, or ft and mi for scale_bar_units = "imperial") near a fifth of the
/// still's width; its length in pixels and its label ("500 m", "2 km", "1 mi").
struct ScaleBar {
    double metres = 0;
    double pixels = 0;
    std::string label;
};
ScaleBar chooseScaleBar(double metresPerPixel, int widthPx, const scene::OverlaySpec& spec = {});

/// Round tick values for a legend over [zMin, zMax]: about five, at 1, 2 or
/// 5 x 10^k metres.
std::vector<double> legendTicks(double zMinM, double zMaxM);

/// True north's direction in a still of the view, degrees clockwise from
/// straight up, at the view's target. `convergenceDeg`: the bearing of grid
/// north (the frame's y axis) clockwise from true north there (GeographicLib's
/// meridian convergence; 0 in a local frame).
double northOnImageDeg(const emit::CameraView& view, double convergenceDeg, int widthPx, int heightPx);

/// Ground metres one pixel spans along the image's x at the view's target.
double metresPerPixelAtTarget(const emit::CameraView& view, double metresPerUnit, int widthPx);

/// Whether the overlays are drawn on a still `widthPx` wide.
bool overlaysWanted(const scene::OverlaySpec& spec, int widthPx);

}  // namespace relief::annotate
