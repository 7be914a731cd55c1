// [overlay] frame: the ticks along the terrain's edges, in metres, then on the still.
#include "pipeline/map_frame.h"

#include <algorithm>
#include <cmath>
#include <functional>

#include <fmt/format.h>

#include "core/number_format.h"
#include "emit/graticule.h"
#include "geo/normalize.h"

namespace relief {

namespace {

using Side = annotate::MapFrame::Side;

// A label's length in characters (code points: UTF-8's continuation bytes are none).
size_t charactersOf(const std::string& label) {
    return std::count_if(label.begin(), label.end(), [](char c) { return (c & 0xC0) != 0x80; });
}

// A frame tick's share of an annotation interval `step` (degrees, or metres):
// in its unit (degrees, minutes or seconds; metres) quarters of 1 and 2 (1° by
// 15′, 2 km by 500 m; 1 × 10^k m by fifths), fifths of 5 and 10 (5′ by 1′),
// thirds of 15 and 30 (30′ by 10′).
int frameTicksPerAnnotation(double step, bool degrees) {
    double v = step;
    if (degrees) v = step >= 1 - 1e-9 ? step : step >= 1.0 / 60 - 1e-9 ? step * 60 : step * 3600;
    const double rounded = std::round(v);
    if (std::abs(v - rounded) < 1e-6 && rounded >= 15 && std::fmod(rounded, 15) == 0) return 3;
    const double mantissa = v / std::pow(10.0, std::floor(std::log10(v) + 1e-9));
    if (std::abs(mantissa - 2) < 1e-6 || (degrees && std::abs(v - 1) < 1e-9)) return 4;
    return 5;
}

// A round interval of metres: 1, 2 or 5 x 10^k, at most `most` over `spanM`.
double metresStep(double spanM, int most) {
    double step = std::pow(10.0, std::floor(std::log10(std::max(spanM, 1e-3) / most)));
    for (const double m : {1.0, 2.0, 5.0, 10.0})
        if (spanM / (m * step) <= most) return m * step;
    return 10 * step;
}

// The ticks of one edge, where `valueAt` (a longitude or a latitude,
// increasing from `from` to `to` along it) crosses a multiple of the frame
// interval: found by bisection, to a millionth of the edge. No `valueAt`:
// the coordinate itself, each tick at its value.
void edgeTicks(Side side, double from, double to, const std::function<double(double)>& valueAt, double step,
               int perAnnotation, const std::function<std::string(double)>& label, MapFrameTicks& out) {
    const double lo = valueAt ? valueAt(from) : from, hi = valueAt ? valueAt(to) : to, minor = step / perAnnotation;
    // An edge of a few dozen ticks at most; a span or an origin no double can count in steps of these has none.
    if (!std::isfinite(lo) || !std::isfinite(hi) || !(hi > lo) || !(minor > 0) || (hi - lo) / minor > 1000 ||
        std::max(std::abs(lo), std::abs(hi)) / minor > 0x1p52)
        return;
    for (long long k = std::llround(std::ceil(lo / minor - 1e-9)); k * minor <= hi + 1e-9 * minor; ++k) {
        const double value = k * minor;
        double a = valueAt ? from : value, b = valueAt ? to : value;
        for (int i = 0; i < 60 && b - a > 1e-6 * std::abs(to - from); ++i) {
            const double m = 0.5 * (a + b);
            (valueAt(m) < value ? a : b) = m;
        }
        const bool annotated = k % perAnnotation == 0;
        out.ticks.push_back({side, std::clamp(0.5 * (a + b), from, to), value, annotated ? label(value) : std::string()});
    }
}

}  // namespace

size_t MapFrameTicks::widestLabelChars() const {
    size_t widest = 0;
    for (const Tick& t : ticks) widest = std::max(widest, charactersOf(t.label));
    return widest;
}

namespace {

// The ticks with at most `mostX` annotation intervals across the map and
// `mostY` up it: the graticule's steps (at most five over a span) for a span
// five `most`ths as wide.
std::optional<MapFrameTicks> ticksWithin(const scene::SceneSpec& spec, const geo::GeoGrid& net, int mostX, int mostY,
                                         Diagnostics& diags) {
    MapFrameTicks f{net.x0, net.y0, net.xMax(), net.yMax(), {}};
    if (spec.overlay.frameMetres) {
        const auto label = [](double v) { return formatShortest(v); };
        const double xStep = metresStep(f.x1 - f.x0, mostX), yStep = metresStep(f.y1 - f.y0, mostY);
        for (const Side side : {Side::Bottom, Side::Top})
            edgeTicks(side, f.x0, f.x1, nullptr, xStep, frameTicksPerAnnotation(xStep, false), label, f);
        for (const Side side : {Side::Left, Side::Right})
            edgeTicks(side, f.y0, f.y1, nullptr, yStep, frameTicksPerAnnotation(yStep, false), label, f);
        return f;
    }
    const auto lonLat = [&net](double x, double y) { return geo::reverse(net.frame, Vec3{x, y, 0}); };
    for (const double x : {f.x0, f.x1})
        for (const double y : {f.y0, f.y1})
            if (!lonLat(x, y)) {
                diags.error(spec.overlay.locs.at("overlay.frame"),
                            "overlay.frame: the terrain's frame has no longitude and latitude to annotate; "
                            "set overlay.frame_units = \"metres\"");
                return std::nullopt;
            }
    // Longitudes east of the west edge's, across the antimeridian too (179°E to 181°, not -179°);
    // NaN where a point has none (the bisection and edgeTicks pass it by).
    const double westLon = lonLat(f.x0, f.y0)->lonDeg;
    const auto unwrapped = [westLon](double lon) { return lon < westLon - 180 ? lon + 360 : lon; };
    const auto lonAt = [&](double y) {
        return [&, y](double x) {
            const auto g = lonLat(x, y);
            return g ? unwrapped(g->lonDeg) : std::nan("");
        };
    };
    const auto latAt = [&](double x) {
        return [&, x](double y) {
            const auto g = lonLat(x, y);
            return g ? g->latDeg : std::nan("");
        };
    };
    const double lonSpan = std::max(lonAt(f.y0)(f.x1), lonAt(f.y1)(f.x1)) - std::min(westLon, lonAt(f.y1)(f.x0));
    const double latSpan = std::max(latAt(f.x0)(f.y1), latAt(f.x1)(f.y1)) - std::min(latAt(f.x0)(f.y0), latAt(f.x1)(f.y0));
    const double lonStep = emit::graticuleStepDeg(lonSpan * 5 / mostX);
    const double latStep = emit::graticuleStepDeg(latSpan * 5 / mostY);
    const auto lonLabel = [lonStep](double v) { return emit::graticuleLabel(v > 180 ? v - 360 : v, true, lonStep); };
    const auto latLabel = [latStep](double v) { return emit::graticuleLabel(v, false, latStep); };
    const int lonTicks = frameTicksPerAnnotation(lonStep, true), latTicks = frameTicksPerAnnotation(latStep, true);
    edgeTicks(Side::Bottom, f.x0, f.x1, lonAt(f.y0), lonStep, lonTicks, lonLabel, f);
    edgeTicks(Side::Top, f.x0, f.x1, lonAt(f.y1), lonStep, lonTicks, lonLabel, f);
    edgeTicks(Side::Left, f.y0, f.y1, latAt(f.x0), latStep, latTicks, latLabel, f);
    edgeTicks(Side::Right, f.y0, f.y1, latAt(f.x1), latStep, latTicks, latLabel, f);
    return f;
}

// The widest annotation of the bottom and top edges, in characters.
size_t widestAcross(const MapFrameTicks& f) {
    size_t widest = 0;
    for (const auto& t : f.ticks)
        if (annotate::MapFrame::alongX(t.side)) widest = std::max(widest, charactersOf(t.label));
    return widest;
}

}  // namespace

std::optional<MapFrameTicks> mapFrameTicks(const scene::SceneSpec& spec, const geo::GeoGrid& net, Diagnostics& diags) {
    const int W = spec.render.width, H = spec.render.height;
    if (!spec.overlay.frame || !annotate::overlaysWanted(spec.overlay, W)) return std::nullopt;
    // At most five annotations an edge, fewer where they would not fit: the map's size on the still
    // is known before the camera (the room the first ticks leave, filled), and an annotation takes
    // its width and a half along the bottom and top, two and a half lines of text up the sides.
    const auto first = ticksWithin(spec, net, 5, 5, diags);
    if (!first) return std::nullopt;
    const auto [left, top, right, bottom] =
        annotate::mapFrameInset(spec.overlay, W, H, first->widestLabelChars());
    if (W - left - right < 0.2 * W || H - top - bottom < 0.2 * H) {
        diags.error(spec.overlay.locs.at("overlay.frame"),
                    fmt::format("overlay.frame: the annotations and the furniture leave the map {:.0f} x {:.0f} px of "
                                "the {} x {} still, less than a fifth of it: lower overlay.text_scale, turn the "
                                "legend off, or make the still larger",
                                std::max(0.0, W - left - right), std::max(0.0, H - top - bottom), W, H));
        return std::nullopt;
    }
    const double spanX = first->x1 - first->x0, spanY = first->y1 - first->y0;
    const double pxPerM = std::min((W - left - right) / spanX, (H - top - bottom) / spanY);
    const double textPx = annotate::frameTextPx(annotate::furnitureUnitPx(spec.overlay, W, H));
    const double acrossPx = 1.5 * annotate::kDigitWidthEm * textPx * double(std::max<size_t>(widestAcross(*first), 1));
    const double upPx = 2.5 * annotate::kLineHeightEm * textPx;
    const auto most = [](double px, double each) {
        const double n = px / each;
        return std::isfinite(n) ? std::clamp(int(std::floor(n)), 1, 5) : 5;
    };
    return ticksWithin(spec, net, most(pxPerM * spanX, acrossPx), most(pxPerM * spanY, upPx), diags);
}

emit::FrameInsetPx frameInsetOf(const scene::SceneSpec& spec, const std::optional<MapFrameTicks>& ticks) {
    if (!ticks) return {};
    return annotate::mapFrameInset(spec.overlay, spec.render.width, spec.render.height, ticks->widestLabelChars());
}

annotate::MapFrame mapFrameOnImage(const MapFrameTicks& ticks, const emit::ScenePlacement& where,
                                   const emit::CameraView& view, int widthPx, int heightPx) {
    const double z = where.zMinM;
    const auto onImage = [&](double x, double y) {
        return emit::projectToImage(view, where.scenePoint({x, y, z}), widthPx, heightPx);
    };
    const auto topLeft = onImage(ticks.x0, ticks.y1), bottomRight = onImage(ticks.x1, ticks.y0);
    annotate::MapFrame frame;
    frame.map = {topLeft[0], topLeft[1], bottomRight[0], bottomRight[1]};
    for (const MapFrameTicks::Tick& t : ticks.ticks) {
        const bool alongX = annotate::MapFrame::alongX(t.side);
        const auto p = alongX ? onImage(t.atM, t.side == Side::Bottom ? ticks.y0 : ticks.y1)
                              : onImage(t.side == Side::Left ? ticks.x0 : ticks.x1, t.atM);
        frame.ticks.push_back({t.side, alongX ? p[0] : p[1], t.label});
    }
    return frame;
}

}  // namespace relief
