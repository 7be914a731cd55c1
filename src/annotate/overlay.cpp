#include "annotate/overlay.h"

#include "annotate/labels.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <memory>

#include <fmt/format.h>
#include <cairo-pdf.h>
#include <cairo-svg.h>
#include <pango/pangocairo.h>

#include "core/number_format.h"
#include "core/output_set.h"
#include "core/text_escape.h"

namespace relief::annotate {

namespace {

constexpr double kPi = 3.14159265358979323846;

// 1, 2 or 5 x 10^k: the largest not above `v`.
double roundDown125(double v) {
    const double p = std::pow(10.0, std::floor(std::log10(v)));
    const double m = v / p;
    return (m >= 5 ? 5 : m >= 2 ? 2 : 1) * p;
}

std::string metresLabel(double m) {
    if (m >= 1000) return formatShortest(m / 1000) + " km";
    return formatShortest(m) + " m";
}

// The sRGB transfer function (IEC 61966-2-1): the still's PNG is sRGB, the
// ramp's colours are linear.
double linearToSrgb(double c) {
    c = std::clamp(c, 0.0, 1.0);
    return c <= 0.0031308 ? 12.92 * c : 1.055 * std::pow(c, 1 / 2.4) - 0.055;
}

struct CairoDeleter {
    void operator()(cairo_surface_t* s) const { cairo_surface_destroy(s); }
    void operator()(cairo_t* c) const { cairo_destroy(c); }
    void operator()(PangoLayout* l) const { g_object_unref(l); }
    void operator()(PangoFontDescription* f) const { pango_font_description_free(f); }
};
template <class T>
using Owned = std::unique_ptr<T, CairoDeleter>;

// What the drawing goes onto: the still's pixels, or a document's page (whose
// device units are points, devicePerPixel of them a pixel of the still).
struct DrawingTarget {
    bool realText = false;
    double devicePerPixel = 1;
};

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
        pango_font_description_set_absolute_size(font.get(), std::max(sizeUnits * unit_, 10.0) * PANGO_SCALE);
        pango_layout_set_font_description(layout.get(), font.get());
        if (maxWidth > 0) {
            pango_layout_set_width(layout.get(), static_cast<int>(maxWidth * PANGO_SCALE));
            pango_layout_set_wrap(layout.get(), PANGO_WRAP_WORD_CHAR);
            pango_layout_set_height(layout.get(), -maxLines);
            pango_layout_set_ellipsize(layout.get(), PANGO_ELLIPSIZE_END);
            pango_layout_set_alignment(layout.get(), anchorX >= 1 ? PANGO_ALIGN_RIGHT : PANGO_ALIGN_LEFT);
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
        } else {
            cairo_stroke_preserve(cr_);
            cairo_set_source_rgb(cr_, 0.08, 0.08, 0.08);
            cairo_fill(cr_);
        }
        double px = left, py = top;  // the box in the still's pixels, wherever the drawing was moved
        cairo_user_to_device(cr_, &px, &py);
        drawn_.push_back({s, px / devicePerPixel_, py / devicePerPixel_, w, h, std::max(sizeUnits * unit_, 10.0), bold});
        return {w, h};
    }

    cairo_t* cr_;
    double unit_;
    bool realText_;
    double devicePerPixel_;
    std::vector<DrawnText>& drawn_;
};

struct Box {
    double x0, y0, x1, y1;
    double w() const { return x1 - x0; }
    double h() const { return y1 - y0; }
    bool meets(const Box& o, double pad) const {
        return x0 < o.x1 + pad && o.x0 < x1 + pad && y0 < o.y1 + pad && o.y0 < y1 + pad;
    }
};

// Where the overlays go: each in the first of its places that neither the
// terrain nor an overlay placed before it covers (a corner of it may touch
// the terrain: 2 of 81 points); else the first no overlay covers (its halo
// keeps it legible on the terrain).
class Placer {
public:
    Placer(int W, int H, double u, const TerrainOnImage& terrain) : W_(W), H_(H), u_(u), terrain_(terrain) {}

