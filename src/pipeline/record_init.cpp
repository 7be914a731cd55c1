// relief init's scene: the scene relief makes for elevation data, written
// out as TOML (values by toml++, never pasted), every key with the value
// chosen and why.
#include <sstream>

#include <fmt/format.h>
#include <toml++/toml.h>

#include "core/number_format.h"
#include "core/text_escape.h"
#include "pipeline/record.h"
#include "scene/enum_names.h"

namespace relief {

namespace fs = std::filesystem;

std::string tomlString(const std::string& text) {
    // A basic string on one line: toml++ writes a string holding ' and a line break as a literal
    // ('''...''') that a ''' inside it closes, and a multi-line one would carry the line breaks
    // into the file. Escapes only ("\n", "\"", "\u0001") hold any text whole.
    std::ostringstream out;
    const toml::value<std::string> value(utf8Replaced(text));
    out << toml::toml_formatter(value, toml::format_flags::allow_unicode_strings);
    return out.str();
}

namespace {

// A TOML file written a key at a time, each with the reason for its value.
// Values are written by toml++ (tomlString); keys and sections are relief's
// own bare names. A comment is relief's text, but may quote the data (a CRS's
// name, a file's): always on one line, control characters as \xNN, so no
// text of a file can end a comment and start a key.
class CommentedScene {
public:
    void section(std::string_view name, std::string_view about) {
        text_ += fmt::format("{}[{}]{}\n", text_.empty() ? "" : "\n", name,
                             about.empty() ? "" : "  # " + oneLineText(about));
    }
    void key(std::string_view name, const std::string& value, std::string_view why) {
        const std::string line = fmt::format("{} = {}", name, value);
        text_ += why.empty() ? line + "\n" : fmt::format("{:<28}  # {}\n", line, oneLineText(why));
    }
    void number(std::string_view name, double value, std::string_view why) { key(name, formatShortest(value), why); }
    void text(std::string_view name, const std::string& value, std::string_view why) {
        key(name, tomlString(value), why);
    }
    void comment(std::string_view line) { text_ += fmt::format("# {}\n", oneLineText(line)); }
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
               const std::string& path) {
    out.section("samples", "");
    out.text("path", path, fs::path(path).is_absolute() ? "" : "relative to this file");
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

std::string samplesPathFromScene(const fs::path& dataPath, const fs::path& scenePath) {
    const fs::path data = fs::absolute(dataPath).lexically_normal();
    const fs::path folder = fs::absolute(scenePath).parent_path().lexically_normal();
    const fs::path relative = data.lexically_relative(folder);
    // Relative to the scene's file, unless that climbs further than the path from the root.
    const bool climbs = std::distance(relative.begin(), relative.end()) > std::distance(data.begin(), data.end());
    return (climbs ? data : relative).generic_string();
}

bool initCanNameData(const fs::path& data, const fs::path& scenePath, Diagnostics& diags) {
    const std::string path = samplesPathFromScene(data, scenePath);
    if (isUtf8(path)) return true;
    diags.error({data.string(), 0, 0},
                fmt::format("the scene would say samples.path = \"{}\", which is not UTF-8, and TOML holds only "
                            "UTF-8: rename the file (or its folder) to a UTF-8 name and run relief init again "
                            "(relief render reads the file as it is named)",
                            path));
    return false;
}

std::string initSceneText(const LoadedScene& loaded, const Surface& surface, const fs::path& scenePath) {
    const fs::path& data = loaded.scene.samples.path;
    const std::string path = samplesPathFromScene(data, scenePath);  // UTF-8: initCanNameData said so
    CommentedScene out;
    out.comment(fmt::format("The scene relief chose for {}: relief render of this file makes the still",
                            data.filename().string()));
    out.comment("that relief render of the data alone does. Every key: docs/scene-format.md.");
    writeData(out, loaded.scene, surface.net, path);
    writeSurface(out, loaded, surface);
    writeLook(out, loaded.scene);
    return out.str();
}

}  // namespace relief
