#include "annotate/facts.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <fmt/format.h>

#include "core/number_format.h"
#include "emit/mesh.h"

namespace relief::annotate {

namespace {

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

ScaleBar chooseScaleBar(double metresPerPixel, int widthPx, const scene::OverlaySpec& spec) {
    using scene::kFootM, scene::kMileM;
    ScaleBar bar;
    if (!(metresPerPixel > 0) || widthPx <= 0) return bar;
    const double wanted = 0.2 * widthPx * metresPerPixel;
    if (spec.scaleBarUnit) {
        bar.metres = spec.scaleBarLength * spec.scaleBarUnit->metres;
        bar.label = formatShortest(spec.scaleBarLength) + " " + spec.scaleBarUnit->name;
    } else if (spec.scaleBarImperial && wanted >= kMileM) {
        const double miles = roundDown125(wanted / kMileM);
        bar.metres = miles * kMileM;
        bar.label = formatShortest(miles) + " mi";
    } else if (spec.scaleBarImperial) {
        const double feet = roundDown125(wanted / kFootM);
        bar.metres = feet * kFootM;
        bar.label = formatShortest(feet) + " ft";
    } else {
        bar.metres = roundDown125(wanted);
        bar.label = metresLabel(bar.metres);
    }
    bar.pixels = bar.metres / metresPerPixel;
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
    const double g = convergenceDeg * std::numbers::pi / 180;
    const double step = 1e-3 * view.radius;
    const SceneVec3 north{-std::sin(g) * step, 0, std::cos(g) * step};
    const auto a = emit::projectToImage(view, view.target, widthPx, heightPx);
    const auto b = emit::projectToImage(view, view.target + north, widthPx, heightPx);
    return std::atan2(b[0] - a[0], a[1] - b[1]) * 180 / std::numbers::pi;
}

double metresPerPixelAtTarget(const emit::CameraView& view, double metresPerUnit, int widthPx) {
    const double span = view.perspective ? 2 * length(view.target - view.eye) * view.tanHalfFov
                                         : view.orthoHeight * view.aspect;
    return span * metresPerUnit / widthPx;
}

double furnitureUnitPx(const scene::OverlaySpec& spec, int widthPx, int heightPx) {
    return std::min(widthPx, heightPx * 4 / 3) / 100.0 * spec.textScale;
}

std::array<double, 4> mapFrameInset(const scene::OverlaySpec& spec, int widthPx, int heightPx,
                                    size_t widestLabelChars) {
    const double u = furnitureUnitPx(spec, widthPx, heightPx);
    // The annotations' band: a tick, a gap, the text and a gap; the still's edge a unit beyond.
    const double tick = kFrameTickUnits * u, gap = 0.5 * u, text = frameTextPx(u);
    const double across = 1 * u + tick + gap + kLineHeightEm * text + gap;
    const double beside = 1 * u + tick + gap + kDigitWidthEm * text * double(widestLabelChars) + gap;
    const bool title = !spec.title.empty(), subtitle = !spec.subtitle.empty();
    // The furniture's own room, from the sizes paint.cpp draws it at.
    const double top = (title || subtitle) ? 2.2 * u + (title ? 4.6 * u : 0) + (subtitle ? 3.1 * u : 0) : 0;
    const double right = spec.legend ? 18 * u : 0;
    const double bottom = spec.scaleBar ? 10 * u : 3.5 * u;  // the credits, at least
    return {beside, across + top, beside + right, across + bottom};
}

bool overlaysWanted(const scene::OverlaySpec& spec, int widthPx) {
    using E = scene::OverlaySpec::Enabled;
    return spec.enabled == E::On || (spec.enabled == E::Auto && widthPx >= scene::OverlaySpec::kMinAutoWidthPx);
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
    f.mapFurniture = !view.wide;
    if (view.wide) return f;  // no pinhole: nothing projects onto it as below
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