    struct Choice {
        double dx = 0, dy = 0;  ///< move from the default box
        std::string where;      ///< "top-left", ...
        bool onTerrain = false;
    };

    using Candidates = std::vector<std::pair<Box, std::string>>;

    /// `box` moved to a corner of the still (2 units in from its edges).
    Box corner(const Box& box, const std::string& where) const {
        const double m = 2 * u_;
        const double x = where.find("left") != std::string::npos ? m : W_ - m - box.w();
        const double y = where.find("top") != std::string::npos ? m : H_ - m - box.h();
        return {x, y, x + box.w(), y + box.h()};
    }

    /// `box` at its default place, named `defaultName`, then in each corner of `order`.
    Choice place(const Box& box, const std::string& defaultName, const std::vector<std::string>& order) {
        Candidates candidates{{box, defaultName}};
        for (const std::string& where : order) candidates.push_back({corner(box, where), where});
        return place(box, candidates);
    }

    /// The first of `candidates` (boxes the size of `box`) that is free.
    Choice place(const Box& box, const Candidates& candidates) {
        const auto freeOfOverlays = [&](const Box& b) {
            return std::none_of(placed_.begin(), placed_.end(), [&](const Box& p) { return b.meets(p, u_); });
        };
        const std::pair<Box, std::string>* chosen = nullptr;
        for (const auto& c : candidates)
            if (freeOfOverlays(c.first) && !coversTerrain(c.first)) {
                chosen = &c;
                break;
            }
        if (!chosen)
            for (const auto& c : candidates)
                if (freeOfOverlays(c.first)) {
                    chosen = &c;
                    break;
                }
        if (!chosen) chosen = &candidates.front();
        placed_.push_back(chosen->first);
        return {chosen->first.x0 - box.x0, chosen->first.y0 - box.y0, chosen->second, coversTerrain(chosen->first)};
    }

    /// The boxes placed so far.
    const std::vector<Box>& placed() const { return placed_; }

private:
    bool coversTerrain(const Box& b) const {
        constexpr int kSamples = 9, kAllowed = 2;
        int on = 0;
        for (int i = 0; i < kSamples; ++i)
            for (int j = 0; j < kSamples; ++j)
                on += terrain_.covers(b.x0 + b.w() * i / (kSamples - 1), b.y0 + b.h() * j / (kSamples - 1));
        return on > kAllowed;
    }
    int W_, H_;
    double u_;
    const TerrainOnImage& terrain_;
    std::vector<Box> placed_;
};

}  // namespace

TerrainOnImage TerrainOnImage::fromPoints(const std::vector<std::array<double, 2>>& points, int widthPx) {
    TerrainOnImage t;
    const int bands = std::max(1, static_cast<int>(std::ceil(widthPx / t.bandPx)));
    t.top.assign(bands, 1e300);
    t.bottom.assign(bands, -1e300);
    for (const auto& [x, y] : points) {
        if (!(x >= 0 && x < widthPx) || !std::isfinite(y)) continue;
        const int b = static_cast<int>(x / t.bandPx);
        t.top[b] = std::min(t.top[b], y), t.bottom[b] = std::max(t.bottom[b], y);
    }
    // Bands between covered ones: linear between their neighbours (the lattice's
    // nodes land a few pixels apart).
    int last = -1;
    for (int b = 0; b < bands; ++b) {
        if (t.top[b] > t.bottom[b]) continue;
        for (int k = last + 1; last >= 0 && k < b; ++k) {
            const double f = double(k - last) / (b - last);
            t.top[k] = t.top[last] + f * (t.top[b] - t.top[last]);
            t.bottom[k] = t.bottom[last] + f * (t.bottom[b] - t.bottom[last]);
        }
        last = b;
    }
    return t;
}

bool TerrainOnImage::covers(double x, double y) const {
    const int b = static_cast<int>(std::floor(x / bandPx));
    return b >= 0 && b < static_cast<int>(top.size()) && y >= top[b] && y <= bottom[b];
}

