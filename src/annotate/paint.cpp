#include "annotate/paint.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include <fmt/format.h>

#include "annotate/layout.h"
#include "core/number_format.h"
#include "core/text_escape.h"

namespace relief::annotate {

namespace {

// The sRGB transfer function (IEC 61966-2-1): the still's PNG is sRGB, the
// ramp's colours are linear.
double linearToSrgb(double c) {
    c = std::clamp(c, 0.0, 1.0);
    return c <= 0.0031308 ? 12.92 * c : 1.055 * std::pow(c, 1 / 2.4) - 0.055;
}

// Text in one place: dark, with a pale halo so it reads over any terrain.
// anchorX: 0 left, 0.5 centre, 1 right of (x, y); y is the top.
class Painter {
public:
    /// realText: the glyphs' fill as text (a PDF's fonts, which pdftotext and
    /// a reader's search find), not as outlines; the halo is an outline either
    /// way. Every string drawn is recorded in `drawn`.
    Painter(cairo_t* cr, double unit, const DrawingTarget& target, std::vector<DrawnText>& drawn)
        : cr_(cr), unit_(unit), realText_(target.realText), devicePerPixel_(target.devicePerPixel), drawn_(drawn) {}

    // Returns the text's width and height, in pixels. With maxWidth, the text
    // wraps at words onto at most maxLines lines, the last cut with an
    // ellipsis: an overlong string cannot cover the still. anchorY: 0 puts
    // the top at y, 1 the bottom.
    std::pair<double, double> text(const std::string& s, double x, double y, double sizeUnits, bool bold,
                                   double anchorX = 0, double maxWidth = 0, int maxLines = 1, double anchorY = 0) {
        return laidOut(s, x, y, sizeUnits, bold, anchorX, maxWidth, maxLines, anchorY, true);
    }
    /// The size text() would give, drawing nothing.
    std::pair<double, double> measure(const std::string& s, double sizeUnits, bool bold, double maxWidth = 0,
                                      int maxLines = 1, double anchorX = 0) {
        // A wrapped layout reports its whole width: a text that fits on one
        // line is measured as the line it is.
        const auto natural = laidOut(s, 0, 0, sizeUnits, bold, anchorX, 0, 1, 0, false);
        if (maxWidth <= 0 || natural.first <= maxWidth) return natural;
        return laidOut(s, 0, 0, sizeUnits, bold, anchorX, maxWidth, maxLines, 0, false);
    }

private:
    std::pair<double, double> laidOut(const std::string& given, double x, double y, double sizeUnits, bool bold,
                                      double anchorX, double maxWidth, int maxLines, double anchorY, bool draw) {
        // Pango takes UTF-8 only (it prints a warning and drops the rest); a plan's text may not be.
        const std::string s = utf8Replaced(given);
        Owned<PangoLayout> layout(pango_cairo_create_layout(cr_));
        Owned<PangoFontDescription> font(pango_font_description_from_string(bold ? "DejaVu Sans Bold" : "DejaVu Sans"));
        // Never below 10 px: a label a reader cannot read is no label.
        pango_font_description_set_absolute_size(font.get(), std::max(sizeUnits * unit_, kMinTextPx) * PANGO_SCALE);
        pango_layout_set_font_description(layout.get(), font.get());
        if (maxWidth > 0) {
            pango_layout_set_width(layout.get(), static_cast<int>(maxWidth * PANGO_SCALE));
            pango_layout_set_wrap(layout.get(), PANGO_WRAP_WORD_CHAR);
            pango_layout_set_height(layout.get(), -maxLines);
            pango_layout_set_ellipsize(layout.get(), PANGO_ELLIPSIZE_END);
            pango_layout_set_alignment(layout.get(), anchorX >= 1    ? PANGO_ALIGN_RIGHT
                                                     : anchorX == 0.5 ? PANGO_ALIGN_CENTER
                                                                      : PANGO_ALIGN_LEFT);
        }
        pango_layout_set_single_paragraph_mode(layout.get(), TRUE);  // line breaks in a string are spaces
        pango_layout_set_text(layout.get(), s.c_str(), static_cast<int>(s.size()));  // text, never markup
        PangoRectangle box;  // the lines as laid out (a right-aligned line starts right of 0)
        pango_layout_get_pixel_extents(layout.get(), nullptr, &box);
        const double w = box.width, h = box.height;
        if (!draw) return {w, h};
        const double left = x - anchorX * w, top = y - anchorY * h;
        cairo_move_to(cr_, left - box.x, top - box.y);
        pango_cairo_layout_path(cr_, layout.get());
        cairo_set_line_join(cr_, CAIRO_LINE_JOIN_ROUND);
        cairo_set_line_width(cr_, std::max(1.0, 0.35 * sizeUnits * unit_ / 3));
        cairo_set_source_rgba(cr_, 1, 1, 1, 0.85);
        if (realText_) {
            cairo_stroke(cr_);
            cairo_set_source_rgb(cr_, 0.08, 0.08, 0.08);
            cairo_move_to(cr_, left - box.x, top - box.y);
            pango_cairo_show_layout(cr_, layout.get());
            // The text leaves its start as the current point: the next path
            // (a swatch's arc) would begin with a line from it.
            cairo_new_path(cr_);
        } else {
            cairo_stroke_preserve(cr_);
            cairo_set_source_rgb(cr_, 0.08, 0.08, 0.08);
            cairo_fill(cr_);
        }
        double px = left, py = top;  // the box in the still's pixels, wherever the drawing was moved
        cairo_user_to_device(cr_, &px, &py);
        drawn_.push_back({s, px / devicePerPixel_, py / devicePerPixel_, w, h, std::max(sizeUnits * unit_, kMinTextPx), bold});
        return {w, h};
    }

