// Elevation data in place of a scene file: what the file is, the scene relief
// makes for it, and `relief init`'s commented scene.
#include "scene_for_data.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include <fmt/format.h>
#include <toml++/toml.h>

#include "core/input_file.h"
#include "core/number_format.h"
#include "geo/raster.h"
#include "geo/raster_mosaic.h"
#include "scene/enum_names.h"

namespace relief {

namespace fs = std::filesystem;

std::string tomlString(const std::string& text) {
    std::ostringstream out;
    out << toml::value<std::string>(text);
    return out.str();
}

InputKind inputKindOf(const fs::path& path, std::string& why) {
    std::error_code ec;
    if (fs::is_directory(path, ec)) {  // a folder of tiles
        if (!geo::rasterTilesIn(path, why).empty()) return InputKind::Raster;
        return InputKind::Neither;
    }
    if (!fs::is_regular_file(path, ec) || path.extension() == ".toml") return InputKind::Scene;
    if (geo::isRasterDem(path)) return InputKind::Raster;
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

std::string sceneTextForData(const fs::path& path) {
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
    // Deeper than any dry land (the Dead Sea's shore, -430 m): a sea floor, in the topobathy ramp's blues.
    const bool seaFloor = summary && summary->range && (*summary->range)[0] <= kSeaFloorM;
    return fmt::format(
        "# The scene relief makes for {} (relief init writes it out, every choice explained).\n"
        "[samples]\npath = {}\n{}\n[overlay]\ntitle = {}\n",
        data.filename().string(), tomlString(data.filename().string()),
        seaFloor ? "\n[texture]\nramp = \"topobathy\"\n" : "", tomlString(title));
}

namespace {

// A TOML file written a key at a time, each with the reason for its value.
class CommentedScene {
public:
    void section(std::string_view name, std::string_view about) {
        text_ += fmt::format("{}[{}]{}\n", text_.empty() ? "" : "\n", name,
                             about.empty() ? "" : "  # " + std::string(about));
    }
    void key(std::string_view name, const std::string& value, std::string_view why) {
        const std::string line = fmt::format("{} = {}", name, value);
        text_ += why.empty() ? line + "\n" : fmt::format("{:<28}  # {}\n", line, why);
    }
    void number(std::string_view name, double value, std::string_view why) { key(name, formatShortest(value), why); }
    void text(std::string_view name, const std::string& value, std::string_view why) {
        key(name, tomlString(value), why);
    }
    void comment(std::string_view line) { text_ += fmt::format("# {}\n", line); }
    const std::string& str() const { return text_; }

private:
    std::string text_;
};

// The scene's word for a vertical unit of this many metres.
std::string verticalUnitName(double metresPerUnit) {
    if (metresPerUnit == 0.3048) return "ft";
    if (metresPerUnit == 1200.0 / 3937.0) return "us-ft";
    return "m";
}

std::string zoneName(const geo::Frame& frame) {
    return frame.utmZone == 0 ? std::string("UPS") : fmt::format("{}{}", frame.utmZone, frame.northp ? "N" : "S");
}

void writeData(CommentedScene& out, const scene::SceneSpec& spec, const geo::ControlNet& net,
               const fs::path& scenePath) {
    out.section("samples", "");
    const fs::path data = fs::absolute(spec.samples.path).lexically_normal();
    const fs::path folder = fs::absolute(scenePath).parent_path().lexically_normal();
    // Relative to this file, unless that climbs further than the path from the root.
    const fs::path relative = data.lexically_relative(folder);
    const bool climbs = std::distance(relative.begin(), relative.end()) > std::distance(data.begin(), data.end());
    out.text("path", (climbs ? data : relative).generic_string(), climbs ? "" : "relative to this file");
    if (!net.attribution.empty()) out.comment("attribution: the raster's metadata gives the credit the still shows");
    out.text("resample", std::string(scene::nameOf(net.resample)),
             net.copiedCells ? "not needed: every node is a cell's centre, read as it is"
             : net.resample == spec.samples.resample
                 ? "GDAL's warper at each node"
                 : "the net is coarser than the cells: every cell under a node counts");
    if (!net.raster.empty())
        out.text("vertical_unit", verticalUnitName(net.metresPerUnit),
                 net.verticalUnitAssumed ? "the raster does not say: metres assumed (check, and say so here)"
                                         : "the raster's own");
    out.section("frame", "");
    out.text("kind", std::string(scene::nameOf(net.frame.kind)),
             net.frame.kind == scene::FrameKind::Raster
                 ? fmt::format("{}: the cells are not reprojected", net.frame.crsName)
                 : "");
    if (net.frame.kind == scene::FrameKind::Utm)
        out.text("zone", zoneName(net.frame), "the standard zone of the data's centre");
    out.section("net", fmt::format("{} x {} nodes", net.rows(), net.cols()));
    out.number("spacing_m", net.dx, net.spacingReason);
}

void writeSurface(CommentedScene& out, const LoadedScene& loaded, const Surface& surface) {
    const scene::SceneSpec& spec = loaded.scene;
    out.section("vertical", "");
    out.number("exaggeration", spec.look.vertical.exaggeration, "true heights");
    out.section("subdivision", "");
    out.text("scheme", loaded.resolved.family, "");
    for (const auto& [name, value] : loaded.resolved.params) out.number(name, value, "");
    out.number("depth", surface.depth, surface.depthReason);
    out.section("geometry", "");
    out.text("kind", "auto", fmt::format("{}: {}", scene::nameOf(surface.geometry.kind), surface.geometry.reason));
}

void writeLook(CommentedScene& out, const scene::SceneSpec& spec) {
    const scene::LookSpec& look = spec.look;
    out.section("texture", "");
    out.text(
        "ramp", look.texture.ramp.preset,
        !spec.madeForData.empty() && look.texture.ramp.preset == "topobathy"
            ? fmt::format("the data reach {} m or deeper, a sea floor: blues below 0 m", formatShortest(kSeaFloorM))
            : "elevation colours over the surface's range");
    out.section("lighting", "");
    out.number("sun_azimuth_deg", look.lighting.sunAzimuthDeg, "light from the north-west, as maps have it");
    out.number("sun_altitude_deg", look.lighting.sunAltitudeDeg, "");
    out.section("camera", "the terrain framed whole");
    out.number("azimuth_deg", look.camera.azimuthDeg, "looking from the south-south-west");
    out.number("elevation_deg", look.camera.elevationDeg, "");
    out.number("fov_deg", look.camera.fovDeg, "");
    out.section("render", "");
    out.number("width", spec.render.width, "");
    out.number("height", spec.render.height, "");
    out.section("overlay", "a report's furniture: title, credits, legend, scale bar, north arrow");
    out.text("title", spec.overlay.title, "the raster's metadata, else the file's name");
}

}  // namespace

std::string initSceneText(const LoadedScene& loaded, const Surface& surface, const fs::path& scenePath) {
    CommentedScene out;
    out.comment(fmt::format("The scene relief chose for {}: relief render of this file makes the still",
                            loaded.scene.samples.path.filename().string()));
    out.comment("that relief render of the data alone does. Every key: docs/scene-format.md.");
    writeData(out, loaded.scene, surface.net, scenePath);
    writeSurface(out, loaded, surface);
    writeLook(out, loaded.scene);
    return out.str();
}

}  // namespace relief