ScaleBar chooseScaleBar(double metresPerPixel, int widthPx) {
    ScaleBar bar;
    if (!(metresPerPixel > 0) || widthPx <= 0) return bar;
    bar.metres = roundDown125(0.2 * widthPx * metresPerPixel);
    bar.pixels = bar.metres / metresPerPixel;
    bar.label = metresLabel(bar.metres);
    return bar;
}

std::vector<double> legendTicks(double zMinM, double zMaxM) {
    std::vector<double> ticks;
    if (!(zMaxM > zMinM)) return {zMinM};
    const double step = roundDown125((zMaxM - zMinM) / 4);
    for (double v = std::ceil(zMinM / step) * step; v <= zMaxM + 1e-9 * step; v += step)
        ticks.push_back(std::abs(v) < 1e-9 * step ? 0.0 : v);
    return ticks;
}

double northOnImageDeg(const emit::CameraView& view, double convergenceDeg, int widthPx, int heightPx) {
    // True north is convergenceDeg anticlockwise of grid north: in scene axes
    // (x east, z north) the direction (-sin g, 0, cos g).
    const double g = convergenceDeg * kPi / 180;
    const double step = 1e-3 * view.radius;
    const SceneVec3 north{-std::sin(g) * step, 0, std::cos(g) * step};
    const auto a = emit::projectToImage(view, view.target, widthPx, heightPx);
    const auto b = emit::projectToImage(view, view.target + north, widthPx, heightPx);
    return std::atan2(b[0] - a[0], a[1] - b[1]) * 180 / kPi;
}

double metresPerPixelAtTarget(const emit::CameraView& view, double metresPerUnit, int widthPx) {
    const double span = view.perspective ? 2 * length(view.target - view.eye) * view.tanHalfFov
                                         : view.orthoHeight * view.aspect;
    return span * metresPerUnit / widthPx;
}

bool overlaysWanted(const scene::OverlaySpec& spec, int widthPx) {
    using E = scene::OverlaySpec::Enabled;
    return spec.enabled == E::On || (spec.enabled == E::Auto && widthPx >= scene::OverlaySpec::kMinAutoWidthPx);
}

namespace {

// Cairo's ARGB32 (premultiplied, one native 32-bit word a pixel) holding the still's pixels.
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
    OverlayDrawing(cairo_t* c, int W, int H, const OverlayFacts& facts, const DrawingTarget& target)
        : c(c), W(W), H(H), u(std::min(W, H * 4 / 3) / 100.0), paint(c, u, target, record.texts),
          placer(W, H, u, facts.terrain) {}

    // Title and subtitle, top left.
    void title(const scene::OverlaySpec& spec) {
        double w = 0, h = 0;
        if (!spec.title.empty()) {
            const auto [tw, th] = paint.measure(spec.title, 3.6, true, 0.62 * W, 2);
            w = std::max(w, tw), h += th;
        }
        if (!spec.subtitle.empty()) {
            const auto [sw, sh] = paint.measure(spec.subtitle, 2.2, false, 0.62 * W, 2);
            w = std::max(w, sw), h += sh + 0.3 * u;
        }
        const Box box{2.5 * u, 2.2 * u, 2.5 * u + w, 2.2 * u + h};
        const auto choice = placer.place(box, "top-left", {"top-right"});  // a title stays at the top
        cairo_save(c);
        cairo_translate(c, choice.dx, choice.dy);
        // Right-aligned in a right-hand corner.
        const bool right = choice.where.find("right") != std::string::npos;
        const double x = right ? box.x1 : box.x0, anchor = right ? 1 : 0;
        double y = box.y0;
        if (!spec.title.empty()) {
            y += paint.text(spec.title, x, y, 3.6, true, anchor, 0.62 * W, 2).second;
            placed("title", choice);
        }
        if (!spec.subtitle.empty()) {
            paint.text(spec.subtitle, x, y + 0.3 * u, 2.2, false, anchor, 0.62 * W, 2);
            placed("subtitle", choice);
        }
        cairo_restore(c);
    }