    cairo_t* cr_;
    double unit_;
    bool realText_;
    double devicePerPixel_;
    std::vector<DrawnText>& drawn_;
};

// The drawn surface back into the still's pixels, unpremultiplied.
void copyBack(cairo_surface_t* surface, PngImage8& image) {
    const int W = image.width, H = image.height, n = image.channels;
    cairo_surface_flush(surface);
    const unsigned char* data = cairo_image_surface_get_data(surface);
    const int stride = cairo_image_surface_get_stride(surface);
    for (int yy = 0; yy < H; ++yy)
        for (int x = 0; x < W; ++x) {
            const std::uint32_t v = reinterpret_cast<const std::uint32_t*>(data + static_cast<size_t>(yy) * stride)[x];
            const unsigned a = v >> 24;
            const auto un = [&](unsigned pc) { return a ? std::min(255u, (pc * 255 + a / 2) / a) : 0u; };
            std::uint8_t* p = &image.pixels[(static_cast<size_t>(yy) * W + x) * n];
            p[0] = static_cast<std::uint8_t>(un((v >> 16) & 255));
            p[1] = static_cast<std::uint8_t>(un((v >> 8) & 255));
            p[2] = static_cast<std::uint8_t>(un(v & 255));
            if (n == 4) p[3] = static_cast<std::uint8_t>(a);
        }
}

// One still's overlays as they are drawn: the Cairo context over its pixels,
// the unit the sizes scale with, and where each overlay went. Each overlay has
// its box where it goes by default, then is moved (cairo_translate) to the
// place the placer chooses.
class OverlayDrawing {
public:
    OverlayDrawing(cairo_t* c, int W, int H, const scene::OverlaySpec& spec, const OverlayFacts& facts,
                   const DrawingTarget& target)
        : c(c), W(W), H(H), u(furnitureUnitPx(spec, W, H)), spec(spec),
          paint(c, u, target, record.texts), placer(W, H, u, facts.terrain) {}

