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

/// readSceneText on a document already made: `root` (its strings may hold
/// any bytes: a file's name that is not UTF-8 still names that file), read as
/// if from `path`; `record` is the text its sceneSha1 is taken over.
std::optional<SceneSpec> readSceneTable(toml::table root, const std::string& record, const std::filesystem::path& path,
                                        Diagnostics& diags, const SceneOverrides& overrides = {});

}  // namespace relief::scene