    // North arrow, top right: an arrow pointing where true north lies.
    void northArrow(const OverlayFacts& facts) {
        const double cx = W - 6 * u, cy = 7.5 * u, len = 3.6 * u;
        const Box box{cx - 1.9 * len, cy - 1.9 * len - 1.3 * u, cx + 1.9 * len, cy + 1.9 * len};
        const auto choice = placer.place(box, "top-right", {"top-left", "bottom-right", "bottom-left"});
        cairo_save(c);
        cairo_translate(c, choice.dx, choice.dy);
        cairo_save(c);
        cairo_translate(c, cx, cy);
        cairo_rotate(c, facts.northDeg * kPi / 180);
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
        const double a = facts.northDeg * kPi / 180;
        paint.text("N", cx + std::sin(a) * 1.75 * len, cy - std::cos(a) * 1.75 * len - 1.3 * u, 2.4, true, 0.5);
        cairo_restore(c);
        placed("north_arrow", choice);
        record.northDeg = facts.northDeg;
    }

    // Credits, bottom right: whose data (CC BY and the OGL ask for it).
    void credits(const OverlayFacts& facts) {
        const auto [w, h] = paint.measure(facts.credits, 1.4, false, 0.55 * W, 4, 1);
        const Box box{W - 2 * u - w, H - 1.2 * u - h, W - 2 * u, H - 1.2 * u};
        const auto choice = placer.place(box, "bottom-right", {"bottom-left"});
        const bool right = choice.where.find("right") != std::string::npos;
        // Left-aligned in a left-hand corner.
        paint.text(facts.credits, right ? box.x1 + choice.dx : box.x0 + choice.dx, box.y1 + choice.dy, 1.4, false,
                   right ? 1 : 0, 0.55 * W, 4, 1);
        placed("credits", choice);
    }

    // Scale bar, bottom left: four alternating segments.
    void scaleBar(const OverlayFacts& facts) {
        const ScaleBar bar = chooseScaleBar(facts.metresPerPixel, W);
        if (bar.pixels > 0) {
            const double x0 = 3 * u, y0 = H - 7 * u, h = 0.9 * u;
            const double labelW = paint.measure(bar.label, 1.7, false).first;
            const double noteW = facts.perspective ? paint.measure("at the centre of the view", 1.4, false).first : 0;
            const Box box{x0 - 1.2 * u, y0 - 2.8 * u, std::max(x0 + bar.pixels + labelW / 2, x0 + noteW),
                          y0 + h + (facts.perspective ? 3.2 * u : 0.6 * u)};
            const auto choice = placer.place(box, "bottom-left", {"bottom-right", "top-left", "top-right"});
            cairo_save(c);
            cairo_translate(c, choice.dx, choice.dy);
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
            paint.text("0", x0, y0 - 2.6 * u, 1.7, false, 0.5);
            paint.text(bar.label, x0 + bar.pixels, y0 - 2.6 * u, 1.7, false, 0.5);
            if (facts.perspective) paint.text("at the centre of the view", x0, y0 + h + 0.6 * u, 1.4, false, 0);
            cairo_restore(c);
            placed("scale_bar", choice);
            record.scaleBar = bar;
        }
    }