    // [overlay] frame, as GMT's plain frame: the neat line, ticks out of it
    // (a frame tick half an annotation's), the annotations beyond them, each
    // left out where it would overlap the one before it on its side or leave
    // the still. The furniture keeps off each side's annotations.
    void mapFrame(const MapFrame& frame) {
        using Side = MapFrame::Side;
        const PixelBox& m = frame.map;
        const double tick = kFrameTickUnits * u, gap = 0.5 * u;
        cairo_save(c);
        cairo_set_source_rgb(c, 0.08, 0.08, 0.08);
        cairo_set_line_width(c, 0.2 * u);
        cairo_rectangle(c, m.x0, m.y0, m.w(), m.h());
        cairo_stroke(c);
        cairo_set_line_width(c, 0.12 * u);
        // Each side's foot of a tick at `px` along it, and the way out of the map.
        const auto foot = [&m](Side side, double px) -> std::array<double, 4> {
            switch (side) {
                case Side::Bottom: return {px, m.y1, 0, 1};
                case Side::Top: return {px, m.y0, 0, -1};
                case Side::Left: return {m.x0, px, -1, 0};
                default: return {m.x1, px, 1, 0};
            }
        };
        for (const MapFrame::Tick& t : frame.ticks) {
            const auto [x, y, ox, oy] = foot(t.side, t.px);
            const double len = t.label.empty() ? tick / 2 : tick;
            cairo_move_to(c, x, y);
            cairo_line_to(c, x + ox * len, y + oy * len);
            cairo_stroke(c);
        }
        cairo_restore(c);
        std::map<Side, PixelBox> bands;  // each side's annotations
        std::map<Side, PixelBox> last;
        for (const MapFrame::Tick& t : frame.ticks) {
            if (t.label.empty()) continue;
            const auto [x, y, ox, oy] = foot(t.side, t.px);
            const double ax = x + ox * (tick + gap), ay = y + oy * (tick + gap);
            const double anchorX = ox < 0 ? 1 : ox > 0 ? 0 : 0.5, anchorY = oy < 0 ? 1 : oy > 0 ? 0 : 0.5;
            const auto [w, h] = paint.measure(t.label, kFrameTextSize, false);
            const PixelBox box{ax - anchorX * w, ay - anchorY * h, ax - anchorX * w + w, ay - anchorY * h + h};
            const bool inside = box.x0 >= 0 && box.y0 >= 0 && box.x1 <= W && box.y1 <= H;
            const auto before = last.find(t.side);
            if (!inside || (before != last.end() && before->second.meets(box, 0.5 * u))) continue;
            paint.text(t.label, ax, ay, kFrameTextSize, false, anchorX, 0, 1, anchorY);
            record.frameAnnotations.push_back({t.label, t.side, t.px, box});
            last[t.side] = box;
            auto [band, fresh] = bands.try_emplace(t.side, box);
            if (!fresh)
                band->second = {std::min(band->second.x0, box.x0), std::min(band->second.y0, box.y0),
                                std::max(band->second.x1, box.x1), std::max(band->second.y1, box.y1)};
        }
        record.drawn.push_back("frame");
        record.boxes["frame"] = m;
        record.frame = frame;
        for (const auto& [side, band] : bands) placer.reserve("frame", band);
    }

    // Title and subtitle, top left.
    void title() {
        double w = 0, h = 0;
        if (!spec.title.empty()) {
            const auto [tw, th] = paint.measure(spec.title, 3.6, true, 0.62 * W, 2);
            w = std::max(w, tw), h += th;
        }
        if (!spec.subtitle.empty()) {
            const auto [sw, sh] = paint.measure(spec.subtitle, 2.2, false, 0.62 * W, 2);
            w = std::max(w, sw), h += sh + 0.3 * u;
        }
        const PixelBox box{2.5 * u, 2.2 * u, 2.5 * u + w, 2.2 * u + h};
        const auto choice = placeItem("title", box, around(box, "top-left", {"top-right"}));  // a title stays at the top
        if (!choice) return;
        cairo_save(c);
        cairo_translate(c, choice->dx, choice->dy);
        // Right-aligned in a right-hand place, centred in the middle of an edge.
        const double anchor = alignmentAt(choice->where), x = box.x0 + anchor * box.w();
        double y = box.y0;
        if (!spec.title.empty()) {
            y += paint.text(spec.title, x, y, 3.6, true, anchor, 0.62 * W, 2).second;
            placed("title", *choice);
        }
        if (!spec.subtitle.empty()) {
            paint.text(spec.subtitle, x, y + 0.3 * u, 2.2, false, anchor, 0.62 * W, 2);
            placed("subtitle", *choice);
        }
        cairo_restore(c);
    }

    // North arrow, top right: an arrow pointing where true north lies, an "N" beyond its tip.
    void northArrow(const OverlayFacts& facts) {
        const double cx = W - 6 * u, cy = 7.5 * u, len = 3.6 * u;
        const double a = facts.northDeg * std::numbers::pi / 180;
        const PixelPoint nTop{cx + std::sin(a) * 1.75 * len, cy - std::cos(a) * 1.75 * len - 1.3 * u};
        const auto [nw, nh] = paint.measure("N", 2.4, true);
        // The arrow turned any way stays within `reach` of its centre (its tip
        // at len, its stroke's half width beyond); the box holds the "N" whole too.
        const double reach = len + 0.6 * u;  // the tip's mitre reaches 0.58 units past the point
        const PixelBox box{std::min(cx - reach, nTop.x - nw / 2), std::min(cy - reach, nTop.y),
                           std::max(cx + reach, nTop.x + nw / 2), std::max(cy + reach, nTop.y + nh)};
        // At a named place the arrow's centre stays where the arrow and its "N" fit at any angle:
        // a film's arrow turns in place instead of sliding as its box changes shape.
        const double turning = 1.75 * len + 1.3 * u + std::hypot(nw / 2, nh);
        const PixelBox anyAngle{cx - turning, cy - turning, cx + turning, cy + turning};
        const auto choice = placeItem("north_arrow", box,
                                      places(box, {"top-right", "top-left", "bottom-right", "bottom-left"}), &anyAngle);
        if (!choice) return;
        cairo_save(c);
        cairo_translate(c, choice->dx, choice->dy);
        cairo_save(c);
        cairo_translate(c, cx, cy);
        cairo_rotate(c, a);
        cairo_move_to(c, 0, -len);
        cairo_line_to(c, 0.55 * len, 0.75 * len);
        cairo_line_to(c, 0, 0.35 * len);
        cairo_line_to(c, -0.55 * len, 0.75 * len);
        cairo_close_path(c);
        cairo_set_line_width(c, 0.35 * u);
        cairo_set_source_rgba(c, 1, 1, 1, 0.85);
        cairo_stroke_preserve(c);
        cairo_set_source_rgb(c, 0.08, 0.08, 0.08);
        cairo_fill(c);
        cairo_restore(c);
        paint.text("N", nTop.x, nTop.y, 2.4, true, 0.5);
        cairo_restore(c);
        placed("north_arrow", *choice);
        record.northDeg = facts.northDeg;
        record.northCentre = PixelPoint{cx + choice->dx, cy + choice->dy};
    }

