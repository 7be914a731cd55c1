#include "scene/section.h"

#include <cmath>

#include <fmt/format.h>

#include "core/input_file.h"
#include "core/number_format.h"
#include "core/text_distance.h"
#include "core/text_escape.h"
#include "core/utf8_record.h"
#include "scene/read_scene.h"

namespace relief::scene {

SourceLoc locOf(const std::string& file, const toml::source_region& r) {
    // A value from --set was parsed from the command line, not the file: no line of it.
    if (!r.path) return {file, 0, 0};
    return {file, static_cast<int>(r.begin.line), static_cast<int>(r.begin.column)};
}

namespace {

std::string joinQuoted(const std::vector<std::string>& names) {
    std::string out;
    for (size_t i = 0; i < names.size(); ++i) out += fmt::format("{}\"{}\"", i ? ", " : "", names[i]);
    return out;
}

}  // namespace

void Section::recordLocations(KeyLocations& locs) {
    locs_ = &locs;
    locs.file = file_;
    locs.sections[name_] = sectionLoc_;
    if (!table_) return;
    for (auto&& [k, v] : *table_) locs.keys[qualified(std::string(k.str()))] = locOf(file_, v.source());
}

SourceLoc Section::keyLoc(const std::string& key) const {
    if (const toml::node* n = find(key)) return locOf(file_, n->source());
    return sectionLoc_;
}

std::optional<double> Section::number(const std::string& key, double lo, double hi, std::string_view unit,
                                      bool loOpen, bool hiOpen) {
    known_.insert(key);
    const toml::node* n = find(key);
    if (!n) return std::nullopt;
    std::optional<double> v;
    if (auto i = n->value_exact<int64_t>()) v = static_cast<double>(*i);
    else if (auto d = n->value_exact<double>()) v = *d;
    else if (auto s = n->value_exact<std::string>()) v = parseFraction(*s);
    if (!v) {
        error(key, fmt::format("{} must be a number{}{}", qualified(key), unit.empty() ? "" : " in ", unit));
        return std::nullopt;
    }
    const bool belowLo = loOpen ? !(*v > lo) : !(*v >= lo);
    const bool aboveHi = hiOpen ? !(*v < hi) : !(*v <= hi);
    if (!std::isfinite(*v) || belowLo || aboveHi) {
        error(key, fmt::format("{} = {} is outside {}{}, {}{}{}{}", qualified(key), formatShortest(*v),
                               loOpen ? "(" : "[", formatShortest(lo), formatShortest(hi), hiOpen ? ")" : "]",
                               unit.empty() ? "" : " ", unit));
        return std::nullopt;
    }
    return v;
}

std::optional<int> Section::integer(const std::string& key, int lo, int hi, std::string_view unit) {
    known_.insert(key);
    integers_.insert(key);
    const toml::node* n = find(key);
    if (!n) return std::nullopt;
    auto i = n->value_exact<int64_t>();
    if (!i) {
        // A whole number too large for 64 bits (from --set) is out of range, not a non-integer.
        if (const auto d = n->value_exact<double>(); d && std::isfinite(*d) && *d == std::floor(*d)) {
            error(key, fmt::format("{} = {} is outside [{}, {}]{}{}", qualified(key), formatShortest(*d), lo, hi,
                                   unit.empty() ? "" : " ", unit));
            return std::nullopt;
        }
        error(key, fmt::format("{} must be an integer{}{}", qualified(key), unit.empty() ? "" : " number of ", unit));
        return std::nullopt;
    }
    if (*i < lo || *i > hi) {
        error(key, fmt::format("{} = {} is outside [{}, {}]{}{}", qualified(key), *i, lo, hi, unit.empty() ? "" : " ",
                               unit));
        return std::nullopt;
    }
    return static_cast<int>(*i);
}

std::optional<bool> Section::boolean(const std::string& key) {
    known_.insert(key);
    const toml::node* n = find(key);
    if (!n) return std::nullopt;
    auto b = n->value_exact<bool>();
    if (!b) error(key, fmt::format("{} must be true or false", qualified(key)));
    return b;
}

std::optional<std::string> Section::string(const std::string& key) {
    known_.insert(key);
    const toml::node* n = find(key);
    if (!n) return std::nullopt;
    auto s = n->value_exact<std::string>();
    if (!s) error(key, fmt::format("{} must be a string", qualified(key)));
    return s;
}

std::optional<std::string> Section::text(const std::string& key) {
    auto s = string(key);
    if (s && s->size() > kMaxTextBytes) {
        error(key, fmt::format("{} is {} bytes long, more than the {} a text of the still may be", qualified(key),
                               s->size(), kMaxTextBytes));
        return std::nullopt;
    }
    // A TOML file's strings are UTF-8; --set's and a scene made for a file named in Latin-1 may not be.
    if (s && !isUtf8(*s)) {
        warnNotUtf8(diags_, keyLoc(key), qualified(key));
        s = utf8Replaced(*s);
    }
    return s;
}

std::optional<std::string> Section::choice(const std::string& key, const std::vector<std::string>& choices) {
    auto s = string(key);
    if (!s) return std::nullopt;
    for (const auto& c : choices)
        if (c == *s) return s;
    error(key, fmt::format("{} = \"{}\" is not one of {}{}", qualified(key), terminalText(*s, 100),
                           joinQuoted(choices), s->size() > 100 ? std::string() : didYouMean(*s, choices)));
    return std::nullopt;
}

std::optional<std::array<double, 4>> Section::box(const std::string& key, std::string_view what) {
    const auto out = numbers<4>(key, what);
    if (!out) return std::nullopt;
    // TOML has inf and nan; no extent is either, and none reaches past the Earth (1e8 m).
    for (const double v : *out)
        if (!std::isfinite(v) || std::fabs(v) > 1e8) {
            error(key, fmt::format("{} = [{}, {}, {}, {}] must be finite numbers within ±1e8 (a frame's metres "
                                   "or degrees)",
                                   qualified(key), (*out)[0], (*out)[1], (*out)[2], (*out)[3]));
            return std::nullopt;
        }
    return out;
}

std::optional<GeoPoint> Section::lonLatHeight(const std::string& key) {
    static constexpr std::string_view kWhat =
        "[lon, lat, height_m]: degrees in [-180, 180] and [-90, 90], metres above sea level in [-11100, 1e7]";
    const auto out = numbers<3>(key, kWhat);
    if (!out) return std::nullopt;
    const auto [lon, lat, h] = *out;
    if (!(std::fabs(lon) <= 180 && std::fabs(lat) <= 90 && h >= -11100 && h <= 1e7)) {
        error(key, fmt::format("{} must be {}", qualified(key), kWhat));
        return std::nullopt;
    }
    return GeoPoint{lon, lat, h};
}

void Section::require(const std::string& key, std::string_view what) {
    if (!find(key)) diags_.error(sectionLoc_, fmt::format("missing {}: {}", qualified(key), what));
}

void Section::finish() {
    if (locs_) {
        for (const auto& key : known_) locs_->known.insert(qualified(key));
        for (const auto& key : integers_) locs_->wholeNumbers.insert(qualified(key));
    }
    if (!table_) return;
    const std::vector<std::string> knownList(known_.begin(), known_.end());
    for (auto&& [k, v] : *table_) {
        const std::string key(k.str());
        if (known_.count(key)) continue;
        diags_.error(locOf(file_, k.source()), fmt::format("unknown key {}{}", qualified(key), didYouMean(key, knownList)));
    }
}

std::optional<std::filesystem::path> Section::fileBesideScene(const std::string& key,
                                                              const std::filesystem::path& sceneFile,
                                                              std::string& asWritten) {
    const auto text = string(key);
    if (!text) return std::nullopt;
    asWritten = *text;
    const std::filesystem::path path = sceneFile.parent_path() / *text;
    if (const std::string problem = inputFileProblem(path); problem == "no such file")
        error(key, fmt::format("{}: file \"{}\" not found (looked for {}; the path is relative to the scene file)",
                               qualified(key), printableExcerpt(*text, 200), printableExcerpt(path.string(), 200)));
    else if (!problem.empty())
        error(key, fmt::format("{} = \"{}\": {}", qualified(key), printableExcerpt(*text, 200), problem));
    else
        return path;
    return std::nullopt;
}

}  // namespace relief::scene
