#include "pipeline/film_flyover.h"

#include <algorithm>

#include <fmt/format.h>

#include "core/number_format.h"
#include "film/flyover.h"
#include "geo/normalize.h"
#include "geo/vector_file.h"

namespace relief {

namespace {

// The terrain's extent in degrees, for messages: "lon 174.7611 .. 174.7683, lat -36.8800 .. -36.8720".
std::string extentInDegrees(const geo::GeoGrid& g) {
    double lon0 = 1e9, lon1 = -1e9, lat0 = 1e9, lat1 = -1e9;
    for (const double x : {g.x0, g.xMax()})
        for (const double y : {g.y0, g.yMax()})
            if (const auto p = geo::reverse(g.frame, {x, y, 0})) {
                lon0 = std::min(lon0, p->lonDeg), lon1 = std::max(lon1, p->lonDeg);
                lat0 = std::min(lat0, p->latDeg), lat1 = std::max(lat1, p->latDeg);
            }
    return fmt::format("lon {:.4f} .. {:.4f}, lat {:.4f} .. {:.4f}", lon0, lon1, lat0, lat1);
}

// The path's points in the frame, each on the terrain; what they are called in messages.
struct PathPoints {
    std::vector<GeoPoint> geo;
    const char* key;   ///< "animation.waypoints" or "animation.track"
    const char* name;  ///< "waypoint" or "vertex"
};

std::optional<PathPoints> pathPoints(const scene::AnimationSpec& a, Diagnostics& diags) {
    const auto& fly = a.flyover;
    if (!fly.waypoints.empty()) return PathPoints{fly.waypoints, "animation.waypoints", "waypoint"};
    const std::string shown = fly.trackAsWritten;
    auto line = geo::firstLineOf(fly.track, fly.trackLayer, a.locs.at("animation.track"), diags);
    if (!line) return std::nullopt;
    // Consecutive repeats (a GPS standing still) are one point of the path.
    line->erase(
        std::unique(line->begin(), line->end(),
                    [](const GeoPoint& p, const GeoPoint& q) { return p.lonDeg == q.lonDeg && p.latDeg == q.latDeg; }),
        line->end());
    if (line->size() < 2) {
        diags.error(a.locs.at("animation.track"),
                    fmt::format("animation.track: the line in {} has one place only: a path needs two or more", shown));
        return std::nullopt;
    }
    return PathPoints{std::move(*line), "animation.track", "vertex"};
}

std::optional<film::FlyoverPath> flyoverPath(const scene::AnimationSpec& a, const PathPoints& points,
                                             const geo::GeoGrid& surface, const film::Ground& ground,
                                             Diagnostics& diags) {
    const auto& fly = a.flyover;
    film::FlyoverPath path;
    // A track's heights are the ground's (a walk, a drive): the eye follows the ground above it.
    const bool ownHeights = fly.waypointHeights && !fly.heightAboveTerrainM;
    if (!ownHeights) path.aboveGroundM = fly.heightAboveTerrainM.value_or(ground.diagonal() / 20);
    path.lookAheadM = fly.lookAheadM;
    for (size_t i = 0; i < points.geo.size(); ++i) {
        GeoPoint g = points.geo[i];
        if (!ownHeights) g.heightM = 0;
        const auto p = geo::forward(surface.frame, g);
        if (!p || !ground.covers(p->x, p->y)) {
            diags.error(a.locs.at(points.key),
                        fmt::format("{}: {} {} (lon {}, lat {}) is off the terrain ({}): a flyover's waypoints and "
                                    "track lie over the terrain",
                                    points.key, points.name, i + 1, formatShortest(g.lonDeg), formatShortest(g.latDeg),
                                    extentInDegrees(surface)));
            return std::nullopt;
        }
        path.points.push_back(*p);
    }
    if (fly.lookAt) {
        path.lookAtM = geo::forward(surface.frame, *fly.lookAt);
        if (!path.lookAtM) {
            diags.error(a.locs.at("animation.look_at"), "animation.look_at cannot be placed in the terrain's frame");
            return std::nullopt;
        }
    }
    return path;
}

std::string lonLatHeightText(const GeoPoint& g) {
    return fmt::format("[{}, {}, {}]", formatShortest(g.lonDeg), formatShortest(g.latDeg), formatShortest(g.heightM));
}

}  // namespace

std::optional<std::vector<scene::SceneOverrides>> flyoverKeys(const scene::AnimationSpec& a,
                                                              const geo::GeoGrid& surface,
                                                              const std::vector<size_t>& frames, Diagnostics& diags) {
    const film::Ground ground(surface);
    const auto points = pathPoints(a, diags);
    if (!points) return std::nullopt;
    const auto path = flyoverPath(a, *points, surface, ground, diags);
    if (!path) return std::nullopt;
    const auto cameras = film::flyoverCameras(*path, a.frames, ground);
    std::vector<scene::SceneOverrides> keys;
    for (const size_t k : frames) {
        const Vec3& eye = cameras[k].eyeM;
        const double groundZ = ground.highestAt(eye.x, eye.y);
        const auto eyeGeo = geo::reverse(surface.frame, eye);
        // Only an eye at the waypoints' own heights can be under the ground: above it, it is placed over its highest.
        if (!eyeGeo || !(eye.z > groundZ)) {
            const auto groundGeo = geo::reverse(surface.frame, {eye.x, eye.y, groundZ});
            diags.error(a.locs.at(points->key),
                        fmt::format("{}: at frame {} the eye (lon {:.6f}, lat {:.6f}, {:.1f} m) is not above the "
                                    "ground there ({:.1f} m): raise the waypoints near it, or give "
                                    "height_above_terrain_m",
                                    points->key, k + 1, eyeGeo ? eyeGeo->lonDeg : 0.0, eyeGeo ? eyeGeo->latDeg : 0.0,
                                    eyeGeo ? eyeGeo->heightM : eye.z, groundGeo ? groundGeo->heightM : groundZ));
            return std::nullopt;
        }
        const auto targetGeo = geo::reverse(surface.frame, cameras[k].targetM);
        if (!targetGeo) {
            diags.error(a.locs.at(a.flyover.lookAheadM ? "animation.look_ahead_m" : points->key),
                        fmt::format("animation: at frame {} the point looked at, {:.0f} m ahead along the path, has no "
                                    "longitude and latitude in the terrain's frame: give a shorter look_ahead_m",
                                    k + 1, length(cameras[k].targetM - eye)));
            return std::nullopt;
        }
        keys.push_back(
            {{"camera.position", lonLatHeightText(*eyeGeo)}, {"camera.look_at", lonLatHeightText(*targetGeo)}});
    }
    return keys;
}

}  // namespace relief