    // Elevation legend, right: the ramp as a bar, ticks in true metres.
    void legend(const OverlayFacts& facts) {
        const double barW = 2.0 * u, barH = 0.38 * H, x0 = W - 13 * u, y0 = 17 * u;
        const bool exaggerated = std::abs(facts.exaggeration - 1) > 1e-9;
        const double titleW = paint.measure(facts.legendTitle, 1.9, true).first;
        const double noteW = facts.legendNote.empty() ? 0 : paint.measure(facts.legendNote, 1.6, false).first;
        const double bottom =
            y0 + barH + 1.2 * u + (exaggerated ? 2.4 * u : 0) + (facts.legendNote.empty() ? 0 : 2.4 * u);
        const Box box{std::min({x0 - 1.5 * u, x0 + barW - titleW / 2, W - 2 * u - noteW}), y0 - 3.6 * u,
                      std::max(W - 2 * u, x0 + barW + titleW / 2), bottom};
        // Down the right edge from below the north arrow, then down the left edge.
        Placer::Candidates candidates;
        for (const bool left : {false, true})
            for (double top = box.y0; top + box.h() <= H - 2 * u || top == box.y0; top += 2 * u) {
                const double x = left ? 2 * u : box.x0;
                candidates.push_back({{x, top, x + box.w(), top + box.h()}, left ? "left" : "right"});
            }
        const auto choice = placer.place(box, candidates);
        cairo_save(c);
        cairo_translate(c, choice.dx, choice.dy);
        paint.text(facts.legendTitle, x0 + barW, y0 - 3.4 * u, 1.9, true, 0.5);
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
        for (double v : legendTicks(facts.zMinM, facts.zMaxM)) {
            const double ty = y0 + barH * (1 - (v - facts.zMinM) / span);
            cairo_move_to(c, x0 + barW, ty);
            cairo_line_to(c, x0 + barW + 0.8 * u, ty);
            cairo_set_source_rgb(c, 0.08, 0.08, 0.08);
            cairo_stroke(c);
            paint.text(formatShortest(v), x0 + barW + 1.2 * u, ty - 1.0 * u, 1.7, false);
        }
        double noteY = y0 + barH + 1.2 * u;
        if (exaggerated) {
            paint.text(fmt::format("vertical \u00d7{}", formatShortest(facts.exaggeration)), x0 + barW, noteY, 1.6,
                       false, 0.5);
            noteY += 2.4 * u;
        }
        if (!facts.legendNote.empty()) paint.text(facts.legendNote, W - 2 * u, noteY, 1.6, false, 1);
        cairo_restore(c);
        placed("legend", choice);
    }

    // The [[layer]]s' legend: a swatch and a line of text an entry, on a pale card.
    void layerLegend(const OverlayFacts& facts) {
        const double size = 1.6, rowH = 2.6 * u, swatchW = 3.2 * u, pad = 1.0 * u;
        double textW = 0;
        for (const auto& e : facts.layerLegend) textW = std::max(textW, paint.measure(drawnText(e.text), size, false, 0.35 * W).first);
        const double w = 2 * pad + swatchW + 0.8 * u + textW, h = 2 * pad + rowH * facts.layerLegend.size();
        const Box box{2.5 * u, H - 11 * u - h, 2.5 * u + w, H - 11 * u};
        const auto choice = placer.place(box, "bottom-left", {"bottom-right", "top-left", "top-right"});
        cairo_save(c);
        cairo_translate(c, choice.dx, choice.dy);
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
        placed("layer_legend", choice);
    }