    // Credits, bottom right: whose data (CC BY and the OGL ask for it).
    void credits(const OverlayFacts& facts) {
        const auto [w, h] = paint.measure(facts.credits, 1.4, false, 0.55 * W, 4, 1);
        const PixelBox box{W - 2 * u - w, H - 1.2 * u - h, W - 2 * u, H - 1.2 * u};
        const auto choice = placeItem("credits", box, around(box, "bottom-right", {"bottom-left"}));
        if (!choice) return;
        // Left-aligned in a left-hand place, centred in the middle of an edge.
        const double anchor = alignmentAt(choice->where);
        paint.text(facts.credits, box.x0 + anchor * box.w() + choice->dx, box.y1 + choice->dy, 1.4, false, anchor,
                   0.55 * W, 4, 1);
        placed("credits", *choice);
    }

    // Scale bar, bottom left: four alternating segments, its length above
    // them, and under them in a perspective view where it holds.
    void scaleBar(const OverlayFacts& facts) {
        const ScaleBar bar = chooseScaleBar(facts.metresPerPixel, W, spec);
        if (!(bar.pixels > 0)) return;
        const char* const kNote = "at the centre of the view";
        const double x0 = 3 * u, y0 = H - 7 * u, h = 0.9 * u, gap = 0.4 * u;
        const auto [zeroW, figureH] = paint.measure("0", 1.7, false);
        const double labelW = paint.measure(bar.label, 1.7, false).first;
        const auto [noteW, noteH] = facts.perspective ? paint.measure(kNote, 1.4, false) : std::pair{0.0, 0.0};
        const PixelBox box{std::min(x0 - std::max(zeroW / 2, 0.3 * u), x0 + bar.pixels - labelW / 2), y0 - gap - figureH,
                           std::max(x0 + bar.pixels + labelW / 2, x0 + noteW), y0 + h + gap + noteH};
        const auto choice =
            placeItem("scale_bar", box, places(box, {"bottom-left", "bottom-right", "top-left", "top-right"}));
        if (!choice) return;
        cairo_save(c);
        cairo_translate(c, choice->dx, choice->dy);
        cairo_set_line_width(c, 0.15 * u);
        for (int i = 0; i < 4; ++i) {
            cairo_rectangle(c, x0 + i * bar.pixels / 4, y0, bar.pixels / 4, h);
            if (i % 2 == 0)
                cairo_set_source_rgb(c, 0.08, 0.08, 0.08);
            else
                cairo_set_source_rgb(c, 1, 1, 1);
            cairo_fill_preserve(c);
            cairo_set_source_rgb(c, 0.08, 0.08, 0.08);
            cairo_stroke(c);
        }
        paint.text("0", x0, y0 - gap, 1.7, false, 0.5, 0, 1, 1);
        paint.text(bar.label, x0 + bar.pixels, y0 - gap, 1.7, false, 0.5, 0, 1, 1);
        if (facts.perspective) paint.text(kNote, x0, y0 + h + gap, 1.4, false, 0);
        cairo_restore(c);
        placed("scale_bar", *choice);
        record.scaleBar = bar;
    }

