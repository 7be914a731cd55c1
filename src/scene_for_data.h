#pragma once
// Elevation data named where a scene file goes (relief render dem.tif, relief
// info, relief init): what the file is, the scene relief makes for it, and
// that scene written out with every choice relief made and why.
#include <filesystem>
#include <optional>
#include <string>

#include "pipeline.h"

namespace relief {

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

/// The scene relief makes for elevation data given alone, read: [samples]
/// path (the file's name, whatever its bytes: the scene is read as if it were
/// the file, from its folder), the topobathy ramp for a raster reaching
/// kSeaFloorM, and a title from the raster's metadata or the file's name.
/// Every other choice is relief's default: the net and the depth for the
/// still. Its `madeForData` is sceneTextForData's.
std::optional<scene::SceneSpec> readSceneForData(const std::filesystem::path& data, Diagnostics& diags,
                                                 const scene::SceneOverrides& overrides = {});

/// That scene's record, as the sidecar keeps it: TOML text, with U+FFFD for
/// the bytes of a name that are not UTF-8.
std::string sceneTextForData(const std::filesystem::path& data);

/// `relief init`: the scene as a TOML file at `scenePath`, every choice
/// written with the value relief made and a comment saying why, in the
/// order of docs/scene-format.md. Rendering it gives the still that
/// rendering `loaded`'s scene does.
/// The data's path must be UTF-8 (initCanNameData).
std::string initSceneText(const LoadedScene& loaded, const Surface& surface, const std::filesystem::path& scenePath);

/// The path a scene at `scenePath` names `data` by: relative to the scene's
/// folder, unless that climbs further than the path from the root.
std::string samplesPathFromScene(const std::filesystem::path& data, const std::filesystem::path& scenePath);

/// Whether relief init's scene at `scenePath` can name `data`: TOML holds only
/// UTF-8, and a Linux name may be any bytes. If not, an error at the file
/// saying to rename it.
bool initCanNameData(const std::filesystem::path& data, const std::filesystem::path& scenePath, Diagnostics& diags);

/// A TOML basic string on one line (quoted, every control character, quote
/// and line break escaped) holding `text`; bytes that are not UTF-8 as U+FFFD.
std::string tomlString(const std::string& text);

}  // namespace relief