    // Every label at the first free place beside its anchor (annotate/labels.h),
    // clear of the furniture placed before and of every marker.
    void labels(const OverlayFacts& facts) {
        // The furniture a little larger: a label beside the scale bar's figures would read as one of them.
        std::vector<LabelBox> obstacles;
        const double margin = 0.6 * u;
        for (const Box& b : placer.placed()) obstacles.push_back({b.x0 - margin, b.y0 - margin, b.x1 + margin, b.y1 + margin});
        std::vector<LabelRequest> requests;
        std::vector<std::string> texts;
        for (const auto& l : facts.labels) {
            texts.push_back(drawnText(l.text));
            const auto [w, h] = paint.measure(texts.back(), l.sizePx / u, false, 0.3 * W);
            const LabelBox marker = l.markerPx > 0 ? LabelBox{l.x - l.markerPx, l.y - l.markerPx, l.x + l.markerPx, l.groundY}
                                                   : LabelBox{};
            requests.push_back({l.x, l.y, l.markerPx, w, h, marker});
        }
        const auto places = placeLabels(requests, W, H, obstacles);
        for (size_t i = 0; i < places.size(); ++i) {
            OverlayRecord::Label rec{texts[i], facts.labels[i].layer};
            if (places[i]) {
                const PlacedLabel& p = *places[i];
                if (p.leader) leader(facts.labels[i].x, facts.labels[i].y, p.leaderX, p.leaderY);
                paint.text(texts[i], p.box.x0, p.box.y0, facts.labels[i].sizePx / u, false, 0, 0.3 * W);
                rec = {texts[i], facts.labels[i].layer, true, p.leader, p.box.x0, p.box.y0, p.box.x1, p.box.y1};
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
            cairo_arc(c, x + w / 2, y + h / 2, 0.3 * h, 0, 2 * kPi);
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
    void leader(double x0, double y0, double x1, double y1) {
        cairo_save(c);
        cairo_move_to(c, x0, y0);
        cairo_line_to(c, x1, y1);
        cairo_set_line_cap(c, CAIRO_LINE_CAP_ROUND);
        cairo_set_source_rgba(c, 1, 1, 1, 0.85);
        cairo_set_line_width(c, 3);
        cairo_stroke_preserve(c);
        cairo_set_source_rgb(c, 0.08, 0.08, 0.08);
        cairo_set_line_width(c, 1.2);
        cairo_stroke(c);
        cairo_restore(c);
    }

    void placed(const char* name, const Placer::Choice& choice) {
        record.drawn.push_back(name);
        record.placement[name] = choice.where;
        if (choice.onTerrain) record.onTerrain.push_back(name);
    }

    cairo_t* c;
    const int W, H;
    const double u;  // sizes scale with the still
    Painter paint;
    Placer placer;
};

}  // namespace

namespace {

// Every overlay the spec asks for, drawn with `cr` over a still W x H pixels.
OverlayRecord drawOverlaysOn(cairo_t* cr, int W, int H, const scene::OverlaySpec& spec, const OverlayFacts& facts,
                             const DrawingTarget& target) {
    OverlayDrawing drawing(cr, W, H, facts, target);
    if (!spec.title.empty() || !spec.subtitle.empty()) drawing.title(spec);
    if (spec.northArrow) drawing.northArrow(facts);
    if (!facts.credits.empty()) drawing.credits(facts);
    if (spec.scaleBar) drawing.scaleBar(facts);
    if (spec.legend && facts.palette.size() >= 2) drawing.legend(facts);
    if (!facts.layerLegend.empty()) drawing.layerLegend(facts);
    if (!facts.labels.empty()) drawing.labels(facts);
    return drawing.record;
}

// An invisible text of every string drawn, over its glyphs: cairo's SVG draws
// glyphs as outlines, which a reader cannot search or copy. Escaped as text.
std::string svgTextLayer(const std::vector<DrawnText>& texts, double pointsPerPixel) {
    std::string layer = "<g id=\"relief-text\" fill-opacity=\"0\" font-family=\"DejaVu Sans\">\n";
    for (const auto& t : texts)
        layer += fmt::format("<text x=\"{:.2f}\" y=\"{:.2f}\" font-size=\"{:.2f}\"{} textLength=\"{:.2f}\" "
                             "lengthAdjust=\"spacingAndGlyphs\">{}</text>\n",
                             t.x * pointsPerPixel, (t.y + 0.8 * t.h) * pointsPerPixel, t.sizePx * pointsPerPixel,
                             t.bold ? " font-weight=\"bold\"" : "", t.w * pointsPerPixel, markupText(t.text));
    return layer + "</g>\n";
}

// cairo's SVG with the text layer put in before its end.
std::string withTextLayer(const std::filesystem::path& svg, const std::vector<DrawnText>& texts, double pointsPerPixel,
                          std::string& error) {
    std::ifstream in(svg, std::ios::binary);
    std::string doc((std::istreambuf_iterator<char>(in)), {});
    const size_t end = doc.rfind("</svg>");
    if (end == std::string::npos) {
        error = "cairo wrote no whole SVG";
        return {};
    }
    return doc.insert(end, svgTextLayer(texts, pointsPerPixel));
}

// The file a document is written into, keeping the system's reason for a
// failed write: cairo's own file writer says only "error while writing to
// output stream", which hid a full disk.
class DocumentFile {
public:
    explicit DocumentFile(const std::filesystem::path& path)
        : file_(std::fopen(path.c_str(), "wbe")), err_(file_ ? 0 : errno) {}
    ~DocumentFile() {
        if (file_) std::fclose(file_);
    }
    DocumentFile(const DocumentFile&) = delete;
    DocumentFile& operator=(const DocumentFile&) = delete;

    /// Cairo's write function, `self` a DocumentFile.
    static cairo_status_t write(void* self, const unsigned char* data, unsigned int length) {
        return static_cast<DocumentFile*>(self)->append(data, length) ? CAIRO_STATUS_SUCCESS : CAIRO_STATUS_WRITE_ERROR;
    }
    bool append(const void* data, size_t length) {
        if (err_ == 0 && std::fwrite(data, 1, length, file_) != length) err_ = errno != 0 ? errno : EIO;
        return err_ == 0;
    }
    /// Closes the file: "" or "cannot be written: " and the system's reason,
    /// or cairo's (`status`) when the system gave none.
    std::string close(cairo_status_t status = CAIRO_STATUS_SUCCESS) {
        if (file_ && std::fclose(file_) != 0 && err_ == 0) err_ = errno;
        file_ = nullptr;
        if (err_ != 0) return "cannot be written: " + writeFailureReason(err_);
        if (status != CAIRO_STATUS_SUCCESS) return fmt::format("cannot be written: {}", cairo_status_to_string(status));
        return "";
    }

private:
    std::FILE* file_;
    int err_;
};

// The SVG cairo drew, at `drawnAt`, with the text layer added, written to `path`.
std::string finishSvg(const std::filesystem::path& drawnAt, const std::filesystem::path& path,
                      const std::vector<DrawnText>& texts, double pointsPerPixel) {
    std::string error;
    const std::string svg = withTextLayer(drawnAt, texts, pointsPerPixel, error);
    std::error_code ec;
    std::filesystem::remove(drawnAt, ec);
    if (!error.empty()) return error;
    DocumentFile out(path);
    out.append(svg.data(), svg.size());
    return out.close();
}

}  // namespace

std::string drawOverlays(PngImage8& image, const scene::OverlaySpec& spec, const OverlayFacts& facts,
                         OverlayRecord* record) {
    if (image.channels != 3 && image.channels != 4) return "overlays need an RGB or RGBA image";
    const Owned<cairo_surface_t> surface = surfaceOf(image);
    if (!surface) return "cannot make a drawing surface";
    const Owned<cairo_t> cr(cairo_create(surface.get()));
    const OverlayRecord drawn = drawOverlaysOn(cr.get(), image.width, image.height, spec, facts, {});
    copyBack(surface.get(), image);
    if (record) *record = drawn;
    return {};
}

std::string writeDocument(const PngImage8& still, const DocumentRequest& request, OverlayRecord* record) {
    if (still.channels != 3 && still.channels != 4) return "a document needs an RGB or RGBA still";
    const double pointsPerPixel = 72.0 / request.dpi;
    const double widthPt = still.width * pointsPerPixel, heightPt = still.height * pointsPerPixel;
    const std::filesystem::path drawnAt =
        request.format == DocumentFormat::Svg ? std::filesystem::path(request.path.string() + ".cairo") : request.path;
    DocumentFile pageFile(drawnAt);  // declared first: the page, destroyed before it, may still write
    Owned<cairo_surface_t> page(
        request.format == DocumentFormat::Pdf
            ? cairo_pdf_surface_create_for_stream(DocumentFile::write, &pageFile, widthPt, heightPt)
            : cairo_svg_surface_create_for_stream(DocumentFile::write, &pageFile, widthPt, heightPt));
    if (cairo_surface_status(page.get()) != CAIRO_STATUS_SUCCESS) return pageFile.close(cairo_surface_status(page.get()));
    if (request.format == DocumentFormat::Pdf) {
        // No clock in the file: the same still gives the same bytes.
        cairo_pdf_surface_set_metadata(page.get(), CAIRO_PDF_METADATA_CREATE_DATE, kDocumentDate);
        cairo_pdf_surface_set_metadata(page.get(), CAIRO_PDF_METADATA_CREATOR, "relief");
        // UTF-8, which cairo writes as the PDF's UTF-16: anything else fails the whole page ("input
        // string not valid UTF-8").
        if (!request.spec.title.empty()) {
            const std::string title = utf8Replaced(request.spec.title);
            cairo_pdf_surface_set_metadata(page.get(), CAIRO_PDF_METADATA_TITLE, title.c_str());
        }
    } else {
        cairo_svg_surface_set_document_unit(page.get(), CAIRO_SVG_UNIT_PT);
    }
    const Owned<cairo_t> cr(cairo_create(page.get()));
    cairo_scale(cr.get(), pointsPerPixel, pointsPerPixel);
    // The ray-traced image once, at its own pixels: drawn unscaled in pixel units, never resampled.
    const Owned<cairo_surface_t> image = surfaceOf(still);
    if (!image) return "cannot make a drawing surface";
    cairo_set_source_surface(cr.get(), image.get(), 0, 0);
    cairo_pattern_set_filter(cairo_get_source(cr.get()), CAIRO_FILTER_NEAREST);
    cairo_paint(cr.get());
    OverlayRecord drawn;
    if (request.overlays)
        drawn = drawOverlaysOn(cr.get(), still.width, still.height, request.spec, request.facts,
                               {true, pointsPerPixel});
    cairo_show_page(cr.get());
    cairo_surface_finish(page.get());
    if (std::string problem = pageFile.close(cairo_surface_status(page.get())); !problem.empty()) return problem;
    if (request.format == DocumentFormat::Svg)
        if (std::string problem = finishSvg(drawnAt, request.path, drawn.texts, pointsPerPixel); !problem.empty())
            return problem;
    if (record) *record = drawn;
    return {};
}

OverlayFacts overlayFacts(const scene::LookSpec& look, const emit::ScenePlacement& where, const emit::CameraView& view,
                          const scene::RenderSpec& render, double convergenceDeg) {
    OverlayFacts f;
    f.palette.assign(where.paletteColors.begin(),
                     where.paletteColors.begin() + std::min<size_t>(emit::kPaletteSize, where.paletteColors.size()));
    f.zMinM = where.zMinM;
    f.zMaxM = where.zMaxM;
    using Colouring = scene::TextureSpec::Colouring;
    if (look.texture.colouring == Colouring::Image) {
        f.palette.clear();  // an image's colours are its own: no elevation legend
    } else if (look.texture.colouring == Colouring::Slope) {
        f.legendTitle = "Slope (\u00b0)";
        f.zMinM = 0;
        f.zMaxM = emit::kSlopePaletteMaxDeg;
    } else if (look.texture.colouring == Colouring::Blend) {
        f.legendNote = fmt::format("rock on slopes over {}\u00b0", formatShortest(look.texture.rockFromDeg));
    }
    f.exaggeration = where.exaggeration;
    f.perspective = view.perspective;
    f.metresPerPixel = metresPerPixelAtTarget(view, where.metresPerUnit, render.width);
    f.northDeg = northOnImageDeg(view, convergenceDeg, render.width, render.height);
    // Where the terrain lies on the still (points in front of the eye only).
    std::vector<std::array<double, 2>> onImage;
    const SceneVec3 forward = view.target - view.eye;
    for (const SceneVec3& p : where.outline)
        if (!view.perspective || dot(p - view.eye, forward) > 0)
            onImage.push_back(emit::projectToImage(view, p, render.width, render.height));
    f.terrain = TerrainOnImage::fromPoints(onImage, render.width);
    return f;
}

}  // namespace relief::annotate