    // Elevation legend, right: the ramp as a bar, ticks in true metres (or feet).
    void legend(const OverlayFacts& facts) {
        const double barW = 2.0 * u, barH = 0.38 * H, x0 = W - 13 * u, y0 = 17 * u;
        const bool exaggerated = std::abs(facts.exaggeration - 1) > 1e-9;
        const bool feet = spec.legendFeet && facts.legendTitle == kElevationTitle;
        const std::string title = !spec.legendTitle.empty() ? spec.legendTitle
                                  : feet                    ? std::string("Elevation (ft)")
                                                            : facts.legendTitle;
        const double unitM = feet ? scene::kFootM : 1;
        const std::vector<double> ticks = legendTicks(facts.zMinM / unitM, facts.zMaxM / unitM);
        const std::string vertical = fmt::format("vertical \u00d7{}", formatShortest(facts.exaggeration));
        // Every string in the box, measured: at small sizes (no text under 10 px) they outgrow the units.
        const double titleW = paint.measure(title, 1.9, true).first;
        const double noteW = facts.legendNote.empty() ? 0 : paint.measure(facts.legendNote, 1.6, false).first;
        const double verticalW = exaggerated ? paint.measure(vertical, 1.6, false).first : 0;
        double tickW = 0;
        for (double v : ticks) tickW = std::max(tickW, paint.measure(formatShortest(v), 1.7, false).first);
        const double bottom =
            y0 + barH + 1.2 * u + (exaggerated ? 2.4 * u : 0) + (facts.legendNote.empty() ? 0 : 2.4 * u);
        const PixelBox box{std::min({x0 - 1.5 * u, x0 + barW - titleW / 2, x0 + barW - verticalW / 2, W - 2 * u - noteW}),
                           y0 - 3.6 * u,
                           std::max({W - 2 * u, x0 + barW + titleW / 2, x0 + barW + verticalW / 2,
                                     x0 + barW + 1.2 * u + tickW}),
                           bottom};
        // Down the right edge from below the north arrow, then down the left edge.
        FurniturePlacer::Candidates candidates;
        for (const bool left : {false, true})
            for (double top = box.y0; top + box.h() <= H - 2 * u || top == box.y0; top += 2 * u) {
                const double x = left ? 2 * u : box.x0;
                candidates.push_back({{x, top, x + box.w(), top + box.h()}, left ? "left" : "right"});
            }
        // Put at "right" or "left" by name: down that edge as above, the first free place there.
        const auto named = spec.places.find("legend");
        const bool column = named != spec.places.end() && (named->second == "right" || named->second == "left");
        std::erase_if(candidates, [&](const auto& c) { return column && c.second != named->second; });
        const auto choice =
            column ? leftOutIfNone("legend", placer.place("legend", box, candidates)) : placeItem("legend", box, candidates);
        if (!choice) return;
        cairo_save(c);
        cairo_translate(c, choice->dx, choice->dy);
        paint.text(title, x0 + barW, y0 - 3.4 * u, 1.9, true, 0.5);
        const int steps = static_cast<int>(std::ceil(barH));
        for (int i = 0; i < steps; ++i) {  // top: the highest
            const double t = 1.0 - (i + 0.5) / steps;
            const auto& col = facts.palette[std::min(facts.palette.size() - 1,
                                                     static_cast<size_t>(std::lround(t * (facts.palette.size() - 1))))];
            cairo_rectangle(c, x0, y0 + i * barH / steps, barW, barH / steps + 0.6);
            cairo_set_source_rgb(c, linearToSrgb(col.r), linearToSrgb(col.g), linearToSrgb(col.b));
            cairo_fill(c);
        }
        cairo_rectangle(c, x0, y0, barW, barH);
        cairo_set_line_width(c, 0.15 * u);
        cairo_set_source_rgb(c, 0.08, 0.08, 0.08);
        cairo_stroke(c);
        const double span = facts.zMaxM > facts.zMinM ? facts.zMaxM - facts.zMinM : 1;
        for (double v : ticks) {
            const double ty = y0 + barH * (1 - (v * unitM - facts.zMinM) / span);
            cairo_move_to(c, x0 + barW, ty);
            cairo_line_to(c, x0 + barW + 0.8 * u, ty);
            cairo_set_source_rgb(c, 0.08, 0.08, 0.08);
            cairo_stroke(c);
            paint.text(formatShortest(v), x0 + barW + 1.2 * u, ty - 1.0 * u, 1.7, false);
        }
        double noteY = y0 + barH + 1.2 * u;
        if (exaggerated) {
            paint.text(vertical, x0 + barW, noteY, 1.6, false, 0.5);
            noteY += 2.4 * u;
        }
        if (!facts.legendNote.empty()) paint.text(facts.legendNote, W - 2 * u, noteY, 1.6, false, 1);
        cairo_restore(c);
        placed("legend", *choice);
    }

