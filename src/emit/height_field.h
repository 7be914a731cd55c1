#pragma once
// Stage 4 of 6, the height_field geometry kind. Input: the refined GeoGrid
// (every node with data) and its ScenePlacement. Output: a 16-bit greyscale
// PNG of its heights and the SDL `height_field` that places it, which POV-Ray
// parses in a fraction of a mesh2's time (0.45 s against 75 s for 6 M
// triangles, measured) because it reads pixels, not text.
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "emit/mesh.h"
#include "geo/geo_grid.h"
#include "geo/raster.h"

namespace relief::emit {

/// The refined lattice's heights as 16-bit levels: level 0 is zMinM, level
/// 65535 zMaxM. POV-Ray spans the image over its unit square, pixel (0, 0) at
/// x = 0, z = 1: row 0 of the image is the northern edge, column 0 the
/// western, so node (r, c) is pixel (c, rows - 1 - r).
struct HeightField {
    int rows = 0, cols = 0;
    std::vector<std::uint16_t> levels;  ///< rows x cols, row 0 north (the PNG's order)
    double zMinM = 0, zMaxM = 0;
    /// The vertical quantization: one level, in metres.
    double stepM() const { return (zMaxM - zMinM) / 65535.0; }
};

/// Quantizes the grid's heights as drawn (ScenePlacement::drawnHeight: in a
/// local frame the Earth's curvature is not exaggerated) to the nearest
/// level, over the range of the nodes with data (masked nodes keep their
/// filled heights, clamped to it: the drape makes them transparent).
HeightField quantizeHeights(const geo::GeoGrid& refined, const ScenePlacement& where);

/// The colour draped on the height field: per node, the palette colour the
/// mesh2 gives its vertex (the ramp over zMinM..zMaxM), linear RGB in 16 bits,
/// rows x cols x channels, row 0 north. POV-Ray interpolates it bilinearly
/// between the nodes, as it interpolates a mesh2's vertex colours across a
/// triangle.
///
/// A height_field has no holes, so a grid with masked nodes gets a fourth
/// channel, alpha, 0 at the masked nodes: POV-Ray takes a PNG's alpha as
/// transmit, so the surface there lets every ray and the sun's light through
/// (no colour, no shadow). Alpha is interpolated like the colour, so the
/// hole's edge lies between a node with data and one without, where the
/// mesh2's lies on the node with data: half a cell, under a pixel at the
/// grid sizes the height field is for.
struct Drape {
    int rows = 0, cols = 0, channels = 3;  ///< RGB, or RGBA when nodes are masked
    std::vector<std::uint16_t> pixels;
};
Drape elevationDrape(const geo::GeoGrid& refined, const ScenePlacement& where);

/// The drape of an image ([texture] image) resampled onto the refined grid:
/// its sRGB colours made linear; nodes the image does not cover keep the
/// ramp's colour; masked nodes are transparent, as in elevationDrape.
Drape imageDrape(const geo::GeoGrid& refined, const ScenePlacement& where, const geo::ImageOnGrid& image);

/// A texture for a mesh (the mesh2 or adaptive kinds) taking its colours from
/// a drape PNG laid flat over the refined grid, its pixel centres on the nodes,
/// as the height field lays its own: the image drape on a mesh.
std::string drapeTextureSdl(const geo::GeoGrid& refined, const ScenePlacement& where, const std::string& drapePng);

/// Write the levels as a 16-bit greyscale PNG and the drape as a 16-bit RGB
/// PNG, atomically and byte for byte the same for the same values. Return ""
/// or the error.
void writeHeightFieldPng(const HeightField& field, const std::filesystem::path& png);
void writeDrapePng(const Drape& drape, const std::filesystem::path& png);

/// The SDL of the height field: the heights' PNG and the drape's by their
/// file names (found through POV-Ray's library path), smooth normals, the
/// drape as a linear (gamma 1) image map whose pixel centres sit on the
/// nodes, scaled and placed where the mesh2 of the same grid would be. The
/// names must be plain file names (see siblingPngName).
void writeHeightFieldSdl(std::FILE* out, const HeightField& field, const geo::GeoGrid& refined,
                         const ScenePlacement& where, const std::string& heightPng, const std::string& drapePng);

/// A PNG's name beside a .pov: "<stem>.<what>.png", every character of the
/// stem outside letters, digits, '.', '-' and '_' made '_', so that it can
/// stand in an SDL string as it is.
std::string siblingPngName(const std::filesystem::path& pov, const std::string& what);

}  // namespace relief::emit
