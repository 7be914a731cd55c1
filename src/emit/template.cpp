#include "emit/template.h"

#include <set>
#include <vector>

#include <fmt/format.h>

namespace relief::emit {

namespace {

struct Placeholder {
    size_t begin, end;  // [begin, end) covers "{{name}}"
    std::string name;
    int line, column;
};

std::vector<Placeholder> findPlaceholders(const std::string& text) {
    std::vector<Placeholder> out;
    int line = 1;
    size_t lineStart = 0;
    for (size_t i = 0; i + 1 < text.size(); ++i) {
        if (text[i] == '\n') {
            ++line;
            lineStart = i + 1;
            continue;
        }
        if (text[i] != '{' || text[i + 1] != '{') continue;
        const size_t close = text.find("}}", i + 2);
        if (close == std::string::npos) break;
        out.push_back({i, close + 2, text.substr(i + 2, close - i - 2), line,
                       static_cast<int>(i - lineStart) + 1});
        i = close + 1;
    }
    return out;
}

}  // namespace

bool checkTemplate(const Template& t, const Bindings& bindings, Diagnostics& diags) {
    bool ok = true;
    std::set<std::string> used;
    for (const auto& p : findPlaceholders(t.text)) {
        used.insert(p.name);
        if (!bindings.count(p.name)) {
            diags.error({t.file, p.line, p.column},
                        fmt::format("template placeholder {{{{{}}}}} has no value", p.name));
            ok = false;
        }
    }
    for (const auto& [name, b] : bindings) {
        if (!used.count(name)) {
            diags.error({t.file, 0, 0},
                        fmt::format("template does not use {{{{{}}}}}; add it to the template",
                                    name));
            ok = false;
        }
    }
    return ok;
}

void renderTemplate(const Template& t, const Bindings& bindings, std::FILE* out) {
    size_t pos = 0;
    for (const auto& p : findPlaceholders(t.text)) {
        std::fwrite(t.text.data() + pos, 1, p.begin - pos, out);
        const Binding& b = bindings.at(p.name);
        if (b.writer) b.writer(out);
        else std::fwrite(b.text.data(), 1, b.text.size(), out);
        pos = p.end;
    }
    std::fwrite(t.text.data() + pos, 1, t.text.size() - pos, out);
}

}  // namespace relief::emit
