// [animation]: what moves in relief animate's frames.
#include <cmath>

#include <fmt/format.h>

#include "core/input_file.h"
#include "core/number_format.h"
#include "core/text_escape.h"
#include "scene/read_sections.h"

namespace relief::scene {

namespace {

// sun = { from = ..., to = ... }: two instants with their offsets, the first earlier.
std::optional<AnimationSpec::SunWindow> sunWindowOf(Section& s) {
    s.markKnown("sun");
    const toml::node* n = s.find("sun");
    if (!n) return std::nullopt;
    const toml::table* t = n->as_table();
    const auto text = [&](const char* key) { return t && t->get(key) ? dateTimeText(*t->get(key)) : std::nullopt; };
    const auto from = text("from"), to = text("to");
    bool onlyFromTo = t != nullptr;
    if (t)
        for (auto&& [k, v] : *t) onlyFromTo = onlyFromTo && (k.str() == "from" || k.str() == "to");
    if (!from || !to || !onlyFromTo) {
        s.error("sun",
                "animation.sun must be { from = \"2026-06-21T05:00:00+01:00\", to = \"2026-06-21T21:00:00+01:00\" }: "
                "two date-times with their UTC offsets");
        return std::nullopt;
    }
    AnimationSpec::SunWindow w;
    for (auto [txt, out, name] : {std::tuple{&*from, &w.from, "from"}, std::tuple{&*to, &w.to, "to"}}) {
        std::string why = "it must be a date and time with its UTC offset";
        const auto parsed = parseOffsetDateTime(*txt, why);
        if (!parsed) {
            s.error("sun", fmt::format("animation.sun.{} = \"{}\": {}", name, printableExcerpt(*txt), why));
            return std::nullopt;
        }
        *out = *parsed;
    }
    if (!(w.to.utcSeconds > w.from.utcSeconds)) {
        s.error("sun", fmt::format("animation.sun: to = \"{}\" must be later than from = \"{}\"", printableExcerpt(*to),
                                   printableExcerpt(*from)));
        return std::nullopt;
    }
    return w;
}

// vary = { "section.key" = [from, to], ... }: keys the other sections read, numbers at both ends.
std::vector<AnimationSpec::Varied> variedKeysOf(Section& s, SceneSpec& scene) {
    s.markKnown("vary");
    std::vector<AnimationSpec::Varied> out;
    const toml::node* n = s.find("vary");
    if (!n) return out;
    const toml::table* t = n->as_table();
    if (!t || t->empty()) {
        s.error("vary",
                "animation.vary must be a table of keys and their two values, e.g. "
                "{ \"vertical.exaggeration\" = [1, 3] }");
        return out;
    }
    for (auto&& [k, v] : *t) {
        const std::string key(k.str());
        const auto dot = key.find('.');
        const std::string section = key.substr(0, dot == std::string::npos ? 0 : dot);
        bool known = false, wholeNumber = false, many = false;
        for (const auto& reader : sectionReaders())
            if (section == reader.name && section != "animation") {
                many = reader.many;  // its locations() would add a table to the scene: never asked
                if (many) continue;
                known = reader.locations(scene).knows(key);
                wholeNumber = reader.locations(scene).wholeNumbers.count(key) > 0;
            }
        const toml::array* a = v.as_array();
        const auto end = [&](size_t i) { return a && a->size() == 2 ? (*a)[i].value<double>() : std::nullopt; };
        if (many) {
            s.error("vary", fmt::format("animation.vary: [[{}]] keys cannot be varied: there may be many [[{}]] "
                                        "tables; vary a key of another section",
                                        section, section));
        } else if (!known) {
            s.error("vary", fmt::format("animation.vary: \"{}\" is not a key of the scene's sections (write "
                                        "\"section.key\", e.g. \"camera.elevation_deg\")",
                                        printableExcerpt(key)));
        } else if (!end(0) || !end(1)) {
            s.error("vary", fmt::format("animation.vary: \"{}\" must be given two numbers, [from, to]", key));
        } else {
            out.push_back({key, *end(0), *end(1), wholeNumber});
        }
    }
    return out;
}

void checkOrbit(Section& s, const SceneSpec& scene, AnimationSpec& a) {
    if (auto v = s.number("azimuth_from_deg", 0, 360, "degrees (compass bearing)", false, true)) a.azimuthFromDeg = *v;
    if (auto v = s.number("azimuth_to_deg", -3600, 3600, "degrees (compass bearing; past 360 for more turns)"))
        a.azimuthToDeg = *v;
    for (const char* key : {"azimuth_from_deg", "azimuth_to_deg"})
        if (a.path != CameraPath::Orbit && a.locs.has(std::string("animation.") + key))
            s.warning(key, fmt::format("animation.{} is not used: only path = \"orbit\" turns the camera", key));
    if (a.path != CameraPath::Orbit) return;
    if (scene.look.camera.position)
        s.error("path",
                "animation.path = \"orbit\" turns the camera around the terrain, but camera.position places "
                "the eye: remove camera.position, or leave the path out");
    if (a.azimuthFromDeg && a.azimuthToDeg && *a.azimuthFromDeg == *a.azimuthToDeg)
        s.error("azimuth_to_deg", "animation.azimuth_to_deg is azimuth_from_deg: the orbit would not move");
    for (const auto& v : a.vary)
        if (v.key == "camera.azimuth_deg")
            s.error("vary",
                    "animation.vary: \"camera.azimuth_deg\" is what path = \"orbit\" turns: give "
                    "azimuth_from_deg and azimuth_to_deg instead");
}

constexpr size_t kMaxWaypoints = 10000;

// waypoints = [[lon, lat, height_m], ...] or [[lon, lat], ...]: two or more, all alike, no two in a row the same.
void readWaypoints(Section& s, AnimationSpec::Flyover& fly) {
    s.markKnown("waypoints");
    const toml::node* n = s.find("waypoints");
    if (!n) return;
    static constexpr std::string_view kWhat =
        "a list of [lon, lat, height_m] (metres above sea level) or of [lon, lat] (with "
        "height_above_terrain_m), e.g. [[174.764, -36.871, 300], [174.766, -36.879, 320]]";
    const toml::array* list = n->as_array();
    if (!list || list->size() > kMaxWaypoints) {
        s.error("waypoints", fmt::format("animation.waypoints must be {}, at most {}", kWhat, kMaxWaypoints));
        return;
    }
    size_t arity = 0;
    for (size_t i = 0; i < list->size(); ++i) {
        const toml::array* p = (*list)[i].as_array();
        const size_t size = p ? p->size() : 0;
        std::array<double, 3> v{0, 0, 0};
        bool ok = (size == 2 || size == 3) && (arity == 0 || size == arity);
        for (size_t k = 0; ok && k < size; ++k) {
            const auto d = (*p)[k].value<double>();
            ok = d && std::isfinite(*d);
            if (ok) v[k] = *d;
        }
        ok = ok && std::fabs(v[0]) <= 180 && std::fabs(v[1]) <= 90 && v[2] >= -11100 && v[2] <= 1e7;
        if (!ok) {
            s.error("waypoints", fmt::format("animation.waypoints: waypoint {} must be like the first, {} (degrees "
                                             "in [-180, 180] and [-90, 90], metres in [-11100, 1e7])",
                                             i + 1, kWhat));
            return;
        }
        arity = size;
        fly.waypoints.push_back({v[0], v[1], v[2]});
    }
    fly.waypointHeights = arity == 3;
    if (fly.waypoints.size() < 2) {
        s.error("waypoints", fmt::format("animation.waypoints gives {} point{}: a path needs two or more",
                                         fly.waypoints.size(), fly.waypoints.size() == 1 ? "" : "s"));
        fly.waypoints.clear();
        return;
    }
    for (size_t i = 1; i < fly.waypoints.size(); ++i) {
        const GeoPoint &a = fly.waypoints[i - 1], &b = fly.waypoints[i];
        if (a.lonDeg == b.lonDeg && a.latDeg == b.latDeg) {
            s.error("waypoints", fmt::format("animation.waypoints: waypoints {} and {} are one place (lon {}, lat {}): "
                                             "leave one out",
                                             i, i + 1, formatShortest(a.lonDeg), formatShortest(a.latDeg)));
            fly.waypoints.clear();
            return;
        }
    }
}

// track = "walk.gpx": a vector file beside the scene; its line is read by geo when the film is made.
void readTrack(Section& s, const SceneFile& f, AnimationSpec::Flyover& fly) {
    if (auto layer = s.string("track_layer")) fly.trackLayer = *layer;
    if (auto track = s.fileBesideScene("track", f.path, fly.trackAsWritten)) fly.track = *track;
}

constexpr const char* kFlyoverKeys[] = {"waypoints", "track",       "track_layer", "height_above_terrain_m",
                                        "look_at",   "look_ahead_m"};

void readFlyover(Section& s, const SceneFile& f, AnimationSpec& a) {
    AnimationSpec::Flyover& fly = a.flyover;
    readWaypoints(s, fly);
    readTrack(s, f, fly);
    if (auto v = s.number("height_above_terrain_m", 0, 1e6, "metres", true)) fly.heightAboveTerrainM = *v;
    if (auto v = s.number("look_ahead_m", 0, 1e7, "metres", true)) fly.lookAheadM = *v;
    fly.lookAt = s.lonLatHeight("look_at");
    if (a.path != CameraPath::Flyover) {
        for (const char* key : kFlyoverKeys)
            if (s.find(key))
                s.warning(key, fmt::format("animation.{} is not used: only path = \"flyover\" follows a path", key));
        return;
    }
    const bool waypoints = s.find("waypoints"), track = s.find("track");
    if (waypoints == track)
        s.error("path", waypoints ? "animation: give waypoints or track, not both"
                                  : "animation.path = \"flyover\" needs the path: waypoints = [[lon, lat, height_m], "
                                    "...] or track = \"file.gpx\" (any vector file GDAL reads)");
    if (fly.waypointHeights && fly.heightAboveTerrainM)
        s.warning("height_above_terrain_m",
                  "animation.waypoints give heights, and height_above_terrain_m is used instead of them");
    if (fly.lookAt && fly.lookAheadM)
        s.warning("look_ahead_m", "animation.look_ahead_m is not used: look_at fixes where the camera looks");
    if (!s.find("track_layer") || track) return;
    s.warning("track_layer", "animation.track_layer is not used: there is no track");
}

}  // namespace

void readAnimation(Section& s, const SceneFile& f, SceneSpec& scene) {
    AnimationSpec& a = scene.animation;
    a.present = s.present();
    if (!a.present) return;
    s.require("frames", "the number of frames, e.g. frames = 120");
    if (auto v = s.integer("frames", 1, AnimationSpec::kMaxFrames, "frames")) a.frames = *v;
    if (auto v = s.number("fps", 1, 120, "frames a second")) a.fps = *v;
    if (auto p = s.named<CameraPath>("path")) a.path = *p;
    a.sun = sunWindowOf(s);
    if (auto v = s.boolean("skip_night")) a.skipNight = *v;
    if (a.skipNight && !a.sun) s.warning("skip_night", "animation.skip_night is not used: there is no animation.sun");
    if (auto v = s.boolean("counter")) a.counter = *v;
    a.vary = variedKeysOf(s, scene);
    checkOrbit(s, scene, a);
    readFlyover(s, f, a);
    if (a.path == CameraPath::Flyover && scene.overlay.frame)
        s.error("path", "animation.path = \"flyover\" puts the eye among the terrain, and overlay.frame draws a map's "
                        "frame around a view from straight above: remove one of them");
    if (a.path == CameraPath::Still && !s.find("sun") && !s.find("vary"))
        s.error("path",
                "[animation] moves nothing: give path = \"orbit\" or \"flyover\", sun = { from, to } or "
                "vary = { ... }");
}

}  // namespace relief::scene
