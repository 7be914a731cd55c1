#include "scene/read_scene.h"

#include <algorithm>
#include <array>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <set>

#include <fmt/format.h>
#include <openssl/evp.h>
#include <toml++/toml.h>

#include "core/atomic_file.h"
#include "core/input_file.h"
#include "core/number_format.h"
#include "core/text_distance.h"
#include "core/text_escape.h"
#include "scene/color_ramp.h"
#include "scene/cpt_palette.h"

namespace relief::scene {

SourceLoc KeyLocations::at(const std::string& qualifiedKey) const {
    if (auto k = keys.find(qualifiedKey); k != keys.end()) return k->second;
    const auto dot = qualifiedKey.find('.');
    if (auto sec = sections.find(qualifiedKey.substr(0, dot)); sec != sections.end()) return sec->second;
    return {file, 0, 0};
}

namespace {

SourceLoc locOf(const std::string& file, const toml::source_region& r) {
    // A value from --set was parsed from the command line, not the file: no line of it.
    if (!r.path) return {file, 0, 0};
    return {file, static_cast<int>(r.begin.line), static_cast<int>(r.begin.column)};
}

// The scene file's fingerprint for headers and sidecars: SHA-1 as upper-case hex.
std::string sha1Hex(std::string_view bytes) {
    unsigned char digest[EVP_MAX_MD_SIZE];
    unsigned int size = 0;
    if (!EVP_Digest(bytes.data(), bytes.size(), digest, &size, EVP_sha1(), nullptr)) return {};
    std::string hex;
    for (unsigned int i = 0; i < size; ++i) hex += fmt::format("{:02X}", digest[i]);
    return hex;
}

std::string quoteName(std::string_view s) { return fmt::format("\"{}\"", s); }

std::string joinQuoted(const std::vector<std::string>& names) {
    std::string out;
    for (size_t i = 0; i < names.size(); ++i) out += (i ? ", " : "") + quoteName(names[i]);
    return out;
}

// One [section] of the scene file. Each getter marks its key as known,
// checks the type and the range, and reports with the key's location.
// Keys left unmarked are reported as unknown by finish().
class Section {
public:
    Section(const toml::table* table, std::string name, const std::string& file,
            Diagnostics& diags, SourceLoc sectionLoc)
        : table_(table), name_(std::move(name)), file_(file), diags_(diags),
          sectionLoc_(std::move(sectionLoc)) {}

    /// Records the section's and every key's location (the value's) in `locs`.
    void recordLocations(KeyLocations& locs) {
        locs_ = &locs;
        locs.file = file_;
        locs.sections[name_] = sectionLoc_;
        if (!table_) return;
        for (auto&& [k, v] : *table_) locs.keys[qualified(std::string(k.str()))] = locOf(file_, v.source());
    }

    bool present() const { return table_ != nullptr; }
    const SourceLoc& loc() const { return sectionLoc_; }

    SourceLoc keyLoc(const std::string& key) const {
        if (const toml::node* n = find(key)) return locOf(file_, n->source());
        return sectionLoc_;
    }

    const toml::node* find(const std::string& key) const {
        return table_ ? table_->get(key) : nullptr;
    }

    // A number (integer, float, or a fraction string like "7/32") in [lo, hi].
    std::optional<double> number(const std::string& key, double lo, double hi,
                                 std::string_view unit, bool loOpen = false,
                                 bool hiOpen = false) {
        known_.insert(key);
        const toml::node* n = find(key);
        if (!n) return std::nullopt;
        std::optional<double> v;
        if (auto i = n->value_exact<int64_t>()) v = static_cast<double>(*i);
        else if (auto d = n->value_exact<double>()) v = *d;
        else if (auto s = n->value_exact<std::string>()) v = parseFraction(*s);
        if (!v) {
            error(key, fmt::format("{} must be a number{}{}", qualified(key),
                                   unit.empty() ? "" : " in ", unit));
            return std::nullopt;
        }
        const bool belowLo = loOpen ? !(*v > lo) : !(*v >= lo);
        const bool aboveHi = hiOpen ? !(*v < hi) : !(*v <= hi);
        if (!std::isfinite(*v) || belowLo || aboveHi) {
            error(key, fmt::format("{} = {} is outside {}{}, {}{}{}{}", qualified(key),
                                   formatShortest(*v), loOpen ? "(" : "[", formatShortest(lo),
                                   formatShortest(hi), hiOpen ? ")" : "]",
                                   unit.empty() ? "" : " ", unit));
            return std::nullopt;
        }
        return v;
    }

    std::optional<int> integer(const std::string& key, int lo, int hi, std::string_view unit) {
        known_.insert(key);
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
            error(key, fmt::format("{} must be an integer{}{}", qualified(key),
                                   unit.empty() ? "" : " number of ", unit));
            return std::nullopt;
        }
        if (*i < lo || *i > hi) {
            error(key, fmt::format("{} = {} is outside [{}, {}]{}{}", qualified(key), *i, lo, hi,
                                   unit.empty() ? "" : " ", unit));
            return std::nullopt;
        }
        return static_cast<int>(*i);
    }

