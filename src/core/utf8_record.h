#pragma once
// Records are UTF-8: a JSON sidecar, `relief info --json`, a PDF's or SVG's
// text. A name that is not (a Linux file name may hold any byte but '/' and
// NUL) is written with U+FFFD for each byte that is not, and a run says so
// once.
#include <filesystem>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

#include "core/diagnostics.h"

namespace relief {

/// Every string of `record`, values and keys, made valid UTF-8 (utf8Replaced).
/// Returns the first that was not, as "key.key: value" with the value as it
/// was (for a warning, which shows its bytes as \xNN), or "" when all were.
std::string replaceNotUtf8(nlohmann::ordered_json& record);

/// Warns, once a run, that `what` (a name or a key and its value) is not
/// UTF-8 and that the records write it with U+FFFD.
void warnNotUtf8(Diagnostics& diags, SourceLoc at, std::string_view what);

/// warnNotUtf8 when `text` is not UTF-8.
void checkUtf8(Diagnostics& diags, SourceLoc at, std::string_view text, std::string_view what);

/// A name a record must give back whole (a render plan's files and outputs,
/// a film's): j[key] = name when it is UTF-8; else what it shows as
/// (U+FFFD for each byte that is not) and, beside it, j[key + "_bytes"] =
/// its bytes in hex, which JSON can hold.
void putName(nlohmann::ordered_json& j, const std::string& key, const std::string& name);

/// The name putName wrote at `key`. Throws nlohmann::json::exception when it
/// is not one (a damaged record).
std::string nameAt(const nlohmann::ordered_json& j, const std::string& key);

}  // namespace relief
