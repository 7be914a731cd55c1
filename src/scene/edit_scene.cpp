#include "scene/edit_scene.h"

#include <algorithm>
#include <map>
#include <regex>

#include <fmt/format.h>
#include <toml++/toml.h>

namespace relief::scene {

namespace {

// The text as lines, each with its own line ending (the last may have none).
std::vector<std::string> linesOf(std::string_view text) {
    std::vector<std::string> lines;
    size_t at = 0;
    while (at < text.size()) {
        const size_t end = text.find('\n', at);
        const size_t next = end == std::string_view::npos ? text.size() : end + 1;
        lines.emplace_back(text.substr(at, next - at));
        at = next;
    }
    return lines;
}

// Where a key's value sits: its first and last lines (0-based) and, on the
// last, the byte just past it (what follows, a comment, is kept).
struct ValueSpan {
    size_t firstLine = 0, lastLine = 0, endByte = 0;
};
ValueSpan spanOf(const toml::node& value) {
    const auto& s = value.source();
    return {static_cast<size_t>(s.begin.line - 1), static_cast<size_t>(s.end.line - 1),
            static_cast<size_t>(std::max<int>(s.end.column - 1, 0))};
}

// The key's lines with its value replaced: the first line up to its '=' (the
// key as the author wrote it), the new value, the last line's rest.
std::string replacedValue(const std::vector<std::string>& lines, const ValueSpan& span, const std::string& value,
                          const std::string& newline) {
    const std::string& first = lines[span.firstLine];
    const std::string& last = lines[span.lastLine];
    const size_t eq = first.find('=');
    const std::string rest = span.endByte < last.size() ? last.substr(span.endByte) : newline;
    return first.substr(0, eq + 1) + " " + value + rest;
}

}  // namespace

std::optional<std::string> withTableKeys(std::string_view text, const std::string& shown, const std::string& table,
                                         const std::vector<TomlKeyValue>& values, std::span<const std::string> retired,
                                         Diagnostics& diags, const std::vector<TomlKeyValue>& defaults) {
    toml::table root;
    try {
        root = toml::parse(text, shown);
    } catch (const toml::parse_error& e) {
        diags.error({shown, static_cast<int>(e.source().begin.line), static_cast<int>(e.source().begin.column)},
                    fmt::format("{}: fix the file, then use the view again", e.description()));
        return std::nullopt;
    }
    // New lines end as the file's do (a file written on Windows keeps its CRLF).
    const std::string newline = text.find("\r\n") != std::string_view::npos ? "\r\n" : "\n";
    std::vector<std::string> lines = linesOf(text);
    if (!lines.empty() && lines.back().back() != '\n') lines.back() += newline;
    const toml::table* t = root[table].as_table();
    if (!t) {
        std::string out;
        for (const auto& l : lines) out += l;
        out += fmt::format("{}[{}]{}", lines.empty() ? "" : newline, table, newline);
        for (const auto& [key, value] : values) out += fmt::format("{} = {}{}", key, value, newline);
        for (const auto& [key, value] : defaults) out += fmt::format("{} = {}{}", key, value, newline);
        return out;
    }
    const size_t header = static_cast<size_t>(std::max<int>(t->source().begin.line - 1, 0));
    const std::regex headerLine(fmt::format(R"(^\s*\[\s*{}\s*\].*)", table));
    const auto withoutEnding = [](std::string line) {
        while (!line.empty() && (line.back() == '\n' || line.back() == '\r')) line.pop_back();
        return line;
    };
    if (t->is_inline() || header >= lines.size() || !std::regex_match(withoutEnding(lines[header]), headerLine)) {
        diags.error({shown, static_cast<int>(header + 1), 0},
                    fmt::format("{} is written inline or as dotted keys: write it as a [{}] table, then use the view again",
                                table, table));
        return std::nullopt;
    }
    // Per line, what replaces it (a key's lines become one; a retired key's are commented out).
    std::map<size_t, std::string> replaced;
    std::vector<size_t> dropped;
    // The table's own keys end at its last value's last line (a sub-table's header and keys,
    // [camera.x], are not its: new keys go before them). A key replaced is written where its value
    // began, so a new key after the last goes after that line.
    size_t lastKey = header, insertAfter = header;
    for (auto&& [key, node] : *t) {
        if ((node.is_table() && !node.as_table()->is_inline()) || node.is_array_of_tables()) continue;
        const ValueSpan span = spanOf(node);
        if (span.lastLine >= lastKey) lastKey = span.lastLine, insertAfter = span.lastLine;
    }
    std::vector<TomlKeyValue> added;
    const auto isSet = [&](const std::string& key) {
        return std::any_of(values.begin(), values.end(), [&](const TomlKeyValue& kv) { return kv.first == key; });
    };
    for (const auto& [key, value] : values) {
        const toml::node* node = t->get(key);
        if (!node) {
            added.push_back({key, value});
            continue;
        }
        const ValueSpan span = spanOf(*node);
        replaced[span.firstLine] = replacedValue(lines, span, value, newline);
        for (size_t l = span.firstLine + 1; l <= span.lastLine; ++l) dropped.push_back(l);
        if (span.lastLine == lastKey) insertAfter = span.firstLine;
    }
    for (const auto& [key, value] : defaults)
        if (!t->get(key)) added.push_back({key, value});
    for (const std::string& key : retired)  // a key both set and retired is set
        if (const toml::node* node = t->get(key); node && !isSet(key)) {
            const ValueSpan span = spanOf(*node);
            for (size_t l = span.firstLine; l <= span.lastLine; ++l) replaced[l] = "# " + lines[l];
        }
    std::string out;
    for (size_t l = 0; l < lines.size(); ++l) {
        if (std::find(dropped.begin(), dropped.end(), l) != dropped.end()) continue;
        const auto r = replaced.find(l);
        out += r == replaced.end() ? lines[l] : r->second;
        if (l == insertAfter)
            for (const auto& [key, value] : added) out += fmt::format("{} = {}{}", key, value, newline);
    }
    return out;
}

}  // namespace relief::scene
