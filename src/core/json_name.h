#pragma once
// A file name in a JSON record (a plan, a film's record). JSON holds UTF-8,
// a Linux name is any bytes: a name that is not UTF-8 is written as what it
// shows as, with its bytes in hex beside it, so that the real name comes back.
#include <string>

#include <nlohmann/json.hpp>

namespace relief {

/// j[key] = name; when `name` is not UTF-8, also j[key + "_bytes"] = its bytes in hex.
void putName(nlohmann::ordered_json& j, const std::string& key, const std::string& name);

/// The name putName wrote at `key`. Throws nlohmann::json::exception when it is not one.
std::string nameAt(const nlohmann::ordered_json& j, const std::string& key);

}  // namespace relief