    // The [[layer]]s' legend: a swatch and a line of text an entry, on a pale card.
    void layerLegend(const OverlayFacts& facts) {
        const double size = 1.6, rowH = 2.6 * u, swatchW = 3.2 * u, pad = 1.0 * u;
        double textW = 0;
        for (const auto& e : facts.layerLegend) textW = std::max(textW, paint.measure(drawnText(e.text), size, false, 0.35 * W).first);
        const double w = 2 * pad + swatchW + 0.8 * u + textW, h = 2 * pad + rowH * facts.layerLegend.size();
        const PixelBox box{2.5 * u, H - 11 * u - h, 2.5 * u + w, H - 11 * u};
        const auto choice =
            placeItem("layer_legend", box, around(box, "bottom-left", {"bottom-right", "top-left", "top-right"}));
        if (!choice) return;
        cairo_save(c);
        cairo_translate(c, choice->dx, choice->dy);
        cairo_rectangle(c, box.x0, box.y0, w, h);
        cairo_set_source_rgba(c, 1, 1, 1, 0.8);
        cairo_fill_preserve(c);
        cairo_set_line_width(c, std::max(1.0, 0.12 * u));
        cairo_set_source_rgb(c, 0.35, 0.35, 0.35);
        cairo_stroke(c);
        double y = box.y0 + pad;
        for (const auto& e : facts.layerLegend) {
            swatch(e, box.x0 + pad, y + 0.3 * u, swatchW, rowH - 0.6 * u);
            paint.text(drawnText(e.text), box.x0 + pad + swatchW + 0.8 * u, y + 0.25 * u, size, false, 0, 0.35 * W);
            y += rowH;
        }
        cairo_restore(c);
        placed("layer_legend", *choice);
    }

    // Every label at the first free place beside its anchor (placeLabels, layout.h),
    // clear of the furniture placed before and of every marker.
    void labels(const OverlayFacts& facts) {
        // The furniture a little larger: a label beside the scale bar's figures would read as one of them.
        std::vector<PixelBox> obstacles;
        const double margin = 0.6 * u;
        for (const PixelBox& b : placer.placed())
            obstacles.push_back({b.x0 - margin, b.y0 - margin, b.x1 + margin, b.y1 + margin});
        std::vector<LabelRequest> requests;
        std::vector<std::string> texts;
        for (const auto& l : facts.labels) {
            texts.push_back(drawnText(l.text));
            const auto [w, h] = paint.measure(texts.back(), l.sizePx / u, false, 0.3 * W);
            const PixelBox marker = l.markerPx > 0 ? PixelBox{l.anchor.x - l.markerPx, l.anchor.y - l.markerPx,
                                                              l.anchor.x + l.markerPx, l.groundY}
                                                   : PixelBox{};
            requests.push_back({l.anchor, l.markerPx, w, h, marker, l.layer == 0});
        }
        const auto places = placeLabels(requests, W, H, obstacles);
        for (size_t i = 0; i < places.size(); ++i) {
            const LabelFact& l = facts.labels[i];
            OverlayRecord::Label rec{texts[i], l.layer};
            rec.anchor = l.anchor;
            if (places[i]) {
                const PlacedLabel& p = *places[i];
                if (p.leader) leader(l.anchor, p.leaderEnd);
                paint.text(texts[i], p.box.x0, p.box.y0, l.sizePx / u, false, 0, 0.3 * W);
                rec.placed = true, rec.leader = p.leader, rec.box = p.box, rec.leaderEnd = p.leaderEnd;
            }
            record.labels.push_back(rec);
        }
    }

    OverlayRecord record;

private:
    void swatch(const LegendEntry& e, double x, double y, double w, double h) {
        cairo_save(c);
        const auto rgb = [&](const LinearRgb& k, double alpha) {
            cairo_set_source_rgba(c, linearToSrgb(k.r), linearToSrgb(k.g), linearToSrgb(k.b), alpha);
        };
        if (e.kind == LegendEntry::Kind::Point) {
            cairo_arc(c, x + w / 2, y + h / 2, 0.3 * h, 0, 2 * std::numbers::pi);
            rgb(e.colour, 1);
            cairo_fill_preserve(c);
            cairo_set_line_width(c, std::max(1.0, 0.1 * u));
            cairo_set_source_rgb(c, 0.08, 0.08, 0.08);
            cairo_stroke(c);
        } else if (e.kind == LegendEntry::Kind::Polygon) {
            cairo_rectangle(c, x, y, w, h);
            if (e.fill) {
                rgb(*e.fill, e.fillOpacity);
                cairo_fill_preserve(c);
            }
            rgb(e.colour, 1);
            cairo_set_line_width(c, std::max(1.0, e.widthPx));
            cairo_stroke(c);
        } else {
            if (e.dashed) {
                const double dash[] = {0.8 * u, 0.5 * u};
                cairo_set_dash(c, dash, 2, 0);
            }
            cairo_move_to(c, x, y + h / 2);
            cairo_line_to(c, x + w, y + h / 2);
            rgb(e.colour, 1);
            cairo_set_line_width(c, std::max(1.0, e.widthPx));
            cairo_stroke(c);
        }
        cairo_restore(c);
    }

