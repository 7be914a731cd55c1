#include "geo/samples.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <map>
#include <string_view>

#include <fmt/format.h>

#include "core/input_file.h"
#include "core/text_escape.h"

namespace relief::geo {

namespace {

constexpr int kMaxReportedLines = 20;

std::string_view trim(std::string_view s) {
    while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
    while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r'))
        s.remove_suffix(1);
    return s;
}

struct Field {
    std::string_view text;
    int column;  // 1-based
};

std::vector<Field> splitFields(std::string_view line) {
    std::vector<Field> out;
    size_t start = 0;
    while (true) {
        const size_t comma = line.find(',', start);
        const size_t end = comma == std::string_view::npos ? line.size() : comma;
        out.push_back({trim(line.substr(start, end - start)), static_cast<int>(start) + 1});
        if (comma == std::string_view::npos) break;
        start = comma + 1;
    }
    return out;
}

// A CSV's header: two to eight column names, each a short word (letters,
// digits, _ ( ) -, a space): what a table of samples would begin with, and
// not a line of someone's data (a key, a password hash) that no message should quote.
bool looksLikeAHeader(const std::vector<Field>& fields) {
    if (fields.size() < 2 || fields.size() > 8) return false;
    return std::all_of(fields.begin(), fields.end(), [](const Field& f) {
        return !f.text.empty() && f.text.size() <= 32 && std::isalpha(static_cast<unsigned char>(f.text[0])) &&
               std::all_of(f.text.begin(), f.text.end(), [](char ch) {
                   const auto c = static_cast<unsigned char>(ch);
                   return std::isalnum(c) || c == '_' || c == '(' || c == ')' || c == '-' || c == ' ';
               });
    });
}

// Printable text: UTF-8 without control characters (tabs and a CR at the end aside).
bool isText(std::string_view line) {
    for (const char ch : trim(line)) {
        const auto c = static_cast<unsigned char>(ch);
        if ((c < 0x20 && c != '\t') || c == 0x7f) return false;
    }
    return isUtf8(line);
}

// True when every sample lies within a relative 1e-9 of the line through the
// first sample and the one farthest from it, in lon/lat scaled to equal
// ground distances (the space the user wrote them in).
bool allCollinear(const std::vector<GeoSample>& s, size_t& farIndex) {
    const double k = std::cos(s.front().latDeg * 3.14159265358979323846 / 180.0);
    auto x = [&](const GeoSample& g) { return std::remainder(g.lonDeg - s.front().lonDeg, 360.0) * k; };
    auto y = [&](const GeoSample& g) { return g.latDeg - s.front().latDeg; };
    double farD = -1;
    for (size_t i = 0; i < s.size(); ++i) {
        const double d = std::hypot(x(s[i]), y(s[i]));
        if (d > farD) farD = d, farIndex = i;
    }
    if (farD == 0) return true;
    const double ux = x(s[farIndex]) / farD, uy = y(s[farIndex]) / farD;
    for (const auto& g : s)
        if (std::fabs(x(g) * uy - y(g) * ux) > 1e-9 * farD) return false;
    return true;
}

}  // namespace

std::vector<GeoSample> readSamples(const std::filesystem::path& path, const std::string& displayPath,
                                   Diagnostics& diags, bool earthElevations, std::uintmax_t maxBytes) {
    std::string problem;
    auto read = readInputFile(path, maxBytes, problem);
    if (!read) {
        diags.error({displayPath, 0, 0}, "cannot read the samples file: " + problem);
        return {};
    }
    std::string& text = *read;
    if (text.size() >= 3 && static_cast<unsigned char>(text[0]) == 0xEF)  // UTF-8 BOM
        text.erase(0, 3);

    if (text.empty()) {
        diags.error({displayPath, 0, 0}, "the samples file is empty: give a CSV with the header lon,lat,elev and a "
                                         "sample a line, or a raster GDAL reads");
        return {};
    }
    std::vector<GeoSample> samples;
    int lineNo = 0;
    int badLines = 0;
    int colLon = -1, colLat = -1, colElev = -1;
    size_t nColumns = 0;
    std::map<std::pair<double, double>, size_t> seen;  // (lon, lat) -> index in samples

    size_t pos = 0;
    while (pos < text.size()) {
        size_t nl = text.find('\n', pos);
        if (nl == std::string::npos) nl = text.size();
        std::string_view line(text.data() + pos, nl - pos);
        pos = nl + 1;
        ++lineNo;
        if (trim(line).empty()) continue;
        auto fields = splitFields(line);

        if (nColumns == 0) {  // header
            nColumns = fields.size();
            for (size_t i = 0; i < fields.size(); ++i) {
                if (fields[i].text == "lon") colLon = static_cast<int>(i);
                else if (fields[i].text == "lat") colLat = static_cast<int>(i);
                else if (fields[i].text == "elev") colElev = static_cast<int>(i);
            }
            if (colLon < 0 || colLat < 0 || colElev < 0 || nColumns != 3) {
                // Quoted only when it is a CSV's header: any other file's first
                // line (a key file, /etc/shadow) is nobody's business in a message.
                if (looksLikeAHeader(fields) && isText(line))
                    diags.error({displayPath, lineNo, 1},
                                fmt::format("header must name the columns lon,lat,elev (WGS84 "
                                            "degrees, metres); found \"{}\"",
                                            printableExcerpt(trim(line))));
                else
                    diags.error({displayPath, 0, 0},
                                "neither a raster GDAL reads nor a CSV of samples (a header naming the columns "
                                "lon,lat,elev, then a sample a line)");
                return {};
            }
            continue;
        }

        auto bad = [&](int column, std::string message) {
            if (++badLines <= kMaxReportedLines)
                diags.error({displayPath, lineNo, column}, std::move(message));
        };
        if (fields.size() != nColumns) {
            bad(1, fmt::format("expected {} fields (lon,lat,elev), found {}", nColumns,
                               fields.size()));
            continue;
        }
        double values[3];
        const int cols[3] = {colLon, colLat, colElev};
        const char* names[3] = {"lon", "lat", "elev"};
        bool ok = true;
        for (int k = 0; k < 3; ++k) {
            const Field& f = fields[cols[k]];
            double v = 0;
            auto [ptr, ec] = std::from_chars(f.text.data(), f.text.data() + f.text.size(), v);
            if (f.text.empty()) {
                bad(f.column, fmt::format("{} is missing", names[k]));
                ok = false;
            } else if (ec != std::errc() || ptr != f.text.data() + f.text.size()) {
                bad(f.column, fmt::format("{} = \"{}\" is not a number", names[k], f.text));
                ok = false;
            } else if (!std::isfinite(v)) {
                bad(f.column, fmt::format("{} = {} is not a finite number", names[k], f.text));
                ok = false;
            } else if (k == 0 && std::fabs(v) > 180.0) {
                bad(f.column, fmt::format("lon = {}° is outside [-180°, 180°]", f.text));
                ok = false;
            } else if (k == 1 && std::fabs(v) > 90.0) {
                bad(f.column, fmt::format("lat = {}° is outside [-90°, 90°]", f.text));
                ok = false;
            } else if (k == 2 && earthElevations &&
                       (v < scene::kLowestElevationM || v > scene::kHighestElevationM)) {
                bad(f.column, fmt::format("elev = {} m is beyond the Earth's ({} to {} m): fix the value, or set "
                                          "elevations = \"any\" in [samples] for data that are not terrain in "
                                          "metres",
                                          f.text, scene::kLowestElevationM, scene::kHighestElevationM));
                ok = false;
            } else if (k == 2 && std::fabs(v) > scene::kAnyElevationLimitM) {
                bad(f.column, fmt::format("elev = {} m is beyond the {:.0e} m any elevation may be (the surface's "
                                          "vertices are single-precision): fix the value or its unit",
                                          f.text, scene::kAnyElevationLimitM));
                ok = false;
            }
            values[k] = v;
        }
        if (!ok) continue;
        GeoSample s{values[0], values[1], values[2], {displayPath, lineNo, 1}};
        auto [it, inserted] = seen.try_emplace({s.lonDeg, s.latDeg}, samples.size());
        if (!inserted) {
            const GeoSample& first = samples[it->second];
            if (first.elevM != s.elevM)
                bad(fields[colElev].column,
                    fmt::format("lon,lat {},{} appears twice with different elevations: {} m "
                                "here, {} m on line {}; remove one",
                                fields[colLon].text, fields[colLat].text, fields[colElev].text,
                                first.elevM, first.loc.line));
            continue;  // an exact duplicate adds nothing
        }
        samples.push_back(s);
    }
    if (nColumns == 0) {
        diags.error({displayPath, 0, 0}, "the samples file is empty; expected a header "
                                         "lon,lat,elev and at least 4 rows");
        return {};
    }
    if (badLines > kMaxReportedLines)
        diags.error({displayPath, 0, 0},
                    fmt::format("{} more bad lines not shown", badLines - kMaxReportedLines));
    if (diags.hasErrors()) return samples;
    size_t farIndex = 0;
    if (samples.size() < 4)
        diags.error({displayPath, 0, 0},
                    fmt::format("only {} distinct sample point(s); at least 4 are needed to "
                                "build a surface",
                                samples.size()));
    else if (allCollinear(samples, farIndex))
        diags.error({displayPath, 0, 0},
                    fmt::format("all {} samples lie on one line (from line {} to line {}); a "
                                "surface needs samples spread in 2-D",
                                samples.size(), samples.front().loc.line,
                                samples[farIndex].loc.line));
    return samples;
}

}  // namespace relief::geo
