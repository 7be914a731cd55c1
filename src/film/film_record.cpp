#include "film/film_record.h"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <stdexcept>

#include "core/atomic_file.h"
#include "core/utf8_record.h"
#include "core/input_file.h"
#include "film/video.h"
#include "relief/version.h"

namespace relief::film {

namespace fs = std::filesystem;
using nlohmann::ordered_json;

namespace {

constexpr int kFilmRecordFormat = 3;  // 2 named the film and its frames by absolute paths
constexpr size_t kMaxRecordBytes = 64 << 20;  // 10,000 frames of a few keys each fit many times over

ordered_json frameJson(const FilmFrame& f) {
    ordered_json set = ordered_json::object();
    for (const auto& [k, v] : f.settings.overrides) set[k] = v;
    ordered_json j = {{"number", f.settings.number}, {"set", set}};
    if (f.settings.sunTime) {
        j["sun_time"] = formatOffsetDateTime(*f.settings.sunTime);
        j["sun_altitude_deg"] = f.sunAltitudeDeg;
    }
    j["file_number"] = f.fileNumber;
    return j;
}

FilmFrame frameOf(const ordered_json& j) {
    FilmFrame f;
    f.settings.number = j.at("number").get<int>();
    for (const auto& [k, v] : j.at("set").items()) f.settings.overrides.emplace_back(k, v.get<std::string>());
    if (j.contains("sun_time")) {
        std::string why;
        f.settings.sunTime = parseOffsetDateTime(j.at("sun_time").get<std::string>(), why);
        if (!f.settings.sunTime) throw std::invalid_argument("sun_time: " + why);
        f.sunAltitudeDeg = j.at("sun_altitude_deg").get<double>();
    }
    f.fileNumber = j.at("file_number").get<int>();
    f.night = f.fileNumber == 0;
    return f;
}

// The limits a resumed film is held to, and the scene file's line and column of each the scene set.
constexpr std::array<const char*, 2> kRecordedLimits = {"limits.max_film_s", "limits.max_memory_mb"};

ordered_json limitsJson(const scene::LimitsSpec& l) {
    ordered_json setAt = ordered_json::object();
    for (const char* key : kRecordedLimits)
        if (const auto at = l.locs.keys.find(key); at != l.locs.keys.end()) setAt[key] = {at->second.line, at->second.column};
    return {{"max_film_s", l.maxFilmS}, {"max_memory_mb", l.maxMemoryMB}, {"set_at", setAt}};
}

// Throws (as a damaged record) on a key it does not know or a number out of the scene's ranges.
scene::LimitsSpec limitsOf(const ordered_json& j, const fs::path& scene) {
    scene::LimitsSpec l;
    l.maxFilmS = j.at("max_film_s").get<double>();
    l.maxMemoryMB = j.at("max_memory_mb").get<double>();
    const bool memoryInRange = l.maxMemoryMB == 0 || (l.maxMemoryMB >= 1 && l.maxMemoryMB <= 1e9);  // 0: the default
    if (!(l.maxFilmS >= 0 && l.maxFilmS <= 1e9 && memoryInRange)) throw std::invalid_argument("limits out of range");
    l.locs.file = scene.string();
    for (const auto& [key, at] : j.at("set_at").items()) {
        if (std::find(kRecordedLimits.begin(), kRecordedLimits.end(), key) == kRecordedLimits.end())
            throw std::invalid_argument("not a recorded limit: " + key);
        // Line 0: set by --set, on the command line, not in the file.
        const auto line = at.at(0).get<long long>(), column = at.at(1).get<long long>();
        if (line < 0 || line > 1e9 || column < 0 || column > 1e9) throw std::invalid_argument("not a place in a file");
        l.locs.keys[key] = SourceLoc{scene.string(), static_cast<int>(line), static_cast<int>(column)};
    }
    return l;
}

// Frames numbered 1, 2, ... and the kept ones 1, 2, ... in order: what the
// frames' names and the film's order rest on.
bool framesInOrder(const std::vector<FilmFrame>& frames) {
    int kept = 0;
    for (size_t i = 0; i < frames.size(); ++i) {
        if (frames[i].settings.number != int(i) + 1) return false;
        if (frames[i].fileNumber != 0 && frames[i].fileNumber != ++kept) return false;
    }
    return kept > 0;
}

// The record is untrusted: it may only name the film whose working folder it
// is in (<film>.film or <film>.film-N beside it, a video relief makes); the
// film is written beside the folder and its sidecar beside the film.
bool nameBelongsTo(const std::string& film, const fs::path& folder) {
    const fs::path named(film);
    const std::string name = folder.filename().string(), own = named.stem().string() + ".film";
    const bool ours = name == own || (name.rfind(own + "-", 0) == 0 && name.size() > own.size() + 1 &&
                                      name.find_first_not_of("0123456789", own.size() + 1) == std::string::npos);
    VideoFormat format{};
    return ours && film.find('/') == std::string::npos && !named.stem().empty() && videoFormatOf(named, format);
}

}  // namespace

std::string framePlanName(int number) {
    return fmt::format("frame-{:05}.plan", number);
}

void writeFilmRecord(const FilmRecord& r, const fs::path& dir) {
    ordered_json frames = ordered_json::array();
    for (const auto& f : r.frames) frames.push_back(frameJson(f));
    ordered_json j = {{"relief_film", kFilmRecordFormat},
                            {"relief_version", kVersion},
                            {"scene", r.scene.string()},
                            {"scene_sha1", r.sceneSha1},
                            {"fps", r.fps},
                            {"film", ""},
                            {"frames_kept", !r.framesDir.empty()},
                            {"film_given", r.filmGiven},
                            {"terrains", r.terrains},
                            {"compile_seconds", r.compileSeconds},
                            {"limits", limitsJson(r.limits)},
                            {"frames", frames}};
    putName(j, "film", r.film.filename().string());
    writeFileAtomically(dir / "film.json", j.dump(1, ' ', false, nlohmann::json::error_handler_t::replace) + "\n");
}

std::optional<FilmRecord> readFilmRecord(const fs::path& dir, Diagnostics& diags) {
    const fs::path file = dir / "film.json";
    const SourceLoc at{file.string(), 0, 0};
    std::string problem;
    const auto text = readInputFile(file, kMaxRecordBytes, problem);
    if (!text) {
        diags.error(at, problem == "no such file"
                            ? "not a film's working folder (no film.json): give the folder a relief animate kept"
                            : "cannot read the film's record: " + problem);
        return std::nullopt;
    }
    FilmRecord r;
    std::string film;
    try {
        const ordered_json j = ordered_json::parse(*text);
        if (j.at("relief_film").get<int>() != kFilmRecordFormat || j.at("relief_version").get<std::string>() != kVersion) {
            diags.error(at, "the film was begun by another relief: make it again with this one (relief animate SCENE)");
            return std::nullopt;
        }
        r.scene = j.at("scene").get<std::string>();
        r.sceneSha1 = j.at("scene_sha1").get<std::string>();
        r.fps = j.at("fps").get<double>();
        film = nameAt(j, "film");
        r.framesKept = j.at("frames_kept").get<bool>();
        r.filmGiven = j.at("film_given").get<bool>();
        r.terrains = j.at("terrains").get<int>();
        r.compileSeconds = j.at("compile_seconds").get<double>();
        r.limits = limitsOf(j.at("limits"), r.scene);
        for (const auto& f : j.at("frames")) r.frames.push_back(frameOf(f));
    } catch (const std::exception&) {  // nlohmann's, a sun time that is not one, limits out of range
        diags.error(at, "the film's record is damaged (not the JSON relief writes): make the film again");
        return std::nullopt;
    }
    if (!framesInOrder(r.frames) || !(r.fps >= 1 && r.fps <= 120) || r.terrains < 0) {
        diags.error(at, "the film's record is damaged (its frames are not a film's): make the film again");
        return std::nullopt;
    }
    const fs::path folder = fs::absolute(dir).lexically_normal();
    const fs::path own = folder.has_filename() ? folder : folder.parent_path();
    if (!nameBelongsTo(film, own)) {
        diags.error(at, "the film's record names a film that is not this folder's (<film>.film beside the film, "
                        "its sidecar <film>.json): resume it where relief animate left it, or make the film again");
        return std::nullopt;
    }
    r.film = own.parent_path() / film;
    r.sidecar = fs::path(r.film).replace_extension(".json");
    return r;
}

}  // namespace relief::film
