#pragma once
// Stage 6 of 6: the report's furniture, drawn over the rendered still with
// Cairo and Pango (crisp text at any size, fonts from fontconfig: DejaVu
// Sans). Input: the still's pixels, the OverlaySpec and the facts the earlier
// stages know (OverlayFacts). Output: the same pixels with a title, credits,
// an elevation legend, a scale bar and a north arrow.
//
// Every string is set as text (pango_layout_set_text), never as markup: a
// title "<b>x</b> &amp;" prints as written.
#include <array>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "core/png_file.h"
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
/// marker (annotate/labels.h), or a graticule line's, where it leaves the terrain.
struct LabelFact {
    std::string text;       ///< as the file has it: drawn as text (drawnText), never markup
    double x = 0, y = 0;    ///< its anchor: the marker's top, the line's end (pixels, y down)
    double markerPx = 0;    ///< the marker's half width; 0: no marker
    double groundY = 0;     ///< the marker's foot: its box runs from y down to here
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

/// What the overlays say, computed from the scene, its placement and its
/// camera (overlayFacts, below): the numbers, not how to draw them.
struct OverlayFacts {
    std::string credits;  ///< the scene's, or the samples' attribution
    // The legend: the ramp as drawn (linear RGB), over true elevations.
    std::vector<LinearRgb> palette;
    double zMinM = 0, zMaxM = 0;
    std::string legendTitle = "Elevation (m)";  ///< slope colouring: "Slope (°)", its range 0-60
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
};

/// The facts of the overlays from the still's view: the legend (the ramp over
/// elevation, a blend's first layer; the slope palette over degrees; none for
/// a draped image), the scale, true north (`convergenceDeg`: grid north's
/// bearing from true north at the terrain's centre), and where the terrain
/// lies on the still. The credits are the caller's to say.
OverlayFacts overlayFacts(const scene::LookSpec& look, const emit::ScenePlacement& where, const emit::CameraView& view,
                          const scene::RenderSpec& render, double convergenceDeg);

/// A scale bar: a round length (1, 2 or 5 x 10^k m) near a fifth of the
/// still's width, its length in pixels and its label ("500 m", "2 km").
struct ScaleBar {
    double metres = 0;
    double pixels = 0;
    std::string label;
};
ScaleBar chooseScaleBar(double metresPerPixel, int widthPx);

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

/// A string drawn over the still: its box in the still's pixels (x, y the top left).
struct DrawnText {
    std::string text;
    double x = 0, y = 0, w = 0, h = 0;
    double sizePx = 0;
    bool bold = false;
};

/// What was drawn, for the sidecar.
struct OverlayRecord {
    std::vector<std::string> drawn;  ///< "title", "legend", ...
    std::map<std::string, std::string> placement;  ///< each drawn item's place: "top-left", ..., "right"
    std::vector<std::string> onTerrain;  ///< items no free place could keep off the terrain
    ScaleBar scaleBar;
    double northDeg = 0;
    std::vector<DrawnText> texts;  ///< every string, in the order drawn
    /// Every label asked for: where it went, or that no free place was left.
    struct Label {
        std::string text;
        int layer = 0;
        bool placed = false, leader = false;
        double x0 = 0, y0 = 0, x1 = 0, y1 = 0;  ///< its box, pixels
    };
    std::vector<Label> labels;
};

/// Draws the overlays the spec asks for onto `image` (8-bit RGB or RGBA,
/// changed in place). Returns "" or the error.
std::string drawOverlays(PngImage8& image, const scene::OverlaySpec& spec, const OverlayFacts& facts,
                         OverlayRecord* record = nullptr);

enum class DocumentFormat { Pdf, Svg };

/// The date a document says it was made: a fixed one, so that the same still
/// gives the same bytes (a PDF's /CreationDate is otherwise the clock's).
inline constexpr const char* kDocumentDate = "2000-01-01T00:00:00Z";

struct DocumentRequest {
    DocumentFormat format = DocumentFormat::Pdf;
    std::filesystem::path path;  ///< written there (the caller makes it atomic)
    double dpi = 300;            ///< the page: the still's pixels at this many an inch
    bool overlays = true;
    scene::OverlaySpec spec;
    OverlayFacts facts;
};

/// The still as a print-ready page: the ray-traced image embedded once, at
/// its own pixels, and the overlays over it as vector graphics and text, laid
/// out as on a PNG (the same Pango layouts, in the still's pixels, scaled to
/// points): a PDF's text is in embedded (subset) fonts, which pdftotext and a
/// reader's search find; an SVG's glyphs are outlines, with the strings as an
/// invisible text layer over them. Returns "" or the error.
std::string writeDocument(const PngImage8& still, const DocumentRequest& request, OverlayRecord* record = nullptr);

}  // namespace relief::annotate
