#include "emit/height_field.h"

#include <algorithm>
#include <array>
#include <cmath>

#include <fmt/format.h>

#include "core/png_file.h"
#include "core/number_format.h"

namespace relief::emit {

namespace {
// Stored, not deflated: the PNGs are read once, by POV-Ray. For 2373 x 1621
// nodes the emit stage took 0.91 s at zlib's default level, 0.44 s at level 1
// and 0.31 s stored (30.8 MB against 7.8 MB on disk): what the user waits for
// comes first.
constexpr int kPngCompression = 0;
}  // namespace

HeightField quantizeHeights(const geo::GeoGrid& refined, const ScenePlacement& where) {
    const Grid& g = refined.grid;
    HeightField field;
    field.rows = g.rows;
    field.cols = g.cols;
    double zmin = 1e300, zmax = -1e300;
    for (size_t i = 0; i < g.points.size(); ++i) {
        if (!refined.masked.empty() && refined.masked[i]) continue;
        const double h = where.drawnHeight(g.points[i]);
        zmin = std::min(zmin, h), zmax = std::max(zmax, h);
    }
    if (zmin > zmax) zmin = zmax = 0;  // every node masked: nothing to see
    if (flatRange(zmin, zmax)) zmax = zmin;
    field.zMinM = zmin;
    field.zMaxM = zmax;
    const double perLevel = zmax > zmin ? 65535.0 / (zmax - zmin) : 0.0;  // a flat grid: every level 0
    field.levels.resize(g.points.size());
    for (int r = 0; r < g.rows; ++r) {
        std::uint16_t* row = field.levels.data() + static_cast<size_t>(g.rows - 1 - r) * g.cols;
        for (int c = 0; c < g.cols; ++c)
            row[c] = static_cast<std::uint16_t>(
                std::clamp(std::lround((where.drawnHeight(g.at(r, c)) - zmin) * perLevel), 0L, 65535L));
    }
    return field;
}

void writeHeightFieldPng(const HeightField& field, const std::filesystem::path& png) {
    writePngAtomically(png, {field.cols, field.rows, 1, true, field.levels.data(), kPngCompression});
}

namespace {

// A drape PNG as a linear image map laid flat (x east, z north): the unit
// square scaled by (sx, sz) and moved by (tx, tz), each line after `indent`.
std::string drapeTexture(const std::string& png, double sx, double sz, double tx, double tz, const char* indent) {
    return fmt::format(
        "{0}texture {{\n"
        "{0}  pigment {{\n"
        "{0}    image_map {{ png \"{1}\" gamma 1.0 map_type 0 interpolate 2 }}\n"
        "{0}    rotate x*90\n"
        "{0}    scale <{2}, 1, {3}>\n"
        "{0}    translate <{4}, 0, {5}>\n"
        "{0}  }}\n"
        "{0}  finish {{ TerrainFinish }}\n"
        "{0}}}",
        indent, png, fixedNumber(sx), fixedNumber(sz), fixedNumber(tx), fixedNumber(tz));
}
}  // namespace

void writeHeightFieldSdl(std::FILE* out, const HeightField& field, const geo::GeoGrid& refined,
                         const ScenePlacement& where, const std::string& heightPng, const std::string& drapePng) {
    // The unit square's corners and the unit height, in scene units: exactly
    // where the mesh2 would put the nodes.
    const double s = 1.0 / where.metresPerUnit, zs = where.exaggeration * s;
    const SceneVec3 sw{(refined.x0 - where.originM.x) * s, field.zMinM * zs, (refined.y0 - where.originM.y) * s};
    const SceneVec3 ne{(refined.xMax() - where.originM.x) * s, field.zMaxM * zs,
                       (refined.yMax() - where.originM.y) * s};
    const double height = field.zMaxM > field.zMinM ? ne.y - sw.y : 1e-6;
    // The image map spans the unit square with its pixels' edges; the nodes
    // are at i / (n - 1): so pixel centres (i + 0.5) / n go onto them.
    const double cols = field.cols, rows = field.rows;
    const std::string sdl = fmt::format(
        "height_field {{\n"
        "  png \"{}\"\n"
        "  smooth\n"
        "{}\n"
        "  scale <{}, {}, {}>\n"
        "  translate <{}, {}, {}>\n"
        "}}",
        heightPng, drapeTexture(drapePng, cols / (cols - 1), rows / (rows - 1), -0.5 / (cols - 1), -0.5 / (rows - 1), "  "),
        fixedNumber(ne.x - sw.x), fixedNumber(height), fixedNumber(ne.z - sw.z), fixedNumber(sw.x),
        fixedNumber(sw.y), fixedNumber(sw.z));
    std::fwrite(sdl.data(), 1, sdl.size(), out);
}

Drape elevationDrape(const geo::GeoGrid& refined, const ScenePlacement& where) {
    const Grid& g = refined.grid;
    Drape drape;
    drape.rows = g.rows;
    drape.cols = g.cols;
    drape.channels = refined.masked.empty() ? 3 : 4;
    const size_t n = static_cast<size_t>(drape.channels);
    drape.pixels.resize(g.points.size() * n);
    auto level = [](double v) { return static_cast<std::uint16_t>(std::clamp(std::lround(v * 65535), 0L, 65535L)); };
    for (int r = 0; r < g.rows; ++r) {
        std::uint16_t* row = drape.pixels.data() + static_cast<size_t>(g.rows - 1 - r) * g.cols * n;
        for (int c = 0; c < g.cols; ++c) {
            // The mesh2's palette entry for this node, and its colour.
            using C = scene::TextureSpec::Colouring;
            const double e = where.elevation(g.at(r, c));
            const bool slope = where.colouring == C::Slope || where.colouring == C::Blend;
            const auto& colour =
                where.paletteColors[slope ? paletteEntry(where, e, slopeDeg(refined, where, r, c)) : paletteIndex(where, e)];
            const LinearRgb drawn = where.nodeColour(static_cast<size_t>(r) * g.cols + c, colour);
            std::uint16_t* px = row + n * static_cast<size_t>(c);
            px[0] = level(drawn.r), px[1] = level(drawn.g), px[2] = level(drawn.b);
            if (n == 4) px[3] = refined.isMasked(r, c) ? 0 : 65535;
        }
    }
    return drape;
}

Drape imageDrape(const geo::GeoGrid& refined, const ScenePlacement& where, const geo::ImageOnGrid& image) {
    Drape drape = elevationDrape(refined, where);  // the ramp where the image has no data; the mask
    const Grid& g = refined.grid;
    const size_t n = static_cast<size_t>(drape.channels);
    // sRGB to linear (IEC 61966-2-1), one entry a byte value.
    std::array<std::uint16_t, 256> linear{};
    for (int v = 0; v < 256; ++v) {
        const double s = v / 255.0;
        const double l = s <= 0.04045 ? s / 12.92 : std::pow((s + 0.055) / 1.055, 2.4);
        linear[v] = static_cast<std::uint16_t>(std::lround(l * 65535));
    }
    for (int r = 0; r < g.rows; ++r) {
        std::uint16_t* row = drape.pixels.data() + static_cast<size_t>(g.rows - 1 - r) * g.cols * n;
        for (int c = 0; c < g.cols; ++c) {
            const size_t node = static_cast<size_t>(r) * g.cols + c;
            if (!image.covered[node]) continue;
            std::uint16_t* px = row + n * static_cast<size_t>(c);
            const double light = where.skyLightAt(node);
            if (where.tinted(node)) {  // a fill or fade laid over the image: its colour as a fraction, tinted and lit
                const LinearRgb drawn = where.nodeColour(
                    node, {linear[image.rgb[3 * node]] / 65535.0, linear[image.rgb[3 * node + 1]] / 65535.0,
                           linear[image.rgb[3 * node + 2]] / 65535.0});
                px[0] = static_cast<std::uint16_t>(std::lround(drawn.r * 65535));
                px[1] = static_cast<std::uint16_t>(std::lround(drawn.g * 65535));
                px[2] = static_cast<std::uint16_t>(std::lround(drawn.b * 65535));
                continue;
            }
            for (int k = 0; k < 3; ++k)
                px[k] = light == 1.0 ? linear[image.rgb[3 * node + k]]
                                     : static_cast<std::uint16_t>(std::lround(light * linear[image.rgb[3 * node + k]]));
        }
    }
    return drape;
}

std::string drapeTextureSdl(const geo::GeoGrid& refined, const ScenePlacement& where, const std::string& drapePng) {
    const double s = 1.0 / where.metresPerUnit;
    const double west = (refined.x0 - where.originM.x) * s, south = (refined.y0 - where.originM.y) * s;
    const double width = (refined.xMax() - refined.x0) * s, depth = (refined.yMax() - refined.y0) * s;
    const double cols = refined.cols(), rows = refined.rows();
    // Pixel i's centre, (i + 0.5) / n of the map, on node i: the map spans
    // n / (n - 1) node spacings, starting half a spacing west (south) of node 0.
    std::string sdl(1, '\n');
    sdl += drapeTexture(drapePng, width * cols / (cols - 1), depth * rows / (rows - 1),
                        west - 0.5 * width / (cols - 1), south - 0.5 * depth / (rows - 1), "");
    return sdl;
}

void writeDrapePng(const Drape& drape, const std::filesystem::path& png) {
    writePngAtomically(png, {drape.cols, drape.rows, drape.channels, true, drape.pixels.data(), kPngCompression});
}

std::string siblingPngName(const std::filesystem::path& pov, const std::string& what) {
    std::string stem = pov.stem().string();
    for (char& ch : stem)
        if (!std::isalnum(static_cast<unsigned char>(ch)) && ch != '.' && ch != '-' && ch != '_') ch = '_';
    return stem + "." + what + ".png";
}

}  // namespace relief::emit
