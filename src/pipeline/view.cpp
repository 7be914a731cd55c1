// The view: the terrain placed in POV-Ray's scene, the camera, the sun
// (the scene's angles, or where it stood at a date over the terrain's centre).
#include "pipeline/view.h"

#include <cmath>

#include <fmt/format.h>

#include "core/date_time.h"
#include "annotate/overlay.h"
#include "core/text_escape.h"

namespace relief {

namespace {

// The sun: the scene's angles, or where it stood at [lighting] datetime over
// the terrain's centre. The scene's axes are the frame's grid, whose north is
// the meridian convergence away from true north.
std::optional<std::pair<emit::SunDirection, SunFacts>> sunOf(const scene::LookSpec& look,
                                                                        const geo::ControlNet& net, Diagnostics& diags) {
    const emit::SunDirection given{look.lighting.sunAzimuthDeg, look.lighting.sunAltitudeDeg};
    if (!look.lighting.sunTime)
        return std::pair{given, SunFacts{given.azimuthDeg, given.altitudeDeg, false, {}, 0, 0}};
    const auto placed = sunOverTerrain(net, look.lighting.sunTime->utcSeconds);
    if (!placed) {
        diags.error(look.lighting.locs.at("lighting.datetime"),
                    "lighting.datetime: the terrain's centre has no longitude and "
                    "latitude in its frame; give sun_azimuth_deg and "
                    "sun_altitude_deg instead");
        return std::nullopt;
    }
    const auto& [sun, centre] = *placed;
    const double cx = (net.x0 + net.xMax()) / 2, cy = (net.y0 + net.yMax()) / 2;
    if (!(sun.altitudeDeg > 0)) {
        diags.error(look.lighting.locs.at("lighting.datetime"),
                    fmt::format("lighting.datetime = \"{}\"{}: the sun is {:.1f} degrees below the horizon at the "
                                "terrain's centre (lon {:.4f}, lat {:.4f}); choose a time in daylight, or give "
                                "sun_azimuth_deg and sun_altitude_deg",
                                printableExcerpt(look.lighting.sunTimeText),
                                look.lighting.sunTime->offsetMinutes != 0
                                    ? " (" + formatUtc(look.lighting.sunTime->utcSeconds) + ")"
                                    : std::string(),
                                -sun.altitudeDeg, centre.lonDeg, centre.latDeg));
        return std::nullopt;
    }
    const double convergenceDeg = geo::gridConvergenceDeg(net.frame, cx, cy);
    return std::pair{emit::SunDirection{std::fmod(sun.azimuthDeg - convergenceDeg + 360, 360), sun.altitudeDeg},
                     SunFacts{sun.azimuthDeg, sun.altitudeDeg, true, look.lighting.sunTimeText, centre.lonDeg,
                                        centre.latDeg}};
}

}  // namespace

std::optional<View> resolveView(const scene::SceneSpec& spec, const geo::ControlNet& net, const geo::GeoGrid& refined,
                                Diagnostics& diags) {
    const auto points = emit::cameraPointsInFrame(spec.look.camera, net.frame, diags);
    if (!points) return std::nullopt;
    auto sun = sunOf(spec.look, net, diags);
    if (!sun) return std::nullopt;
    View v;
    const int errorsBefore = diags.errorCount();
    v.frameTicks = mapFrameTicks(spec, refined, diags);
    if (diags.errorCount() > errorsBefore) return std::nullopt;
    v.where = emit::placeTerrain(refined, spec.look);
    v.camera = emit::placeCamera(v.where, spec.look.camera, *points, spec.render, frameInsetOf(spec, v.frameTicks));
    v.metresPerPixel = annotate::metresPerPixelAtTarget(v.camera, v.where.metresPerUnit, spec.render.width);
    v.sun = sun->first;
    v.sunRecord = sun->second;
    return v;
}

std::optional<std::pair<geo::SunPosition, GeoPoint>> sunOverTerrain(const geo::ControlNet& net,
                                                                    std::int64_t utcSeconds) {
    const double cx = (net.x0 + net.xMax()) / 2, cy = (net.y0 + net.yMax()) / 2;
    const auto centre = geo::reverse(net.frame, Vec3{cx, cy, 0});
    if (!centre) return std::nullopt;
    return std::pair{geo::sunPosition(centre->lonDeg, centre->latDeg, utcSeconds), *centre};
}

}  // namespace relief
