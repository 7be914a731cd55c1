#pragma once
// One [section] of a scene file, as the section readers (read_sections.h)
// see it: each getter marks its key as known, checks its type and range, and
// reports with the key's location; finish() reports the keys no getter asked
// for. Internal to scene/: the stage's front door is read_scene.h.
#include <array>
#include <filesystem>
#include <optional>
#include <set>
#include <span>
#include <string>
#include <string_view>

#include <fmt/format.h>
#include <toml++/toml.h>

#include "core/diagnostics.h"
#include "scene/enum_names.h"
#include "scene/scene_spec.h"

namespace relief::scene {

/// Where a TOML node was written; a value from --set has no line (0).
SourceLoc locOf(const std::string& file, const toml::source_region& r);

class Section {
public:
    Section(const toml::table* table, std::string name, const std::string& file, Diagnostics& diags,
            SourceLoc sectionLoc)
        : table_(table), name_(std::move(name)), file_(file), diags_(diags), sectionLoc_(std::move(sectionLoc)) {}

    /// Records the section's and every key's location (the value's) in `locs`.
    void recordLocations(KeyLocations& locs);

    bool present() const { return table_ != nullptr; }
    const toml::table* table() const { return table_; }
    const SourceLoc& loc() const { return sectionLoc_; }
    SourceLoc keyLoc(const std::string& key) const;
    const toml::node* find(const std::string& key) const { return table_ ? table_->get(key) : nullptr; }

    /// A number (integer, float, or a fraction string like "7/32") in [lo, hi]
    /// (or open at either end).
    std::optional<double> number(const std::string& key, double lo, double hi, std::string_view unit,
                                 bool loOpen = false, bool hiOpen = false);
    std::optional<int> integer(const std::string& key, int lo, int hi, std::string_view unit);
    std::optional<bool> boolean(const std::string& key);
    std::optional<std::string> string(const std::string& key);
    /// A text drawn on the still or written in the .pov header and sidecar (a
    /// title, a credit line): at most kMaxTextBytes, since laying out megabytes
    /// of text costs minutes and gigabytes, and shows nothing a still can hold.
    /// Valid UTF-8 (bytes that are not as U+FFFD, with a warning once a run):
    /// Pango, PDF metadata and the sidecar take nothing else.
    std::optional<std::string> text(const std::string& key);
    /// A string that must be one of `choices`.
    std::optional<std::string> choice(const std::string& key, const std::vector<std::string>& choices);
    /// A value of E by its name (enum_names.h), among `rows` (all of E's by default).
    template <class E>
    std::optional<E> named(const std::string& key, std::span<const NameRow<E>> rows = EnumNames<E>::rows) {
        const auto name = choice(key, namesOf(rows));
        return name ? valueNamed(*name, rows) : std::nullopt;
    }
    /// N numbers in an array, or nullopt (and an error saying `what` they must be).
    template <size_t N>
    std::optional<std::array<double, N>> numbers(const std::string& key, std::string_view what);
    /// Four numbers, e.g. an extent; `what` says which in the error.
    std::optional<std::array<double, 4>> box(const std::string& key, std::string_view what);
    /// A file named relative to the scene file's folder (a track, a layer's
    /// file): the path resolved, its text as written in `asWritten`; nullopt
    /// (and an error at the key) when it is missing or not a file relief reads.
    std::optional<std::filesystem::path> fileBesideScene(const std::string& key, const std::filesystem::path& sceneFile,
                                                         std::string& asWritten);
    /// [lon, lat, height_m]: degrees within the globe, a height within
    /// -11,100 m and 1e7 m (a camera may be far out, not inside the Earth).
    std::optional<GeoPoint> lonLatHeight(const std::string& key);

    void markKnown(const std::string& key) { known_.insert(key); }
    void require(const std::string& key, std::string_view what);
    void error(const std::string& key, std::string message) { diags_.error(keyLoc(key), std::move(message)); }
    void warning(const std::string& key, std::string message) { diags_.warning(keyLoc(key), std::move(message)); }
    /// Reports the keys no getter asked for, with the closest known key.
    void finish();
    std::string qualified(const std::string& key) const { return name_ + "." + key; }

private:
    const toml::table* table_;
    std::string name_;
    const std::string& file_;
    Diagnostics& diags_;
    SourceLoc sectionLoc_;
    std::set<std::string> known_;
    std::set<std::string> integers_;  ///< the keys read by integer()
    KeyLocations* locs_ = nullptr;  ///< where finish() records the known keys
};

template <size_t N>
std::optional<std::array<double, N>> Section::numbers(const std::string& key, std::string_view what) {
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

}  // namespace relief::scene