    // A leader from a marker to its label: dark on a pale halo.
    void leader(const PixelPoint& from, const PixelPoint& to) {
        cairo_save(c);
        cairo_move_to(c, from.x, from.y);
        cairo_line_to(c, to.x, to.y);
        cairo_set_line_cap(c, CAIRO_LINE_CAP_ROUND);
        cairo_set_source_rgba(c, 1, 1, 1, 0.85);
        cairo_set_line_width(c, 3);
        cairo_stroke_preserve(c);
        cairo_set_source_rgb(c, 0.08, 0.08, 0.08);
        cairo_set_line_width(c, 1.2);
        cairo_stroke(c);
        cairo_restore(c);
    }

    // `item`'s place: where the scene puts it, else the first free of
    // `automatic`; none (recorded as left out, with what is in its way) when
    // that place is not free.
    // `steady`: a box around `box` that places it at a named place instead (`box` moved with it).
    std::optional<FurniturePlacer::Choice> placeItem(const std::string& item, const PixelBox& box,
                                                     const FurniturePlacer::Candidates& automatic,
                                                     const PixelBox* steady = nullptr) {
        const auto named = spec.places.find(item);
        if (named == spec.places.end() || named->second == "auto")
            return leftOutIfNone(item, placer.place(item, box, automatic));
        // A steady item holds its whole square, the same in every frame of a film.
        const PixelBox& by = steady ? *steady : box;
        return leftOutIfNone(item, placer.place(item, by, {{placer.at(by, named->second), named->second}}));
    }
    // Records an item with no place as left out.
    std::optional<FurniturePlacer::Choice> leftOutIfNone(const std::string& item,
                                                         std::optional<FurniturePlacer::Choice> choice) {
        if (!choice) record.leftOut.push_back({item, placer.inTheWay()});
        return choice;
    }

    // `box` where it is (named `here`), then at each of `others`.
    FurniturePlacer::Candidates around(const PixelBox& box, const std::string& here,
                                       const std::vector<std::string>& others) const {
        FurniturePlacer::Candidates out{{box, here}};
        for (const std::string& where : others) out.push_back({placer.at(box, where), where});
        return out;
    }
    // `box` at each of `wheres`.
    FurniturePlacer::Candidates places(const PixelBox& box, const std::vector<std::string>& wheres) const {
        FurniturePlacer::Candidates out;
        for (const std::string& where : wheres) out.push_back({placer.at(box, where), where});
        return out;
    }

    // A text's alignment in a place: 0 left, 0.5 centred, 1 right.
    static double alignmentAt(const std::string& where) {
        return where.find("right") != std::string::npos ? 1 : where.find("left") != std::string::npos ? 0 : 0.5;
    }

    void placed(const char* name, const FurniturePlacer::Choice& choice) {
        record.drawn.push_back(name);
        record.placement[name] = choice.where;
        record.boxes[name] = placer.placed().back();
        if (choice.onTerrain) record.onTerrain.push_back(name);
    }

    cairo_t* c;
    const int W, H;
    const double u;  // sizes scale with the still
    const scene::OverlaySpec& spec;
    Painter paint;
    FurniturePlacer placer;
};

}  // namespace

Owned<cairo_surface_t> surfaceOf(const PngImage8& image) {
    const int W = image.width, H = image.height, n = image.channels;
    Owned<cairo_surface_t> surface(cairo_image_surface_create(CAIRO_FORMAT_ARGB32, W, H));
    if (cairo_surface_status(surface.get()) != CAIRO_STATUS_SUCCESS) return nullptr;
    cairo_surface_flush(surface.get());
    unsigned char* data = cairo_image_surface_get_data(surface.get());
    const int stride = cairo_image_surface_get_stride(surface.get());
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            const std::uint8_t* p = &image.pixels[(static_cast<size_t>(y) * W + x) * n];
            const unsigned a = n == 4 ? p[3] : 255;
            const auto pre = [&](unsigned c) { return (c * a + 127) / 255; };
            reinterpret_cast<std::uint32_t*>(data + static_cast<size_t>(y) * stride)[x] =
                (a << 24) | (pre(p[0]) << 16) | (pre(p[1]) << 8) | pre(p[2]);
        }
    cairo_surface_mark_dirty(surface.get());
    return surface;
}

