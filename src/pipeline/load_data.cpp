// Elevation data in place of a scene file: what the file is, and the scene
// relief makes for it (relief init writes it out: record_init.cpp).
#include "pipeline/load.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include <fmt/format.h>
#include <toml++/toml.h>

#include "core/input_file.h"
#include "core/number_format.h"
#include "core/text_escape.h"
#include "geo/geo.h"
#include "geo/raster.h"
#include "geo/raster_mosaic.h"
#include "scene/enum_names.h"
#include "scene/read_scene_table.h"

namespace relief {

namespace fs = std::filesystem;

InputKind inputKindOf(const fs::path& path, std::string& why) {
    std::error_code ec;
    const bool folder = fs::is_directory(path, ec);
    if (!folder && (!fs::is_regular_file(path, ec) || path.extension() == ".toml")) return InputKind::Scene;
    // Data as geo reads it (a raster, a folder of tiles), by the table controlNet reads samples with.
    if (geo::recognisedSource(path).raster) {
        if (!folder || !geo::rasterTilesIn(path, why).empty()) return InputKind::Raster;
        return InputKind::Neither;  // a folder without tiles: `why` says so
    }
    if (path.extension() == ".csv") return InputKind::Samples;
    std::string problem;
    const auto text = readInputFile(path, kMaxSceneBytes, problem);
    if (!text) {
        why = problem;
        return InputKind::Neither;
    }
    try {
        (void)toml::parse(*text, path.string());
        return InputKind::Scene;
    } catch (const toml::parse_error& e) {
        why = fmt::format("not TOML: {}", e.description());
    }
    // A CSV by what it holds: a first line of comma-separated text.
    const std::string first = text->substr(0, text->find('\n'));
    const bool printable =
        std::all_of(first.begin(), first.end(), [](unsigned char c) { return c >= 0x20 || c == '\t' || c == '\r'; });
    if (printable && first.find(',') != std::string::npos) return InputKind::Samples;
    return InputKind::Neither;
}

namespace {

// The scene relief makes for `path` (a file, or a folder of tiles), as a table.
toml::table sceneTableForData(const fs::path& path) {
    // A folder of tiles is named by the folder, and summed up by its first tile.
    const fs::path data = path.has_filename() ? path : path.parent_path();
    std::error_code ec;
    std::string ignored;
    const std::vector<fs::path> tiles =
        fs::is_directory(data, ec) ? geo::rasterTilesIn(data, ignored) : std::vector<fs::path>{};
    const auto summary = geo::rasterSummary(tiles.empty() ? data : tiles.front());
    std::string title = summary && tiles.empty() ? summary->title : std::string();
    if (title.empty() && tiles.empty()) title = data.stem().string();
    if (title.empty()) title = data.filename().string();
    if (title == "." || title == "..") title = fs::weakly_canonical(data, ec).filename().string();  // its own name
    toml::table scene{{"samples", toml::table{{"path", data.filename().string()}}},
                      {"overlay", toml::table{{"title", title}}}};
    // Deeper than any dry land (the Dead Sea's shore, -430 m): a sea floor, in the topobathy ramp's blues.
    if (summary && summary->range && (*summary->range)[0] <= kSeaFloorM)
        scene.insert("texture", toml::table{{"ramp", "topobathy"}});
    return scene;
}

// The scene as the sidecar records it: TOML, with U+FFFD for bytes that are not UTF-8.
std::string sceneRecord(const fs::path& data, toml::table scene) {
    scene.for_each([](auto& section) {
        if constexpr (toml::is_table<decltype(section)>)
            section.for_each([](auto& value) {
                if constexpr (toml::is_string<decltype(value)>) value = utf8Replaced(value.get());
            });
    });
    std::ostringstream out;
    out << "# The scene relief makes for " << oneLineText(data.filename().string())
        << " (relief init writes it out, every choice explained).\n"
        << toml::toml_formatter(scene, toml::format_flags::allow_unicode_strings) << '\n';
    return out.str();
}

}  // namespace

std::string sceneTextForData(const fs::path& path) { return sceneRecord(path, sceneTableForData(path)); }

scene::SceneDocument sceneDocumentForData(const fs::path& path) {
    // Read as a table, never as TOML text: a file's name need not be UTF-8 (Linux allows any
    // byte but '/' and NUL), TOML cannot hold one that is not, and the table keeps its bytes, so
    // the file is found. Only the record (the sidecar's) shows them as U+FFFD.
    toml::table scene = sceneTableForData(path);
    std::string record = sceneRecord(path, scene);
    return {path, std::move(record), std::move(scene)};
}

}  // namespace relief