    std::optional<bool> boolean(const std::string& key) {
        known_.insert(key);
        const toml::node* n = find(key);
        if (!n) return std::nullopt;
        auto b = n->value_exact<bool>();
        if (!b) error(key, fmt::format("{} must be true or false", qualified(key)));
        return b;
    }

    std::optional<std::string> string(const std::string& key) {
        known_.insert(key);
        const toml::node* n = find(key);
        if (!n) return std::nullopt;
        auto s = n->value_exact<std::string>();
        if (!s) error(key, fmt::format("{} must be a string", qualified(key)));
        return s;
    }

    // A text drawn on the still or written in the .pov header and sidecar (a
    // title, a credit line): at most kMaxTextBytes, since laying out megabytes
    // of text costs minutes and gigabytes, and shows nothing a still can hold.
    std::optional<std::string> text(const std::string& key) {
        auto s = string(key);
        if (s && s->size() > kMaxTextBytes) {
            error(key, fmt::format("{} is {} bytes long, more than the {} a text of the still may be", qualified(key),
                                   s->size(), kMaxTextBytes));
            return std::nullopt;
        }
        return s;
    }

    // A string that must be one of `choices`.
    std::optional<std::string> choice(const std::string& key,
                                      const std::vector<std::string>& choices) {
        auto s = string(key);
        if (!s) return std::nullopt;
        for (const auto& c : choices)
            if (c == *s) return s;
        error(key, fmt::format("{} = \"{}\" is not one of {}{}", qualified(key), terminalText(*s, 100),
                               joinQuoted(choices), s->size() > 100 ? std::string() : didYouMean(*s, choices)));
        return std::nullopt;
    }

    // N numbers in an array, or nullopt (and an error saying `what` they must be).
    template <size_t N>
    std::optional<std::array<double, N>> numbers(const std::string& key, std::string_view what) {
        known_.insert(key);
        const toml::node* n = find(key);
        if (!n) return std::nullopt;
        const toml::array* a = n->as_array();
        std::array<double, N> out{};
        bool ok = a && a->size() == N;
        for (size_t i = 0; ok && i < N; ++i) {
            if (auto d = (*a)[i].value<double>()) out[i] = *d;
            else ok = false;
        }
        if (!ok) {
            error(key, fmt::format("{} must be {}", qualified(key), what));
            return std::nullopt;
        }
        return out;
    }

