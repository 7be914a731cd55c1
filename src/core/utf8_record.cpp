#include "core/utf8_record.h"

#include <fmt/format.h>

#include "core/text_escape.h"

namespace relief {

namespace {

// The first string below `j` that is not UTF-8 ("" if none), named from `at`;
// every such string replaced.
std::string replaceBelow(nlohmann::ordered_json& j, const std::string& at) {
    std::string first;
    const auto note = [&](const std::string& found) {
        if (first.empty()) first = found;
    };
    if (j.is_string()) {
        const std::string& s = j.get_ref<const std::string&>();
        if (isUtf8(s)) return {};
        note(fmt::format("{}: {}", at, s));
        j = utf8Replaced(s);
        return first;
    }
    if (j.is_array()) {
        for (size_t i = 0; i < j.size(); ++i) note(replaceBelow(j[i], fmt::format("{}[{}]", at, i)));
        return first;
    }
    if (!j.is_object()) return {};
    bool keysValid = true;
    for (auto& [key, value] : j.items()) {
        const std::string name = at.empty() ? key : at + "." + key;
        if (!isUtf8(key)) note(fmt::format("{} (a key)", name)), keysValid = false;
        note(replaceBelow(value, name));
    }
    if (keysValid) return first;
    // Keys cannot be changed in place: the object made again, in the same order.
    nlohmann::ordered_json valid = nlohmann::ordered_json::object();
    for (auto& [key, value] : j.items()) valid[utf8Replaced(key)] = std::move(value);
    j = std::move(valid);
    return first;
}

}  // namespace

std::string replaceNotUtf8(nlohmann::ordered_json& record) { return replaceBelow(record, ""); }

void warnNotUtf8(Diagnostics& diags, SourceLoc at, std::string_view what) {
    diags.warningOnce("not UTF-8", std::move(at),
                      fmt::format("{} is not UTF-8: the sidecar, info --json and a PDF's or SVG's text write each "
                                  "byte that is not as U+FFFD, here and in any other such name or text (a UTF-8 "
                                  "name or text keeps it whole)",
                                  what));
}

void checkUtf8(Diagnostics& diags, SourceLoc at, std::string_view text, std::string_view what) {
    if (!isUtf8(text)) warnNotUtf8(diags, std::move(at), what);
}

void putName(nlohmann::ordered_json& j, const std::string& key, const std::string& name) {
    j[key] = utf8Replaced(name);
    if (!isUtf8(name)) j[key + "_bytes"] = hexBytes(name);
}

std::string nameAt(const nlohmann::ordered_json& j, const std::string& key) {
    const std::string bytesKey = key + "_bytes";
    if (!j.contains(bytesKey)) return j.at(key).get<std::string>();
    const auto name = bytesOfHex(j.at(bytesKey).get<std::string>());
    if (!name) throw nlohmann::json::other_error::create(501, bytesKey + " is not two hex digits a byte", &j);
    return *name;
}

}  // namespace relief
