#pragma once
// Elevation data named where a scene file goes (relief render dem.tif, relief
// info, relief init): what the file is, the scene relief makes for it, and
// that scene written out with every choice relief made and why.
#include <filesystem>
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

/// The scene relief makes for elevation data given alone: [samples] path (the
/// file's name: the scene is read as if it were the file, from its folder),
/// the topobathy ramp for a raster reaching kSeaFloorM, and a title from the
/// raster's metadata or the file's name. Every other choice is relief's
/// default: the net and the depth for the still.
std::string sceneTextForData(const std::filesystem::path& data);

/// `relief init`: the scene as a TOML file at `scenePath`, every choice
/// written with the value relief made and a comment saying why, in the
/// order of docs/scene-format.md. Rendering it gives the still that
/// rendering `loaded`'s scene does.
std::string initSceneText(const LoadedScene& loaded, const Surface& surface, const std::filesystem::path& scenePath);

/// A TOML basic string (quoted and escaped) holding `text`.
std::string tomlString(const std::string& text);

}  // namespace relief
