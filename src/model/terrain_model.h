#pragma once
// Stage 4, the other way out: the terrain as a 3-D model (relief export),
// for a 3-D printer, Blender or a web page. Input: the mesh the still would
// render (emit::Mesh: the same depth, exaggeration, colours, masked nodes
// left out). Output: a TerrainModel, a plain value of triangles, and the file
// written from it, glTF by tinygltf, STL, OBJ and PLY by Assimp.
#include <array>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "core/types.h"
#include "emit/mesh.h"

namespace relief::model {

enum class ModelFormat { Glb, Gltf, Stl, Obj, Ply };

/// A format relief writes, named by its file's extension. Y-up formats
/// (glTF, and OBJ as Blender and three.js read it) take the model's
/// (east, north, up) as (x, -z, y); the others keep z up.
struct ModelFormatRow {
    ModelFormat format;
    const char* extension;  ///< with its dot, lower case
    const char* name;
    bool yUp;
    bool solid;  ///< a model for printing: always closed with walls and a floor
};
std::span<const ModelFormatRow> modelFormats();
/// The row of `path`'s extension (any case); null when relief writes no such format.
const ModelFormatRow* modelFormatOf(const std::filesystem::path& path);
/// "`.glb`, `.gltf`, `.stl`, `.obj` or `.ply`", for messages.
std::string modelExtensionsListed();

/// A named set of the model's triangles: a glTF mesh of its own.
struct ModelPart {
    std::string name;  ///< "surface", "walls", "floor"
    std::vector<std::array<std::uint32_t, 3>> faces;  ///< counter-clockwise seen from outside the solid (above, for the surface)
};

/// The terrain as triangles in a right-handed frame: x east, y north, z up,
/// in metres from the scene's origin (the net's centre), heights exaggerated
/// as rendered; or scaled (scaleAcross). Colours are linear RGB, one a vertex.
struct TerrainModel {
    std::vector<Vec3> positions;
    std::vector<LinearRgb> colours;
    /// Unit, a vertex: the surface's the full refined surface's (as the .pov's
    /// mesh2), the floor's straight down, a wall's square to it, outwards (the
    /// walls have vertices of their own, so that a viewer shades them flat).
    std::vector<Vec3> normals;
    std::vector<ModelPart> parts;
    double unitsPerMetre = 1;  ///< 1: metres; scaleAcross's millimetres per metre

    size_t triangles() const;
    /// The part named `name`, or null.
    const ModelPart* part(const std::string& name) const;
};

/// The model of `mesh` (its faces, or the lattice's cells cut as the .pov
/// cuts them). With `floorElevationM`: a closed solid, its walls dropped from
/// every edge of the surface that one triangle alone has (the outline, and
/// holes where nodes have no data) to a floor at that true elevation, which
/// is the surface's own triangles laid flat, facing down, so that every edge
/// (by its corners' positions) belongs to exactly two triangles.
/// `nodeColours`: each refined node's colour (a draped image's, as the drape
/// PNG has it), else the mesh's own (nodeColour: its ramp, fills, fade and
/// sky light, as `where` has them).
TerrainModel terrainModel(const emit::Mesh& mesh, std::optional<double> floorElevationM,
                          std::span<const LinearRgb> nodeColours = {});

/// Scales the model so that its wider horizontal extent is `acrossMM`
/// millimetres (a print's size), about the origin.
void scaleAcross(TerrainModel& model, double acrossMM);

/// `model` as `format`'s bytes (what writeModel writes; what relief preview
/// serves). Throws std::runtime_error with the library's reason when it cannot.
std::string modelBytes(const TerrainModel& model, const ModelFormatRow& format, const std::string& generator);

/// Writes `model` as `format` to `path` (which must be new: a staged output).
/// `generator` names the program in the file where the format has room.
/// Throws std::runtime_error with the library's reason when it cannot.
void writeModel(const TerrainModel& model, const ModelFormatRow& format, const std::filesystem::path& path,
                const std::string& generator);

}  // namespace relief::model
