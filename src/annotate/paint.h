#pragma once
// The overlays painted with Cairo and Pango, onto whatever a Cairo context
// draws on: the still's pixels (drawOverlays, in paint.cpp) or a document's
// page (writeDocument, document.cpp). For annotate/ only: other folders
// include annotate/overlay.h, which names no Cairo type.
#include <memory>

#include <cairo.h>
#include <pango/pangocairo.h>

#include "annotate/overlay.h"
#include "core/png_file.h"

namespace relief::annotate {

struct CairoDeleter {
    void operator()(cairo_surface_t* s) const { cairo_surface_destroy(s); }
    void operator()(cairo_t* c) const { cairo_destroy(c); }
    void operator()(PangoLayout* l) const { g_object_unref(l); }
    void operator()(PangoFontDescription* f) const { pango_font_description_free(f); }
};
/// A Cairo or Pango object, freed as its kind is.
template <class T>
using Owned = std::unique_ptr<T, CairoDeleter>;

/// What the drawing goes onto: the still's pixels, or a document's page (whose
/// device units are points, devicePerPixel of them a pixel of the still).
struct DrawingTarget {
    bool realText = false;  ///< the glyphs as text (a PDF's fonts), not as outlines
    double devicePerPixel = 1;
};

/// Cairo's ARGB32 (premultiplied, one native 32-bit word a pixel) holding the
/// still's pixels (8-bit RGB or RGBA); null if Cairo cannot make it.
Owned<cairo_surface_t> surfaceOf(const PngImage8& image);

/// Every overlay the spec asks for, drawn with `cr` over a still W x H pixels
/// (the context's user units are the still's pixels). Returns what was drawn.
OverlayRecord paintOverlays(cairo_t* cr, int widthPx, int heightPx, const scene::OverlaySpec& spec,
                            const OverlayFacts& facts, const DrawingTarget& target);

/// A warning at `at` for each item the record left out, naming what was in its way.
void warnLeftOut(const OverlayRecord& record, int widthPx, int heightPx, const SourceLoc& at, Diagnostics& diags);

}  // namespace relief::annotate
