#pragma once
// Stage 6 of 6: the report's furniture, drawn over the rendered still with
// Cairo and Pango (crisp text at any size, fonts from fontconfig: DejaVu
// Sans). Input: the still's pixels, the OverlaySpec and the facts the earlier
// stages know (OverlayFacts). Output: the same pixels with a title, credits,
// an elevation legend, a scale bar and a north arrow; or the still as a PDF
// or SVG page with them over it.
//
// Every string is set as text (pango_layout_set_text), never as markup: a
// title "<b>x</b> &amp;" prints as written.
//
// The front door of annotate/, the one header other folders include. Its
// rooms: facts.h (the numbers the overlays say, made when a scene is
// compiled, kept in a render plan), layout.h (where each box goes on the
// still), paint.h (the drawing with Cairo and Pango: drawOverlays, and the
// overlays on a document's page) and document.cpp (writeDocument).
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "annotate/facts.h"
#include "core/diagnostics.h"
#include "core/png_file.h"
#include "core/types.h"
#include "scene/scene_spec.h"

namespace relief::annotate {

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
    std::map<std::string, PixelBox> boxes;         ///< each drawn item's box as placed, pixels
    std::vector<std::string> onTerrain;  ///< items no free place could keep off the terrain
    /// The items with no free place, each with what was in its way ("the
    /// credits", "the still's edge"): left out, never drawn over another.
    struct LeftOut {
        std::string item, inTheWay;
    };
    std::vector<LeftOut> leftOut;
    ScaleBar scaleBar;
    double northDeg = 0;
    std::optional<PixelPoint> northCentre;  ///< the point the north arrow turns about, pixels
    std::vector<DrawnText> texts;  ///< every string, in the order drawn
    /// Every label asked for: where it went, or that no free place was left.
    struct Label {
        std::string text;
        int layer = 0;
        bool placed = false, leader = false;
        PixelBox box{};  ///< where it went, pixels; none when it was left out
        PixelPoint anchor{};     ///< the marker's top or the line's point it labels
        PixelPoint leaderEnd{};  ///< with a leader: where it meets the box
    };
    std::vector<Label> labels;
    /// [overlay] frame: the neat line, the ticks, and each annotation drawn
    /// (one left out where it would meet the one before it or leave the still).
    std::optional<MapFrame> frame;
    struct FrameAnnotation {
        std::string text;
        MapFrame::Side side = MapFrame::Side::Bottom;
        double tickPx = 0;
        PixelBox box{};
    };
    std::vector<FrameAnnotation> frameAnnotations;
};

/// Draws the overlays the spec asks for onto `image` (8-bit RGB or RGBA,
/// changed in place). False with the error at `at` (the still's file).
bool drawOverlays(PngImage8& image, const scene::OverlaySpec& spec, const OverlayFacts& facts, const SourceLoc& at,
                  Diagnostics& diags, OverlayRecord* record = nullptr);

/// One frame of a film as its overlays see it.
struct FrameOverlays {
    const scene::OverlaySpec* spec = nullptr;
    const OverlayFacts* facts = nullptr;
};

/// The places a film's furniture keeps in every frame, as overlay.place
/// holds them: the scene's own, and for each other item the place the
/// automatic choice gives it in most frames (the first frame's unless another
/// is chosen in more), kept only if it holds the item in every frame. Each
/// frame is laid out, not drawn. With every item at a named place, nothing
/// moves from frame to frame (the north arrow's centre included: a named
/// place holds it at every angle).
std::map<std::string, std::string> steadyPlaces(const std::vector<FrameOverlays>& frames, int widthPx, int heightPx);

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
/// invisible text layer over them. False with the error at `at` (the still's
/// file as the user knows it).
bool writeDocument(const PngImage8& still, const DocumentRequest& request, const SourceLoc& at, Diagnostics& diags,
                   OverlayRecord* record = nullptr);

}  // namespace relief::annotate
