// The scene reader's driver: the file read and parsed, the overrides applied,
// the sections checked, then each read by its reader (read_sections.h).
#include "scene/read_scene.h"

#include <algorithm>
#include <cerrno>
#include <cstdlib>

#include <fmt/format.h>
#include <openssl/evp.h>
#include <toml++/toml.h>

#include "core/input_file.h"
#include "core/text_distance.h"
#include "core/text_escape.h"
#include "scene/read_scene_table.h"
#include "scene/read_sections.h"
#include "scene/section.h"

namespace relief::scene {

SourceLoc KeyLocations::at(const std::string& qualifiedKey) const {
    if (auto k = keys.find(qualifiedKey); k != keys.end()) return k->second;
    const auto dot = qualifiedKey.find('.');
    if (auto sec = sections.find(qualifiedKey.substr(0, dot)); sec != sections.end()) return sec->second;
    return {file, 0, 0};
}

std::span<const SectionReader> sectionReaders() {
    static const SectionReader kReaders[] = {
        {"samples", [](SceneSpec& s) -> KeyLocations& { return s.samples.locs; }, readSamples},
        {"frame", [](SceneSpec& s) -> KeyLocations& { return s.frame.locs; }, readFrame},
        {"net", [](SceneSpec& s) -> KeyLocations& { return s.net.locs; }, readNet},
        {"vertical", [](SceneSpec& s) -> KeyLocations& { return s.look.vertical.locs; }, readVertical},
        {"subdivision", [](SceneSpec& s) -> KeyLocations& { return s.subdivision.locs; }, readSubdivision},
        {"limits", [](SceneSpec& s) -> KeyLocations& { return s.limits.locs; }, readLimits},
        {"texture", [](SceneSpec& s) -> KeyLocations& { return s.look.texture.locs; }, readTexture},
        {"lighting", [](SceneSpec& s) -> KeyLocations& { return s.look.lighting.locs; }, readLighting},
        {"camera", [](SceneSpec& s) -> KeyLocations& { return s.look.camera.locs; }, readCamera},
        {"geometry", [](SceneSpec& s) -> KeyLocations& { return s.geometry.locs; }, readGeometry},
        {"render", [](SceneSpec& s) -> KeyLocations& { return s.render.locs; }, readRender},
        {"base", [](SceneSpec& s) -> KeyLocations& { return s.look.base.locs; }, readBase},
        {"water", [](SceneSpec& s) -> KeyLocations& { return s.look.water.locs; }, readWater},
        {"atmosphere", [](SceneSpec& s) -> KeyLocations& { return s.look.atmosphere.locs; }, readAtmosphere},
        {"overlay", [](SceneSpec& s) -> KeyLocations& { return s.overlay.locs; }, readOverlay},
        {"animation", [](SceneSpec& s) -> KeyLocations& { return s.animation.locs; }, readAnimation},
        {"layer", [](SceneSpec& s) -> KeyLocations& { return s.layers.emplace_back().locs; }, readLayer, true},
    };
    return kReaders;
}

namespace {

// The scene file's fingerprint for headers and sidecars: SHA-1 as upper-case hex.
std::string sha1Hex(std::string_view bytes) {
    unsigned char digest[EVP_MAX_MD_SIZE];
    unsigned int size = 0;
    if (!EVP_Digest(bytes.data(), bytes.size(), digest, &size, EVP_sha1(), nullptr)) return {};
    std::string hex;
    for (unsigned int i = 0; i < size; ++i) hex += fmt::format("{:02X}", digest[i]);
    return hex;
}

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

// Whether `name` is a section of many tables ([[layer]]).
bool isManySection(const std::string& name) {
    const auto readers = sectionReaders();
    return std::any_of(readers.begin(), readers.end(), [&](const SectionReader& r) { return r.many && name == r.name; });
}

// Where an override came from: the command line's --set, named as the user wrote it.
SourceLoc overrideLoc(const std::string& dotted) {
    return {"--set " + terminalText(dotted, 200), 0, 0};
}

// Applies `section.key = value` overrides to the parsed document.
bool applyOverrides(toml::table& root, const SceneOverrides& overrides, Diagnostics& diags) {
    bool ok = true;
    for (const auto& [dotted, text] : overrides) {
        const auto dot = dotted.find('.');
        if (dot == std::string::npos || dot == 0 || dot + 1 == dotted.size()) {
            diags.error(overrideLoc(dotted), fmt::format("\"{}\" must name section.key (e.g. subdivision.omega)",
                                                         terminalText(dotted, 200)));
            ok = false;
            continue;
        }
        const std::string section = dotted.substr(0, dot), key = dotted.substr(dot + 1);
        if (isManySection(section)) {
            diags.error(overrideLoc(dotted), fmt::format("[[{}]] keys cannot be set with --set: there may be many "
                                                         "[[{}]] tables; change the scene file",
                                                         section, section));
            ok = false;
            continue;
        }
        if (!root.contains(section)) root.insert(section, toml::table{});
        toml::table* t = root.get_as<toml::table>(section);
        if (!t) {
            diags.error(overrideLoc(dotted),
                        fmt::format("\"{}\" is not a section: it holds a value", terminalText(section, 200)));
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

// Unknown or mistyped top-level sections.
void checkSections(const toml::table& root, const std::string& file, Diagnostics& diags) {
    std::vector<std::string> names;
    for (const auto& reader : sectionReaders()) names.emplace_back(reader.name);
    for (auto&& [k, v] : root) {
        const std::string key(k.str());
        if (std::find(names.begin(), names.end(), key) == names.end())
            diags.error(locOf(file, k.source()), fmt::format("unknown section [{}]{}", key, didYouMean(key, names)));
        else if (isManySection(key) && !v.is_array_of_tables())
            diags.error(locOf(file, k.source()), fmt::format("\"{}\" must be tables, each written [[{}]] (one for "
                                                             "each {}), not [{}]",
                                                             key, key, key, key));
        else if (!isManySection(key) && !v.is_table())
            diags.error(locOf(file, k.source()), fmt::format("\"{}\" must be a section ([{}])", key, key));
    }
}

// A section of many tables: each read as a section of its own into a new element.
void readEachTable(const SectionReader& reader, const SceneFile& f, SceneSpec& scene) {
    const toml::array* tables = f.root.get_as<toml::array>(reader.name);
    if (!tables || !tables->is_array_of_tables()) return;
    for (const toml::node& n : *tables) {
        const toml::table* t = n.as_table();
        Section s(t, reader.name, f.name, f.diags, locOf(f.name, t->source()));
        s.recordLocations(reader.locations(scene));
        reader.read(s, f, scene);
        s.finish();
    }
}

}  // namespace

std::optional<SceneDocument> readSceneFileOnce(const std::filesystem::path& path, Diagnostics& diags) {
    std::string problem;
    auto text = readInputFile(path, kMaxSceneBytes, problem);
    if (!text) {
        diags.error({path.string(), 0, 0}, fmt::format("cannot read the scene file: {}", problem));
        return std::nullopt;
    }
    return SceneDocument{path, std::move(*text), std::nullopt};
}

std::optional<SceneSpec> readSceneDocument(const SceneDocument& document, Diagnostics& diags,
                                           const SceneOverrides& overrides) {
    if (!document.madeForData) return readSceneText(document.record, document.path, diags, overrides);
    auto spec = readSceneTable(*document.madeForData, document.record, document.path, diags, overrides);
    if (spec) spec->madeForData = document.record;
    return spec;
}

std::optional<SceneSpec> readScene(const std::filesystem::path& path, Diagnostics& diags,
                                   const SceneOverrides& overrides) {
    const auto document = readSceneFileOnce(path, diags);
    return document ? readSceneDocument(*document, diags, overrides) : std::nullopt;
}

std::optional<SceneSpec> readSceneText(const std::string& text, const std::filesystem::path& path, Diagnostics& diags,
                                       const SceneOverrides& overrides) {
    const std::string file = path.string();
    toml::table root;
    try {
        root = toml::parse(text, file);
    } catch (const toml::parse_error& e) {
        diags.error(locOf(file, e.source()), fmt::format("invalid TOML: {}", e.description()));
        return std::nullopt;
    }
    return readSceneTable(std::move(root), text, path, diags, overrides);
}

std::optional<SceneSpec> readSceneTable(toml::table root, const std::string& record, const std::filesystem::path& path,
                                        Diagnostics& diags, const SceneOverrides& overrides) {
    const std::string file = path.string();
    if (!applyOverrides(root, overrides, diags)) return std::nullopt;

    SceneSpec scene;
    scene.sceneFile = path;
    scene.overrides = overrides;
    scene.sceneSha1 = sha1Hex(record);
    checkSections(root, file, diags);
    const SceneFile sceneFile{path, file, root, diags};
    for (const auto& reader : sectionReaders()) {
        if (reader.many) {
            readEachTable(reader, sceneFile, scene);
            continue;
        }
        const toml::table* t = root.get_as<toml::table>(reader.name);
        Section s(t, reader.name, file, diags, t ? locOf(file, t->source()) : SourceLoc{file, 0, 0});
        s.recordLocations(reader.locations(scene));
        reader.read(s, sceneFile, scene);
        s.finish();
    }
    return scene;  // complete even when `diags` holds errors, so later checks can add theirs
}

}  // namespace relief::scene