    // Four numbers, e.g. an extent; `what` says which in the error.
    std::optional<std::array<double, 4>> box(const std::string& key, std::string_view what) {
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

    /// [lon, lat, height_m]: degrees within the globe, a height within
    /// -11,100 m and 1e7 m (a camera may be far out, not inside the Earth).
    std::optional<std::array<double, 3>> lonLatHeight(const std::string& key) {
        static constexpr std::string_view kWhat =
            "[lon, lat, height_m]: degrees in [-180, 180] and [-90, 90], metres above sea level in [-11100, 1e7]";
        const auto out = numbers<3>(key, kWhat);
        if (!out) return std::nullopt;
        const auto [lon, lat, h] = *out;
        if (!(std::fabs(lon) <= 180 && std::fabs(lat) <= 90 && h >= -11100 && h <= 1e7)) {
            error(key, fmt::format("{} must be {}", qualified(key), kWhat));
            return std::nullopt;
        }
        return out;
    }

    void markKnown(const std::string& key) { known_.insert(key); }

    void require(const std::string& key, std::string_view what) {
        if (!find(key))
            diags_.error(sectionLoc_, fmt::format("missing {}: {}", qualified(key), what));
    }

    void error(const std::string& key, std::string message) {
        diags_.error(keyLoc(key), std::move(message));
    }

    void warning(const std::string& key, std::string message) {
        diags_.warning(keyLoc(key), std::move(message));
    }

    // Reports the keys no getter asked for, with the closest known key.
    void finish() {
        if (locs_)
            for (const auto& key : known_) locs_->known.insert(qualified(key));
        if (!table_) return;
        const std::vector<std::string> knownList(known_.begin(), known_.end());
        for (auto&& [k, v] : *table_) {
            const std::string key(k.str());
            if (known_.count(key)) continue;
            diags_.error(locOf(file_, k.source()),
                         fmt::format("unknown key {}{}", qualified(key), didYouMean(key, knownList)));
        }
    }

    std::string qualified(const std::string& key) const { return name_ + "." + key; }

private:
    const toml::table* table_;
    std::string name_;
    const std::string& file_;
    Diagnostics& diags_;
    SourceLoc sectionLoc_;
    std::set<std::string> known_;
    KeyLocations* locs_ = nullptr;  ///< where finish() records the known keys
};

const std::vector<std::string> kSections{"samples", "frame",    "net",      "vertical",
                                         "subdivision", "limits", "texture", "lighting",
                                         "camera",   "geometry", "render", "overlay",
                                         "water",    "atmosphere", "base"};

}  // namespace

std::optional<double> parseFraction(std::string_view text) {
    const std::string s(text);
    const char* begin = s.c_str();
    char* end = nullptr;
    const double num = std::strtod(begin, &end);
    if (end == begin) return std::nullopt;
    while (*end == ' ') ++end;
    if (*end == '\0') return num;
    if (*end != '/') return std::nullopt;
    const char* denBegin = end + 1;
    const double den = std::strtod(denBegin, &end);
    if (end == denBegin || *end != '\0' || den == 0.0) return std::nullopt;
    return num / den;
}

namespace {

// Applies `section.key = value` overrides to the parsed document.
bool applyOverrides(toml::table& root, const SceneOverrides& overrides, Diagnostics& diags) {
    bool ok = true;
    for (const auto& [dotted, text] : overrides) {
        const auto dot = dotted.find('.');
        if (dot == std::string::npos || dot == 0 || dot + 1 == dotted.size()) {
            diags.error({}, fmt::format("override \"{}\" must name section.key (e.g. "
                                        "subdivision.omega)",
                                        dotted));
            ok = false;
            continue;
        }
        const std::string section = dotted.substr(0, dot), key = dotted.substr(dot + 1);
        if (!root.contains(section)) root.insert(section, toml::table{});
        toml::table* t = root.get_as<toml::table>(section);
        if (!t) {
            diags.error({}, fmt::format("override {}: \"{}\" is not a section", dotted, section));
            ok = false;
            continue;
        }
        char* end = nullptr;
        errno = 0;
        const long long i = std::strtoll(text.c_str(), &end, 10);
        // An integer past 64 bits stays the number it is (strtoll would clamp it), and the key's range says so.
        if (!text.empty() && *end == '\0' && errno != ERANGE) {
            t->insert_or_assign(key, static_cast<int64_t>(i));
            continue;
        }
        // TOML's own forms: an array (camera.position=[-3.18, 55.95, 400]), an inline
        // table (overlay.contours={interval_m=10}), a quoted string.
        if (!text.empty() && (text.front() == '[' || text.front() == '{' || text.front() == '"')) {
            try {
                toml::table parsed = toml::parse("v = " + text);
                if (toml::node* v = parsed.get("v"); v && (v->is_array() || v->is_table() || v->is_string())) {
                    t->insert_or_assign(key, std::move(*v));
                    continue;
                }
            } catch (const toml::parse_error&) {
                // kept as a string: the key's own check says what it must be
            }
        }
        const double d = std::strtod(text.c_str(), &end);
        if (!text.empty() && *end == '\0') t->insert_or_assign(key, d);
        else if (text == "true" || text == "false") t->insert_or_assign(key, text == "true");
        else t->insert_or_assign(key, text);
    }
    return ok;
}

}  // namespace

std::optional<SceneSpec> readScene(const std::filesystem::path& path, Diagnostics& diags,
                                   const SceneOverrides& overrides) {
    const std::string file = path.string();
    std::string problem;
    const auto read = readInputFile(path, kMaxSceneBytes, problem);
    if (!read) {
        diags.error({file, 0, 0}, fmt::format("cannot read the scene file: {}", problem));
        return std::nullopt;
    }
    const std::string& text = *read;

    toml::table root;
    try {
        root = toml::parse(text, file);
    } catch (const toml::parse_error& e) {
        diags.error(locOf(file, e.source()), fmt::format("invalid TOML: {}", e.description()));
        return std::nullopt;
    }

    if (!applyOverrides(root, overrides, diags)) return std::nullopt;

    SceneSpec scene;
    scene.sceneFile = path;
    scene.overrides = overrides;
    scene.sceneSha1 = sha1Hex(text);

    // Unknown or mistyped top-level sections.
    for (auto&& [k, v] : root) {
        const std::string key(k.str());
        const bool known = std::find(kSections.begin(), kSections.end(), key) != kSections.end();
        if (!known)
            diags.error(locOf(file, k.source()),
                        fmt::format("unknown section [{}]{}", key, didYouMean(key, kSections)));
        else if (!v.is_table())
            diags.error(locOf(file, k.source()),
                        fmt::format("\"{}\" must be a section ([{}])", key, key));
    }
    auto section = [&](const std::string& name) {
        const toml::table* t = root.get_as<toml::table>(name);
        SourceLoc loc = t ? locOf(file, t->source()) : SourceLoc{file, 0, 0};
        return Section(t, name, file, diags, loc);
    };
    // A section whose key locations go to `locs`.
    auto sectionInto = [&](const std::string& name, KeyLocations& locs) {
        Section s = section(name);
        s.recordLocations(locs);
        return s;
    };

    // [samples]
    {
        Section s = sectionInto("samples", scene.samples.locs);
        if (!s.present()) {
            diags.error({file, 0, 0}, "missing section [samples]: give path = \"dem.tif\" (any raster GDAL "
                                      "reads) or \"data.csv\" (columns lon,lat,elev)");
        } else {
            s.require("path", "the elevations: a raster GDAL reads or a CSV of samples (columns "
                              "lon,lat,elev), relative to the scene file");
            if (auto p = s.string("path")) {
                scene.samples.pathAsWritten = *p;
                scene.samples.path = path.parent_path() / *p;
                if (const std::string problem = inputFileProblem(scene.samples.path); problem == "no such file")
                    s.error("path", fmt::format("samples.path: file \"{}\" not found (looked "
                                                "for {}; the path is relative to the scene file)",
                                                printableExcerpt(*p, 200), printableExcerpt(scene.samples.path.string(), 200)));
                else if (!problem.empty())
                    s.error("path", fmt::format("samples.path = \"{}\": {}", printableExcerpt(*p, 200), problem));
            }
        }
        if (auto a = s.text("attribution")) scene.samples.attribution = *a;
        if (auto e = s.choice("elevations", {"earth", "any"})) scene.samples.earthElevations = *e == "earth";
        if (auto b = s.integer("band", 1, 65535, "(1 = the first band)")) scene.samples.band = *b;
        if (auto c = s.string("crs")) scene.samples.crs = *c;
        if (auto r = s.choice("resample", {"bilinear", "cubic", "average", "nearest"}))
            scene.samples.resample = *r == "bilinear" ? Resample::Bilinear
                                     : *r == "cubic"  ? Resample::Cubic
                                     : *r == "average" ? Resample::Average
                                                       : Resample::Nearest;
        if (auto u = s.choice("vertical_unit", {"m", "ft", "us-ft"})) scene.samples.verticalUnit = *u;
        if (auto n = s.choice("nodata", {"mask", "fill", "error"}))
            scene.samples.nodata = *n == "mask"   ? NodataPolicy::Mask
                                   : *n == "fill" ? NodataPolicy::Fill
                                                  : NodataPolicy::Error;
        s.finish();
    }

    // [frame]
    {
        Section s = sectionInto("frame", scene.frame.locs);
        if (auto k = s.choice("kind", {"utm", "local"}))
            scene.frame.kind = *k == "utm" ? FrameKind::Utm : FrameKind::Local;
        if (auto z = s.string("zone")) {
            scene.frame.utmZone = *z;
            if (scene.frame.kind == FrameKind::Local)
                s.error("zone", "frame.zone is only used with kind = \"utm\"; remove it");
        }
        s.finish();
    }

    // [net]
    {
        Section s = sectionInto("net", scene.net.locs);
        auto rows = s.integer("rows", 4, 100000, "nodes");
        auto cols = s.integer("cols", 4, 100000, "nodes");
        auto spacing = s.number("spacing_m", 0, 1e7, "m", true);
        if (spacing && (s.find("rows") || s.find("cols")))
            s.error("spacing_m", "give either net.spacing_m or net.rows and net.cols, not both");
        else if (spacing)
            scene.net.spacingM = *spacing;
        else if (rows && cols) {
            scene.net.rows = *rows;
            scene.net.cols = *cols;
        } else if (s.find("rows") || s.find("cols")) {
            if (!s.find("rows") || !s.find("cols"))
                diags.error(s.loc(), "net: give both rows and cols (or spacing_m alone)");
        } else {
            scene.net.rows = 64;  // default: 64 x 64 nodes over the samples' extent
            scene.net.cols = 64;
        }
        if (auto ext = s.box("extent_m", "[xmin, ymin, xmax, ymax] in metres")) {
            if (!((*ext)[2] > (*ext)[0] && (*ext)[3] > (*ext)[1]))
                s.error("extent_m", "net.extent_m needs xmin < xmax and ymin < ymax (metres)");
            else
                scene.net.extentM = ext;
        }
        if (auto box = s.box("extent_lonlat", "[lon_min, lat_min, lon_max, lat_max] in WGS84 degrees")) {
            const auto& w = *box;
            if (!(w[2] > w[0] && w[3] > w[1] && w[0] >= -180 && w[2] <= 180 && w[1] >= -90 && w[3] <= 90))
                s.error("extent_lonlat", "net.extent_lonlat needs -180 <= lon_min < lon_max <= 180 and "
                                         "-90 <= lat_min < lat_max <= 90 (degrees)");
            else if (s.find("extent_m"))
                s.error("extent_lonlat", "give either net.extent_m or net.extent_lonlat, not both");
            else
                scene.net.extentLonLat = box;
        }
        if (auto g = s.choice("gridding", {"linear", "invdist", "nearest"}))
            scene.net.gridding = *g == "linear"    ? Gridding::Linear
                             : *g == "invdist" ? Gridding::InverseDistance
                                               : Gridding::Nearest;
        s.finish();
    }

    // [vertical]
    {
        Section s = sectionInto("vertical", scene.look.locs);
        if (auto e = s.number("exaggeration", 0, 100, "(unitless factor)", true))
            scene.look.exaggeration = *e;
        s.finish();
    }

    // [subdivision]: the scheme's own parameters are checked by the subdiv stage.
    {
        SubdivisionSpec& sub = scene.subdivision;
        SchemeSpec& scheme = sub.scheme;
        Section s = sectionInto("subdivision", sub.locs);
        if (auto n = s.string("scheme"))
            scheme.name = *n;
        else if (s.find("preset"))
            scheme.name = "";  // the preset names the scheme
        if (const toml::node* d = s.find("depth"); d && d->value_exact<std::string>()) {
            s.markKnown("depth");
            if (*d->value_exact<std::string>() == "auto")
                sub.depthAuto = true;
            else
                s.error("depth", fmt::format("subdivision.depth must be an integer number of levels in "
                                             "[0, {}] or \"auto\" (with tolerance_m)", kMaxDepth));
        } else if (auto n = s.integer("depth", 0, kMaxDepth, "levels")) {
            sub.depth = *n;
        }
        if (auto t = s.number("tolerance_m", 0, 1e6, "m", true)) sub.toleranceM = *t;
        if (sub.depthAuto && sub.toleranceM <= 0 && !s.find("tolerance_m"))
            s.error("depth", "subdivision.depth = \"auto\" needs subdivision.tolerance_m, the "
                             "largest change in metres one more level may make (e.g. "
                             "tolerance_m = 1)");
        if (!sub.depthAuto && s.find("tolerance_m"))
            diags.warning(s.keyLoc("tolerance_m"), "subdivision.tolerance_m is ignored: it is used "
                                                   "only with depth = \"auto\"");
        if (auto p = s.string("preset")) scheme.preset = *p;
        if (auto b = s.boolean("allow_nonconvergent")) scheme.allowNonconvergent = *b;
        if (auto a = s.integer("arity", 2, 3, "(2 = binary, 3 = ternary)")) scheme.maskArity = *a;
        if (auto f = s.integer("mask_first", -1000, 1000, "(exponent of the first coefficient)"))
            scheme.maskFirst = *f;
        s.markKnown("mask");
        if (const toml::node* m = s.find("mask")) {
            const toml::array* a = m->as_array();
            bool ok = a && !a->empty();
            const bool tooLong = ok && a->size() > kMaxMaskCoefficients;  // kept out of the scheme's analysis
            for (size_t i = 0; ok && !tooLong && i < a->size(); ++i) {
                std::optional<double> v = (*a)[i].value<double>();
                if (!v) {
                    if (auto str = (*a)[i].value_exact<std::string>()) v = parseFraction(*str);
                }
                if (v && std::isfinite(*v)) scheme.mask.push_back(*v);
                else ok = false;
            }
            if (!ok)
                s.error("mask", "subdivision.mask must be a list of numbers or fractions (the "
                                "coefficients a_k of the scheme's symbol)");
            else if (tooLong)
                s.error("mask", fmt::format("subdivision.mask has {} coefficients, more than the {} a scheme's mask "
                                            "may have (its smoothness analysis grows as the cube of the length)",
                                            a->size(), kMaxMaskCoefficients));
        }
        const bool isMask = scheme.name == "mask";  // a mask's own keys: subdiv::resolveScheme
        if (!isMask && (s.find("mask") || s.find("arity") || s.find("mask_first")))
            diags.error(s.keyLoc(s.find("mask") ? "mask" : s.find("arity") ? "arity" : "mask_first"),
                        "subdivision.mask, arity and mask_first are only used with scheme = \"mask\"");
        if (const toml::table* t = root.get_as<toml::table>("subdivision")) {
            for (auto&& [k, v] : *t) {
                const std::string key(k.str());
                if (key == "scheme" || key == "depth" || key == "tolerance_m" ||
                    key == "preset" || key == "mask" ||
                    key == "arity" || key == "mask_first" || key == "allow_nonconvergent")
                    continue;
                s.markKnown(key);
                // A parameter is reported at its key, not its value: the value may be fine
                // and the name wrong.
                sub.locs.keys["subdivision." + key] = locOf(file, k.source());
                std::optional<double> value;
                if (auto i = v.value_exact<int64_t>()) value = static_cast<double>(*i);
                else if (auto d = v.value_exact<double>()) value = *d;
                else if (auto str = v.value_exact<std::string>()) value = parseFraction(*str);
                if (!value || !std::isfinite(*value)) {
                    diags.error(locOf(file, v.source()),
                                fmt::format("subdivision.{} must be a number or a fraction "
                                            "such as \"7/32\"",
                                            key));
                    continue;
                }
                scheme.params[key] = *value;
            }
        }
        scheme.locs = sub.locs;
        s.finish();
    }

    // [limits]
    {
        Section s = sectionInto("limits", scene.limits.locs);
        if (auto v = s.number("max_triangles", 1, 1e10, "triangles")) scene.limits.maxTriangles = *v;
        if (auto v = s.number("max_sdl_mb", 0.001, 1e6, "MB")) scene.limits.maxSdlMB = *v;
        if (auto v = s.number("max_parse_s", 0.001, 1e6, "s")) scene.limits.maxParseS = *v;
        if (auto v = s.number("max_memory_mb", 1, 1e9, "MB")) scene.limits.maxMemoryMB = *v;
        s.finish();
    }

    // [texture]
    {
        Section s = sectionInto("texture", scene.look.locs);
        ColorRamp& ramp = scene.look.ramp;
        std::vector<std::string> ramps = rampPresetNames();
        ramps.push_back("custom");
        if (auto r = s.choice("ramp", ramps)) ramp.preset = *r;
        if (auto c = s.string("cpt")) {  // a GMT palette file, beside the scene
            const std::filesystem::path cptPath = path.parent_path() / *c;
            std::optional<std::string> cptText;
            if (s.find("ramp"))
                s.error("cpt", "give either texture.ramp or texture.cpt, not both");
            else if (std::string problem; !(cptText = readInputFile(cptPath, kMaxPaletteBytes, problem)))
                s.error("cpt", problem == "no such file"
                                   ? fmt::format("texture.cpt: file \"{}\" not found (looked for {})",
                                                 printableExcerpt(*c), printableExcerpt(cptPath.string(), 200))
                                   : fmt::format("texture.cpt = \"{}\": {}", printableExcerpt(*c), problem));
            else if (auto stops = parseCpt(*cptText, cptPath.string(), diags)) {
                ramp.preset = "custom";
                ramp.stops = std::move(*stops);
                ramp.cptPath = *c;
            }
        }
        if (auto m = s.choice("mode", {"elevation", "slope", "blend"}))
            scene.look.colouring = *m == "slope"   ? LookSpec::Colouring::Slope
                                   : *m == "blend" ? LookSpec::Colouring::Blend
                                                   : LookSpec::Colouring::Elevation;
        if (auto v = s.string("rock_color"); v && !parseHexColor(*v, scene.look.rockColour))
            s.error("rock_color", fmt::format("texture.rock_color = \"{}\" must be a colour \"#rrggbb\"",
                                              printableExcerpt(*v)));
        if (auto v = s.number("rock_from_deg", 0, 90, "degrees of slope", false, true)) scene.look.rockFromDeg = *v;
        if (auto v = s.number("rock_to_deg", 0, 90, "degrees of slope", true)) scene.look.rockToDeg = *v;
        if (!(scene.look.rockToDeg > scene.look.rockFromDeg))
            s.error(s.find("rock_to_deg") ? "rock_to_deg" : "rock_from_deg",
                    fmt::format("texture.rock_to_deg ({}) must be above texture.rock_from_deg ({})",
                                formatShortest(scene.look.rockToDeg), formatShortest(scene.look.rockFromDeg)));
        if (auto v = s.text("image_attribution")) scene.look.drapeImageAttribution = *v;
        if (auto v = s.string("image")) {
            const std::filesystem::path image = path.parent_path() / *v;
            const std::string problem = inputFileProblem(image);
            if (s.find("mode") && scene.look.colouring != LookSpec::Colouring::Elevation)
                s.error("image", "texture.image colours the surface by itself: leave out texture.mode");
            else if (problem == "no such file")
                s.error("image", fmt::format("texture.image: file \"{}\" not found (looked for {})",
                                             printableExcerpt(*v), printableExcerpt(image.string(), 200)));
            else if (!problem.empty())
                s.error("image", fmt::format("texture.image = \"{}\": {}", printableExcerpt(*v), problem));
            else {
                scene.look.colouring = LookSpec::Colouring::Image;
                scene.look.drapeImage = image;
                scene.look.drapeImageText = *v;
            }
        }
        s.markKnown("stops");
        const toml::node* stopsNode = s.find("stops");
        if (stopsNode && !ramp.cptPath.empty()) {
            s.error("stops", "texture.stops and texture.cpt both give the colours: keep one");
        } else if (!ramp.cptPath.empty()) {
            // the palette file's stops
        } else if (stopsNode && ramp.preset != "custom") {
            s.error("stops", "texture.stops is only used with ramp = \"custom\"; add "
                             "ramp = \"custom\" or remove the stops");
        } else if (ramp.preset == "custom") {
            const toml::array* a = stopsNode ? stopsNode->as_array() : nullptr;
            if (!a || a->size() < 2) {
                diags.error(stopsNode ? locOf(file, stopsNode->source()) : s.loc(),
                            "ramp = \"custom\" needs texture.stops = [{ elev_m = 0, color = "
                            "\"#rrggbb\" }, ...] with at least 2 stops");
            } else {
                for (const toml::node& item : *a) {
                    const toml::table* st = item.as_table();
                    ColorStop stop{};
                    auto elev = st ? st->get("elev_m") : nullptr;
                    auto color = st ? st->get("color") : nullptr;
                    std::optional<double> e = elev ? elev->value<double>() : std::nullopt;
                    std::optional<std::string> c =
                        color ? color->value_exact<std::string>() : std::nullopt;
                    if (!e || !c || !parseHexColor(*c, stop)) {
                        diags.error(locOf(file, item.source()),
                                    "each texture.stops entry must be { elev_m = <metres>, "
                                    "color = \"#rrggbb\" }");
                        continue;
                    }
                    stop.elevM = *e;
                    if (!ramp.stops.empty() && stop.elevM <= ramp.stops.back().elevM)
                        diags.error(locOf(file, item.source()),
                                    fmt::format("texture.stops: elev_m = {} m must be above the "
                                                "previous stop ({} m); list stops bottom to top",
                                                formatShortest(stop.elevM),
                                                formatShortest(ramp.stops.back().elevM)));
                    ramp.stops.push_back(stop);
                }
            }
        }
        s.finish();
    }

    // [lighting]
    {
        Section s = sectionInto("lighting", scene.look.locs);
        if (auto v = s.number("sun_azimuth_deg", 0, 360, "degrees (compass bearing)", false, true))
            scene.look.sunAzimuthDeg = *v;
        if (auto v = s.number("sun_altitude_deg", 0, 90, "degrees", true))
            scene.look.sunAltitudeDeg = *v;
        s.markKnown("datetime");
        if (const toml::node* n = s.find("datetime")) {
            // A string, or TOML's own offset date-time (written without quotes).
            std::optional<std::string> text = n->value_exact<std::string>();
            if (const auto* native = n->as_date_time()) {
                const toml::date_time& t = native->get();
                text = fmt::format("{:04}-{:02}-{:02}T{:02}:{:02}:{:02}", t.date.year, t.date.month, t.date.day,
                                   t.time.hour, t.time.minute, t.time.second);
                if (t.offset)
                    *text += t.offset->minutes == 0 ? std::string("Z")
                                                    : fmt::format("{}{:02}:{:02}", t.offset->minutes < 0 ? '-' : '+',
                                                                  std::abs(t.offset->minutes) / 60,
                                                                  std::abs(t.offset->minutes) % 60);
            }
            std::string why = "it must be a date and time with its UTC offset";
            if (text) scene.look.sunTime = parseOffsetDateTime(*text, why);
            if (!scene.look.sunTime)
                s.error("datetime", fmt::format("lighting.datetime{}: {}", text ? " = \"" + printableExcerpt(*text) + "\"" : "",
                                                why));
            else
                scene.look.sunTimeText = *text;
            for (const char* angle : {"sun_azimuth_deg", "sun_altitude_deg"})
                if (scene.look.locs.has(std::string("lighting.") + angle))
                    s.warning(angle, fmt::format("lighting.{} is not used: lighting.datetime places the sun", angle));
        }
        s.finish();
    }

    // [camera]
    {
        Section s = sectionInto("camera", scene.look.locs);
        CameraSpec& camera = scene.look.camera;
        if (auto v = s.number("azimuth_deg", 0, 360, "degrees (compass bearing)", false, true))
            camera.azimuthDeg = *v;
        if (auto v = s.number("elevation_deg", 0, 90, "degrees", true))
            camera.elevationDeg = *v;
        if (auto v = s.number("distance_m", 0, 1e8, "m", true)) camera.distanceM = *v;
        if (auto v = s.number("fov_deg", 1, 170, "degrees")) camera.fovDeg = *v;
        if (auto p = s.choice("projection", {"perspective", "orthographic"}))
            camera.projection =
                *p == "perspective" ? Projection::Perspective : Projection::Orthographic;
        camera.position = s.lonLatHeight("position");
        camera.lookAt = s.lonLatHeight("look_at");
        if (camera.lookAt && !camera.position)
            s.error("look_at", "camera.look_at needs camera.position (the eye, [lon, lat, height_m])");
        for (const char* orbit : {"azimuth_deg", "elevation_deg", "distance_m"})
            if (camera.position && scene.look.locs.has(std::string("camera.") + orbit))
                s.warning(orbit, fmt::format("camera.{} is not used: camera.position places the eye", orbit));
        s.finish();
    }

    // [geometry]
    {
        Section s = sectionInto("geometry", scene.geometry.locs);
        if (auto k = s.choice("kind", {"auto", "mesh2", "adaptive", "height_field"}))
            scene.geometry.kind = *k == "auto"       ? GeometryKind::Auto
                                  : *k == "mesh2"    ? GeometryKind::Mesh2
                                  : *k == "adaptive" ? GeometryKind::Adaptive
                                                     : GeometryKind::HeightField;
        if (auto v = s.number("tolerance_px", 0, 100, "pixels", true)) scene.geometry.tolerancePx = *v;
        if (auto v = s.number("tolerance_m", 0, 1e4, "metres", true)) scene.geometry.toleranceM = *v;
        s.finish();
    }

    // [render]
    {
        Section s = sectionInto("render", scene.render.locs);
        if (auto v = s.integer("width", 16, 16384, "pixels")) scene.render.width = *v;
        if (auto v = s.integer("height", 16, 16384, "pixels")) scene.render.height = *v;
        if (auto v = s.boolean("antialias")) scene.render.antialias = *v;
        if (auto v = s.number("timeout_s", 0, 1e7, "seconds (0: no limit)")) scene.render.timeoutS = *v;
        if (auto v = s.string("background")) {
            if (*v == "sky") scene.render.background = Background::Sky;
            else if (*v == "transparent") scene.render.background = Background::Transparent;
            else if (parseHexColor(*v, scene.render.backgroundColour)) scene.render.background = Background::Colour;
            else
                s.error("background", fmt::format("render.background = \"{}\" must be \"sky\", \"transparent\" "
                                                  "or a colour \"#rrggbb\"",
                                                  printableExcerpt(*v)));
        }
        if (auto v = s.string("output")) {
            const std::filesystem::path out(*v);
            const bool climbs = std::any_of(out.begin(), out.end(), [](const auto& part) { return part == ".."; });
            if (v->size() < 5 || v->substr(v->size() - 4) != ".png")
                s.error("output", fmt::format("render.output = \"{}\" must name a .png file", printableExcerpt(*v, 200)));
            else if (out.is_absolute() || climbs)
                // A scene from elsewhere must not choose where on the disk it writes; -o can.
                s.error("output", fmt::format("render.output = \"{}\" must stay inside the current folder (no "
                                              "leading /, no ..); give -o to write anywhere else",
                                              printableExcerpt(*v, 200)));
            else
                scene.render.output = *v;
        }
        s.finish();
    }

    // [base]
    {
        Section s = sectionInto("base", scene.look.locs);
        s.markKnown("thickness_m");
        if (const toml::node* n = s.find("thickness_m")) {
            if (auto b = n->value_exact<bool>()) {
                scene.look.base.enabled = *b;
            } else if (auto v = s.number("thickness_m", 0, 1e5, "metres (or false: no block)", true)) {
                scene.look.base.thicknessM = *v;
            }
        }
        s.finish();
    }

    // [water]
    {
        Section s = sectionInto("water", scene.look.locs);
        if (auto v = s.number("level_m", kLowestElevationM, kHighestElevationM, "metres above sea level"))
            scene.look.water.levelM = *v;
        if (auto v = s.string("color")) {
            if (!parseHexColor(*v, scene.look.water.colour))
                s.error("color", fmt::format("water.color = \"{}\" must be a colour \"#rrggbb\"", printableExcerpt(*v)));
        }
        if (auto v = s.number("transparency", 0, 1, "0 (opaque) to 1 (clear)")) scene.look.water.transparency = *v;
        s.finish();
    }

    // [atmosphere]
    {
        Section s = sectionInto("atmosphere", scene.look.locs);
        if (auto v = s.number("haze", 0, 1, "0 (none) to 1 (thick)")) scene.look.haze = *v;
        s.finish();
    }

    // [overlay]
    {
        Section s = sectionInto("overlay", scene.overlay.locs);
        if (auto v = s.boolean("enabled"))
            scene.overlay.enabled = *v ? OverlaySpec::Enabled::On : OverlaySpec::Enabled::Off;
        if (auto v = s.text("title")) scene.overlay.title = *v;
        if (auto v = s.text("subtitle")) scene.overlay.subtitle = *v;
        if (auto v = s.text("credits")) scene.overlay.credits = *v;
        if (auto v = s.boolean("legend")) scene.overlay.legend = *v;
        if (auto v = s.boolean("scale_bar")) scene.overlay.scaleBar = *v;
        if (auto v = s.boolean("north_arrow")) scene.overlay.northArrow = *v;
        s.markKnown("contours");
        if (const toml::node* n = s.find("contours")) {
            // An inline table: { interval_m = 50, index_every = 5, color = "#3e3426" }.
            const toml::table* t = n->as_table();
            ContourSpec contours;
            bool ok = t != nullptr && t->contains("interval_m");
            for (auto&& [k, v] : t ? *t : toml::table{}) {
                const std::string key(k.str());
                if (key == "interval_m") {
                    const auto d = v.value<double>();
                    ok = ok && d && *d > 0 && std::isfinite(*d);
                    if (d) contours.intervalM = *d;
                } else if (key == "index_every") {
                    const auto i = v.value_exact<int64_t>();
                    ok = ok && i && *i >= 0 && *i <= 100;
                    if (i) contours.indexEvery = static_cast<int>(*i);
                } else if (key == "color") {
                    const auto c = v.value_exact<std::string>();
                    ok = ok && c && parseHexColor(*c, contours.colour);
                } else {
                    ok = false;
                }
            }
            if (ok) scene.overlay.contours = contours;
            else
                s.error("contours", "overlay.contours must be { interval_m = <metres> } with optional index_every "
                                    "= <n> (every n-th line heavier, 0: none) and color = \"#rrggbb\"");
        }
        s.finish();
    }

    return scene;  // complete even when `diags` holds errors, so later checks can add theirs
}

}  // namespace relief::scene
