#pragma once
#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/diagnostics.h"
#include "scene/scene_spec.h"

namespace relief::scene {

/// Reads and validates a scene file. Reports every problem it finds in `diags`
/// (TOML syntax, unknown keys with a suggestion, wrong types, values out of
/// range, with the unit). Returns nullopt only when the file cannot be read
/// or is not valid TOML; otherwise the description with defaults filled in,
/// which callers must not use when `diags.hasErrors()` (they may add their own
/// checks first, such as the scheme's parameters, so that every problem is
/// reported at once).
/// `overrides` (section.key = value, see SceneOverrides) are applied on top
/// of the file before validation.
std::optional<SceneSpec> readScene(const std::filesystem::path& path, Diagnostics& diags,
                                   const SceneOverrides& overrides = {});

/// The same for a scene's text, as if read from `path` (which names it in
/// messages and is the folder its paths are resolved against): the scene
/// relief makes for a DEM (scene_for_data.h).
std::optional<SceneSpec> readSceneText(const std::string& text, const std::filesystem::path& path, Diagnostics& diags,
                                       const SceneOverrides& overrides = {});

/// Parses a number written as a TOML float/integer or as a string fraction
/// such as "7/32" or "-1/16". Returns nullopt if it is neither.
std::optional<double> parseFraction(std::string_view text);

}  // namespace relief::scene
