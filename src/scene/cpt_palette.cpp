#include "scene/cpt_palette.h"

#include <cctype>
#include <charconv>
#include <cmath>

#include <fmt/format.h>

#include "core/number_format.h"
#include "core/text_escape.h"
#include "scene/color_ramp.h"

namespace relief::scene {

namespace {

struct Token {
    std::string_view text;
    int column;  // 1-based
};

std::vector<Token> tokens(std::string_view line) {
    std::vector<Token> out;
    size_t i = 0;
    while (i < line.size()) {
        while (i < line.size() && (line[i] == ' ' || line[i] == '\t' || line[i] == '\r')) ++i;
        if (i >= line.size() || line[i] == ';') break;  // the rest is a label
        const size_t start = i;
        while (i < line.size() && line[i] != ' ' && line[i] != '\t' && line[i] != '\r' && line[i] != ';') ++i;
        out.push_back({line.substr(start, i - start), static_cast<int>(start) + 1});
    }
    return out;
}

std::optional<double> number(std::string_view t) {
    double v = 0;
    const auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), v);
    if (ec != std::errc() || end != t.data() + t.size() || !std::isfinite(v)) return std::nullopt;
    return v;
}

bool component(std::string_view t, double& out) {
    const auto v = number(t);
    if (!v || *v < 0 || *v > 255) return false;
    out = *v;
    return true;
}

// A colour starting at tokens[i]: R/G/B, #rrggbb, "R G B" or a grey level.
// Advances i past it; false when there is none.
bool colour(const std::vector<Token>& tk, size_t& i, LinearRgb& out) {
    if (i >= tk.size()) return false;
    const std::string_view t = tk[i].text;
    double rgb[3] = {0, 0, 0};
    if (!t.empty() && t[0] == '#') {
        if (!parseHexColor(std::string(t), out)) return false;
        ++i;
        return true;
    }
    if (t.find('/') != std::string_view::npos) {
        const size_t a = t.find('/'), b = t.find('/', a + 1);
        if (b == std::string_view::npos || t.find('/', b + 1) != std::string_view::npos ||
            !component(t.substr(0, a), rgb[0]) || !component(t.substr(a + 1, b - a - 1), rgb[1]) ||
            !component(t.substr(b + 1), rgb[2]))
            return false;
        ++i;
    } else if (i + 2 < tk.size() && component(tk[i].text, rgb[0]) && component(tk[i + 1].text, rgb[1]) &&
               component(tk[i + 2].text, rgb[2]) &&
               (i + 3 >= tk.size() || number(tk[i + 3].text) || tk[i + 3].text == "L" || tk[i + 3].text == "U" ||
                tk[i + 3].text == "B")) {
        i += 3;  // "R G B" (then the next z, a flag, or the end)
    } else if (component(t, rgb[0])) {
        rgb[1] = rgb[2] = rgb[0];  // a grey level
        ++i;
    } else {
        return false;
    }
    out.r = srgbToLinear(rgb[0] / 255), out.g = srgbToLinear(rgb[1] / 255), out.b = srgbToLinear(rgb[2] / 255);
    return true;
}

}  // namespace

// Where a missing token would stand: one past the end of the last one.
int columnAfter(const std::vector<Token>& tk, size_t i) {
    if (i < tk.size()) return tk[i].column;
    return tk.back().column + static_cast<int>(tk.back().text.size()) + 1;
}

std::optional<std::vector<ColorStop>> parseCpt(std::string_view text, const std::string& file, Diagnostics& diags) {
    std::vector<ColorStop> stops;
    const int errorsBefore = diags.errorCount();
    int lineNo = 0;
    for (size_t start = 0; start <= text.size() && diags.errorCount() - errorsBefore < 20;) {
        const size_t end = std::min(text.find('\n', start), text.size());
        const std::string_view line = text.substr(start, end - start);
        start = end + 1;
        ++lineNo;
        if (line.find('\0') != std::string_view::npos) {
            diags.error({file, lineNo, 1}, "not a colour palette (a NUL byte): a .cpt file is text");
            return std::nullopt;
        }
        const auto tk = tokens(line);
        if (tk.empty()) continue;
        const SourceLoc at{file, lineNo, tk[0].column};
        if (tk[0].text[0] == '#') {
            const std::string upper = [&] {
                std::string u(line);
                for (char& ch : u) ch = static_cast<char>(std::toupper(static_cast<unsigned char>(ch)));
                return u;
            }();
            const size_t model = upper.find("COLOR_MODEL");
            if (model != std::string::npos && upper.find("RGB", model) == std::string::npos)
                diags.error(at, fmt::format("{}: relief reads RGB palettes only; convert it with GMT's gmt makecpt "
                                            "or give the colours as R/G/B",
                                            printableExcerpt(line)));
            continue;
        }
        if (tk[0].text == "B" || tk[0].text == "F" || tk[0].text == "N") continue;  // clamped to the ends instead
        // A slice: z_low colour z_high colour [L|U|B].
        size_t i = 0;
        ColorStop lo{}, hi{};
        const auto z0 = number(tk[i].text);
        if (!z0) {
            diags.error(at, fmt::format("\"{}\" is not a number: each line is z_low colour z_high colour "
                                        "(e.g. 0 0/97/71 500 16/122/47)",
                                        printableExcerpt(tk[i].text)));
            continue;
        }
        ++i;
        if (!colour(tk, i, lo.rgb)) {
            diags.error({file, lineNo, columnAfter(tk, i)},
                        "expected a colour (R/G/B, R G B, #rrggbb or a grey level, 0-255) after z_low; "
                        "named colours and HSV are not read");
            continue;
        }
        const auto z1 = i < tk.size() ? number(tk[i].text) : std::nullopt;
        if (!z1) {
            diags.error({file, lineNo, columnAfter(tk, i)},
                        "expected z_high after the first colour: a categorical palette (one value a line) "
                        "cannot colour elevations");
            continue;
        }
        const int z1Column = tk[i].column;
        ++i;
        if (!colour(tk, i, hi.rgb)) {
            diags.error({file, lineNo, columnAfter(tk, i)},
                        "expected a colour (R/G/B, R G B, #rrggbb or a grey level, 0-255) after z_high");
            continue;
        }
        if (i < tk.size() && !(tk[i].text == "L" || tk[i].text == "U" || tk[i].text == "B")) {
            diags.error({file, lineNo, tk[i].column}, fmt::format("unexpected \"{}\" after the slice's colours",
                                                                  printableExcerpt(tk[i].text)));
            continue;
        }
        if (!(*z1 > *z0)) {
            diags.error({file, lineNo, z1Column}, fmt::format("z_high {} must be above z_low {}",
                                                              formatShortest(*z1), formatShortest(*z0)));
            continue;
        }
        if (!stops.empty() && *z0 < stops.back().elevM) {
            diags.error(at, fmt::format("slice from {} overlaps the one before (to {}): list slices bottom to top",
                                        formatShortest(*z0), formatShortest(stops.back().elevM)));
            continue;
        }
        lo.elevM = *z0, hi.elevM = *z1;
        // Where this slice starts where the last ended, in the same colour, one stop serves.
        const bool joins = !stops.empty() && stops.back().elevM == *z0 && stops.back().rgb == lo.rgb;
        if (!joins) stops.push_back(lo);
        stops.push_back(hi);
    }
    if (diags.errorCount() > errorsBefore) return std::nullopt;
    if (stops.size() < 2) {
        diags.error({file, 0, 0}, "no colour slices: a .cpt needs lines z_low colour z_high colour");
        return std::nullopt;
    }
    return stops;
}

}  // namespace relief::scene
