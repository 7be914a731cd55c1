#pragma once
// A scene file changed by relief (relief preview's "Use this view"): keys of
// one table set in the file's own text, every other line (comments, order,
// spacing) kept as the author wrote it.
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "core/diagnostics.h"

namespace relief::scene {

/// A key and its value as TOML text. The values are relief's own (numbers and
/// arrays of numbers it formats), never text a user or a file gave.
using TomlKeyValue = std::pair<std::string, std::string>;

/// `text` (a scene file's, named `shown` in errors) with table `table`'s keys
/// set: each key it has keeps its line and trailing comment, its value
/// replaced; a key it lacks is added after the table's last key (the table
/// appended when the file has none); each key in `retired` is commented out
/// (kept for the author to see, no longer read); each of `defaults` is added
/// only where the table lacks the key (a value the author chose is kept).
/// nullopt, after an error at
/// the table, when the text does not parse or the table is written inline
/// or as dotted keys only (there is no [table] to add keys to).
std::optional<std::string> withTableKeys(std::string_view text, const std::string& shown, const std::string& table,
                                         const std::vector<TomlKeyValue>& values, std::span<const std::string> retired,
                                         Diagnostics& diags, const std::vector<TomlKeyValue>& defaults = {});

}  // namespace relief::scene
