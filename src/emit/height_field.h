#pragma once
// Stage 4 of 5, the height_field geometry kind. Input: the refined GeoGrid
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
/// level. The grid must have no masked nodes: a height_field has no holes.
HeightField quantizeHeights(const geo::GeoGrid& refined, const ScenePlacement& where);

/// The colour draped on the height field: per node, the palette colour the
/// mesh2 gives its vertex (the ramp over zMinM..zMaxM), linear RGB in 16 bits,
/// rows x cols x 3, row 0 north. POV-Ray interpolates it bilinearly between
/// the nodes, as it interpolates a mesh2's vertex colours across a triangle.
struct Drape {
    int rows = 0, cols = 0;
    std::vector<std::uint16_t> rgb;
};
Drape elevationDrape(const geo::GeoGrid& refined, const ScenePlacement& where);

/// Write the levels as a 16-bit greyscale PNG and the drape as a 16-bit RGB
/// PNG, atomically and byte for byte the same for the same values. Return ""
/// or the error.
std::string writeHeightFieldPng(const HeightField& field, const std::filesystem::path& png);
std::string writeDrapePng(const Drape& drape, const std::filesystem::path& png);

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