OverlayRecord paintOverlays(cairo_t* cr, int widthPx, int heightPx, const scene::OverlaySpec& spec,
                            const OverlayFacts& facts, const DrawingTarget& target) {
    OverlayDrawing drawing(cr, widthPx, heightPx, spec, facts, target);
    // In this order: an item placed first keeps its place; one with no free place left is left out.
    const auto wanted = [&](const char* item) {
        const auto p = spec.places.find(item);
        return p == spec.places.end() || p->second != "off";
    };
    const bool map = facts.mapFurniture;
    if (map && facts.mapFrame) drawing.mapFrame(*facts.mapFrame);
    if ((!spec.title.empty() || !spec.subtitle.empty()) && wanted("title")) drawing.title();
    if (map && spec.northArrow && wanted("north_arrow")) drawing.northArrow(facts);
    if (!facts.credits.empty() && wanted("credits")) drawing.credits(facts);
    if (map && spec.scaleBar && wanted("scale_bar")) drawing.scaleBar(facts);
    if (map && spec.legend && facts.palette.size() >= 2 && wanted("legend")) drawing.legend(facts);
    if (map && !facts.layerLegend.empty() && wanted("layer_legend")) drawing.layerLegend(facts);
    if (map && !facts.labels.empty()) drawing.labels(facts);
    return drawing.record;
}

std::map<std::string, std::string> steadyPlaces(const std::vector<FrameOverlays>& frames, int widthPx, int heightPx) {
    std::map<std::string, std::map<std::string, int>> counts;  // item -> place -> frames
    std::map<std::string, std::string> earliest;
    const Owned<cairo_surface_t> nowhere(cairo_recording_surface_create(CAIRO_CONTENT_COLOR_ALPHA, nullptr));
    for (const FrameOverlays& f : frames) {
        const Owned<cairo_t> cr(cairo_create(nowhere.get()));
        for (const auto& [item, where] : paintOverlays(cr.get(), widthPx, heightPx, *f.spec, *f.facts, {}).placement)
            if (std::find(scene::kFurnitureItems.begin(), scene::kFurnitureItems.end(), item) !=
                scene::kFurnitureItems.end()) {
                ++counts[item][where];
                earliest.emplace(item, where);
            }
    }
    std::map<std::string, std::string> places = frames.empty() ? std::map<std::string, std::string>{}
                                                               : frames.front().spec->places;
    for (const auto& [item, byPlace] : counts) {
        if (places.count(item) && places.at(item) != "auto") continue;  // the scene's own
        std::string best = earliest.at(item);
        for (const auto& [where, n] : byPlace)
            if (n > byPlace.at(best)) best = where;
        places[item] = best;
    }
    // A named place may not hold an item in every frame (the north arrow holds the square it turns
    // in there, larger than its box in any one frame): such an item stays automatic.
    for (const FrameOverlays& f : frames) {
        scene::OverlaySpec named = *f.spec;
        named.places = places;
        const Owned<cairo_t> cr(cairo_create(nowhere.get()));
        for (const auto& l : paintOverlays(cr.get(), widthPx, heightPx, named, *f.facts, {}).leftOut)
            if (!f.spec->places.count(l.item)) places.erase(l.item);
    }
    return places;
}

void warnLeftOut(const OverlayRecord& record, int widthPx, int heightPx, const SourceLoc& at, Diagnostics& diags) {
    const auto spoken = [](std::string item) {
        std::replace(item.begin(), item.end(), '_', ' ');
        return item;
    };
    for (const auto& [item, inTheWay] : record.leftOut)
        diags.warningOnce("overlay left out: " + item, at,
                          fmt::format("the {} is left out: no free place for it on a {} x {} still (in the way: "
                                      "{}); give overlay.place.{} a free place, or make the still larger",
                                      spoken(item), widthPx, heightPx, spoken(inTheWay), item));
}

bool drawOverlays(PngImage8& image, const scene::OverlaySpec& spec, const OverlayFacts& facts, const SourceLoc& at,
                  Diagnostics& diags, OverlayRecord* record) {
    const Owned<cairo_surface_t> surface =
        image.channels == 3 || image.channels == 4 ? surfaceOf(image) : Owned<cairo_surface_t>(nullptr);
    if (!surface) {
        diags.error(at, fmt::format("the overlays cannot be drawn on a still of {} channels (they need RGB or RGBA)",
                                    image.channels));
        return false;
    }
    const Owned<cairo_t> cr(cairo_create(surface.get()));
    const OverlayRecord drawn = paintOverlays(cr.get(), image.width, image.height, spec, facts, {});
    copyBack(surface.get(), image);
    warnLeftOut(drawn, image.width, image.height, at, diags);
    if (record) *record = drawn;
    return true;
}

}  // namespace relief::annotate
