#include "film/frames.h"

#include <cmath>
#include <numbers>
#include <sstream>

#include <fmt/format.h>
#include <toml++/toml.h>

#include "core/number_format.h"

namespace relief::film {

namespace {

// A string as TOML writes it: quoted and escaped, so that --set reads it as a string whatever it holds.
std::string tomlString(const std::string& s) {
    // A basic ("...") string: the --set reader takes TOML's forms that begin with a double quote.
    constexpr auto flags = toml::toml_formatter::default_flags & ~toml::format_flags::allow_literal_strings;
    const toml::value<std::string> value(s);
    std::ostringstream out;
    out << toml::toml_formatter(value, flags);
    return out.str();
}

// The fraction of the way frame k (0-based) of n is through a span that includes both ends.
double throughBothEnds(int k, int n) {
    return n > 1 ? double(k) / double(n - 1) : 0.0;
}

std::string orbitAzimuth(const scene::SceneSpec& scene, int k) {
    const scene::AnimationSpec& a = scene.animation;
    const double from = a.azimuthFromDeg.value_or(scene.look.camera.azimuthDeg);
    const double to = a.azimuthToDeg.value_or(from + 360);
    // A whole number of turns ends where it began: that frame is the next film's first.
    const double turns = (to - from) / 360;
    const bool wholeTurns = turns == std::round(turns);
    const double t = wholeTurns ? double(k) / double(a.frames) : throughBothEnds(k, a.frames);
    double az = std::fmod(from + (to - from) * t, 360.0);
    if (az < 0) az += 360;
    if (az >= 360 || az == 0) az = 0;  // no -0, and 360 is 0
    return formatShortest(az);
}

OffsetDateTime sunTimeOf(const scene::AnimationSpec::SunWindow& w, int k, int n) {
    const double span = double(w.to.utcSeconds - w.from.utcSeconds);
    return {w.from.utcSeconds + std::llround(span * throughBothEnds(k, n)), w.from.offsetMinutes};
}

std::string variedValue(const scene::AnimationSpec::Varied& v, int k, int n) {
    const double value = v.from + (v.to - v.from) * eased(throughBothEnds(k, n));
    return v.wholeNumber ? formatShortest(std::round(value)) : formatShortest(value);
}

// "2026-06-21 05:00:00 +01:00": the frame's time on the still.
std::string clockText(const OffsetDateTime& t) {
    std::string text = formatOffsetDateTime(t);
    text[10] = ' ';
    if (text.back() == 'Z') return text.substr(0, text.size() - 1) + " UTC";
    return text.substr(0, 19) + " " + text.substr(19);
}

}  // namespace

double eased(double t) {
    return (1 - std::cos(std::numbers::pi * t)) / 2;
}

bool changesOnlyTheView(const std::string& key) {
    for (const char* section : {"camera.", "lighting.", "atmosphere."})
        if (key.rfind(section, 0) == 0) return true;
    return key.rfind("overlay.", 0) == 0 && key != "overlay.contours";
}

std::vector<FrameSettings> frameSettings(const scene::SceneSpec& scene) {
    const scene::AnimationSpec& a = scene.animation;
    std::vector<FrameSettings> frames;
    for (int k = 0; k < a.frames; ++k) {
        FrameSettings f;
        f.number = k + 1;
        if (a.path == scene::CameraPath::Orbit) f.overrides.emplace_back("camera.azimuth_deg", orbitAzimuth(scene, k));
        std::string subtitle = scene.overlay.subtitle;
        auto addToSubtitle = [&](const std::string& text) { subtitle += (subtitle.empty() ? "" : "  ") + text; };
        if (a.sun) {
            f.sunTime = sunTimeOf(*a.sun, k, a.frames);
            f.overrides.emplace_back("lighting.datetime", tomlString(formatOffsetDateTime(*f.sunTime)));
            addToSubtitle(clockText(*f.sunTime));
        }
        if (a.counter) addToSubtitle(fmt::format("frame {} of {}", k + 1, a.frames));
        if (a.sun || a.counter) f.overrides.emplace_back("overlay.subtitle", tomlString(subtitle));
        for (const auto& v : a.vary) f.overrides.emplace_back(v.key, variedValue(v, k, a.frames));
        frames.push_back(std::move(f));
    }
    return frames;
}

}  // namespace relief::film
