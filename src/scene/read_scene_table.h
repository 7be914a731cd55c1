#pragma once
// The scene reader on a table made in memory, not parsed from a file: the
// scene relief makes for a DEM (scene_for_data.h). Apart from read_scene.h,
// which needs no toml++ to include.
#include <filesystem>
#include <optional>
#include <string>

#include <toml++/toml.h>

#include "core/diagnostics.h"
#include "scene/read_scene.h"

namespace relief::scene {

/// A scene read once: a scene file's text (the SHA-1 is taken over it), or
/// the table relief makes for data (`record`: that scene's TOML). A film
/// reads each frame's spec from it, the frame's keys set, without reading
/// the file again. A file's text is parsed again for each spec: toml++ does
/// not copy a node's place in the file, and every error must name its line.
struct SceneDocument {
    std::filesystem::path path;
    std::string record;
    std::optional<toml::table> madeForData;  ///< the scene relief made for data; else `record` is the file
};

/// The scene file at `path`, read; nullopt after an error at the file
/// (cannot be read, not a file).
std::optional<SceneDocument> readSceneFileOnce(const std::filesystem::path& path, Diagnostics& diags);

/// The spec of `document` with `overrides` set.
std::optional<SceneSpec> readSceneDocument(const SceneDocument& document, Diagnostics& diags,
                                           const SceneOverrides& overrides = {});

/// readSceneText on a document already made: `root` (its strings may hold
/// any bytes: a file's name that is not UTF-8 still names that file), read as
/// if from `path`; `record` is the text its sceneSha1 is taken over.
std::optional<SceneSpec> readSceneTable(toml::table root, const std::string& record, const std::filesystem::path& path,
                                        Diagnostics& diags, const SceneOverrides& overrides = {});

}  // namespace relief::scene
