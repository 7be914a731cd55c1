// [animation]: what moves in relief animate's frames.
#include <cmath>

#include <fmt/format.h>

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
        bool known = false, wholeNumber = false;
        for (const auto& reader : sectionReaders())
            if (section == reader.name && section != "animation") {
                known = reader.locations(scene).knows(key);
                wholeNumber = reader.locations(scene).wholeNumbers.count(key) > 0;
            }
        const toml::array* a = v.as_array();
        const auto end = [&](size_t i) { return a && a->size() == 2 ? (*a)[i].value<double>() : std::nullopt; };
        if (!known) {
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

}  // namespace

void readAnimation(Section& s, const SceneFile&, SceneSpec& scene) {
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
    a.vary = variedKeysOf(s, scene);
    checkOrbit(s, scene, a);
    if (a.path == CameraPath::Still && !s.find("sun") && !s.find("vary"))
        s.error("path", "[animation] moves nothing: give path = \"orbit\", sun = { from, to } or vary = { ... }");
}

}  // namespace relief::scene
