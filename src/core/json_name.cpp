#include "core/json_name.h"

#include "core/text_escape.h"

namespace relief {

void putName(nlohmann::ordered_json& j, const std::string& key, const std::string& name) {
    if (isUtf8(name)) {
        j[key] = name;
        return;
    }
    j[key] = oneLineText(name);
    j[key + "_bytes"] = hexBytes(name);
}

std::string nameAt(const nlohmann::ordered_json& j, const std::string& key) {
    const std::string bytesKey = key + "_bytes";
    if (!j.contains(bytesKey)) return j.at(key).get<std::string>();
    const auto name = bytesOfHex(j.at(bytesKey).get<std::string>());
    if (!name) throw nlohmann::json::other_error::create(501, "a name's bytes are not hex digits", nullptr);
    return *name;
}

}  // namespace relief
