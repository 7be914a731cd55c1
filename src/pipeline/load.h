#pragma once
// The pipeline's first room: the scene loaded, from a scene file (TOML) or
// from elevation data named where a scene goes (relief render dem.tif:
// the scene relief makes for it), validated and its scheme resolved.
#include <filesystem>
#include <memory>
#include <optional>
#include <string>

#include "core/diagnostics.h"
#include "scene/scene_spec.h"
#include "subdiv/budget.h"
#include "subdiv/resolve.h"

namespace relief::scene {
struct SceneDocument;  // scene/read_scene_table.h
}

namespace relief {

/// Stage 1 and the scheme: everything the scene file says, checked.
struct LoadedScene {
    scene::SceneSpec scene;
    subdiv::ResolvedScheme resolved;
    /// What the job is held to ([limits], the memory this machine's unless
    /// they say): made once here, read by every stage after.
    subdiv::Budget budget;
    double seconds = 0;
};

/// Reads and validates the scene file and resolves its scheme, reporting every
/// problem at once. Nothing is written.
std::optional<LoadedScene> loadScene(const std::filesystem::path& scenePath, Diagnostics& diags,
                                     const scene::SceneOverrides& overrides = {});

/// The scene named `scenePath` read once: a scene file parsed, or the scene
/// relief makes for data named in its place. Nullopt after an error.
std::shared_ptr<const scene::SceneDocument> readSceneDocument(const std::filesystem::path& scenePath,
                                                              Diagnostics& diags);
/// A scene read before, loaded with `overrides` set (a film's frame): the
/// file is not read again.
std::optional<LoadedScene> loadScene(const scene::SceneDocument& document, Diagnostics& diags,
                                     const scene::SceneOverrides& overrides = {});

/// What a file named in place of a scene is.
enum class InputKind {
    Scene,    ///< a scene file (TOML), or a file that is not there (the scene reader says so)
    Raster,   ///< a raster GDAL opens (GeoTIFF, SRTM .hgt, ESRI ASCII grid, VRT, ...), or a folder of them
    Samples,  ///< a CSV of lon,lat,elev samples
    Neither,  ///< none of these; `why` says what it is not
};
InputKind inputKindOf(const std::filesystem::path& path, std::string& why);

/// The elevation (metres) at or below which data hold a sea floor, not dry
/// land: their scene takes the topobathy ramp.
inline constexpr double kSeaFloorM = -500;

/// The scene relief makes for elevation data given alone, as a document:
/// [samples] path (the file's name, whatever its bytes: the scene is read as
/// if it were the file, from its folder), the topobathy ramp for a raster
/// reaching kSeaFloorM, and a title from the raster's metadata or the file's
/// name. Every other choice is relief's default: the net and the depth for
/// the still. Its record (TOML, for the sidecar) becomes the spec's `madeForData`.
scene::SceneDocument sceneDocumentForData(const std::filesystem::path& data);

/// That scene's record, as the sidecar keeps it: TOML text, with U+FFFD for
/// the bytes of a name that are not UTF-8.
std::string sceneTextForData(const std::filesystem::path& data);

}  // namespace relief
