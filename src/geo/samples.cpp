#include "geo/samples.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <map>
#include <optional>
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

// The errors on the data's lines: the first kMaxReportedLines reported, the others counted.
struct BadLines {
    const std::string& displayPath;
    Diagnostics& diags;
    int count = 0;
    void report(int line, int column, std::string message) {
        if (++count <= kMaxReportedLines) diags.error({displayPath, line, column}, std::move(message));
    }
};

// The file's text without a UTF-8 byte order mark; nullopt, after an error,
// when it cannot be read or is empty.
std::optional<std::string> samplesText(const std::filesystem::path& path, const std::string& displayPath,
                                       std::uintmax_t maxBytes, Diagnostics& diags) {
    std::string problem;
    auto text = readInputFile(path, maxBytes, problem);
    if (!text) {
        diags.error({displayPath, 0, 0}, "cannot read the samples file: " + problem);
        return std::nullopt;
    }
    if (text->size() >= 3 && static_cast<unsigned char>((*text)[0]) == 0xEF)  // UTF-8 BOM
        text->erase(0, 3);
    if (text->empty()) {
        diags.error({displayPath, 0, 0}, "the samples file is empty: give a CSV with the header lon,lat,elev and a "
                                         "sample a line, or a raster GDAL reads");
        return std::nullopt;
    }
    return text;
}

struct CsvColumns {
    int lon = -1, lat = -1, elev = -1;
    size_t count = 0;
};

// The header's columns; nullopt, after an error, unless they are lon, lat and elev.
std::optional<CsvColumns> headerColumns(std::string_view line, const std::vector<Field>& fields, int lineNo,
                                        const std::string& displayPath, Diagnostics& diags) {
    CsvColumns columns;
    columns.count = fields.size();
    for (size_t i = 0; i < fields.size(); ++i) {
        if (fields[i].text == "lon") columns.lon = static_cast<int>(i);
        else if (fields[i].text == "lat") columns.lat = static_cast<int>(i);
        else if (fields[i].text == "elev") columns.elev = static_cast<int>(i);
    }
    if (columns.lon >= 0 && columns.lat >= 0 && columns.elev >= 0 && columns.count == 3) return columns;
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
    return std::nullopt;
}

enum Coordinate { kLon, kLat, kElev };
constexpr const char* kCoordinateNames[] = {"lon", "lat", "elev"};

// The value of field `f` as coordinate `k` in `v`, or what is wrong with it.
std::string coordinateProblem(const Field& f, Coordinate k, bool earthElevations, double& v) {
    const char* name = kCoordinateNames[k];
    auto [ptr, ec] = std::from_chars(f.text.data(), f.text.data() + f.text.size(), v);
    if (f.text.empty()) return fmt::format("{} is missing", name);
    if (ec != std::errc() || ptr != f.text.data() + f.text.size())
        return fmt::format("{} = \"{}\" is not a number", name, f.text);
    if (!std::isfinite(v)) return fmt::format("{} = {} is not a finite number", name, f.text);
    if (k == kLon && std::fabs(v) > 180.0) return fmt::format("lon = {}° is outside [-180°, 180°]", f.text);
    if (k == kLat && std::fabs(v) > 90.0) return fmt::format("lat = {}° is outside [-90°, 90°]", f.text);
    if (k == kElev && earthElevations && (v < scene::kLowestElevationM || v > scene::kHighestElevationM))
        return fmt::format("elev = {} m is beyond the Earth's ({} to {} m): fix the value, or set "
                           "elevations = \"any\" in [samples] for data that are not terrain in "
                           "metres",
                           f.text, scene::kLowestElevationM, scene::kHighestElevationM);
    if (k == kElev && std::fabs(v) > scene::kAnyElevationLimitM)
        return fmt::format("elev = {} m is beyond the {:.0e} m any elevation may be (the surface's "
                           "vertices are single-precision): fix the value or its unit",
                           f.text, scene::kAnyElevationLimitM);
    return "";
}

// The sample on a line of data; nullopt when the line is bad (each bad field reported).
std::optional<GeoSample> sampleOnLine(const std::vector<Field>& fields, const CsvColumns& columns, int lineNo,
                                      bool earthElevations, BadLines& bad) {
    if (fields.size() != columns.count) {
        bad.report(lineNo, 1, fmt::format("expected {} fields (lon,lat,elev), found {}", columns.count,
                                          fields.size()));
        return std::nullopt;
    }
    double values[3];
    const int at[3] = {columns.lon, columns.lat, columns.elev};
    bool ok = true;
    for (const Coordinate k : {kLon, kLat, kElev}) {
        const Field& f = fields[at[k]];
        double v = 0;
        if (std::string problem = coordinateProblem(f, k, earthElevations, v); !problem.empty()) {
            bad.report(lineNo, f.column, std::move(problem));
            ok = false;
        }
        values[k] = v;
    }
    if (!ok) return std::nullopt;
    return GeoSample{values[kLon], values[kLat], values[kElev], {bad.displayPath, lineNo, 1}};
}

// Samples by their lon, lat: an exact duplicate adds nothing, another elevation is an error.
struct DistinctSamples {
    std::vector<GeoSample> samples;
    std::map<std::pair<double, double>, size_t> seen;  // (lon, lat) -> index in samples

    void add(const GeoSample& s, const std::vector<Field>& fields, const CsvColumns& columns, BadLines& bad) {
        auto [it, inserted] = seen.try_emplace({s.lonDeg, s.latDeg}, samples.size());
        if (inserted) {
            samples.push_back(s);
            return;
        }
        const GeoSample& first = samples[it->second];
        if (first.elevM != s.elevM)
            bad.report(s.loc.line, fields[columns.elev].column,
                       fmt::format("lon,lat {},{} appears twice with different elevations: {} m "
                                   "here, {} m on line {}; remove one",
                                   fields[columns.lon].text, fields[columns.lat].text, fields[columns.elev].text,
                                   first.elevM, first.loc.line));
    }
};

// Enough samples, spread in two dimensions, for a surface.
void checkSpread(const std::vector<GeoSample>& samples, const std::string& displayPath, Diagnostics& diags) {
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
}

}  // namespace

std::vector<GeoSample> readSamples(const std::filesystem::path& path, const std::string& displayPath,
                                   Diagnostics& diags, bool earthElevations, std::uintmax_t maxBytes) {
    const auto text = samplesText(path, displayPath, maxBytes, diags);
    if (!text) return {};
    std::optional<CsvColumns> columns;  // once the header is read
    DistinctSamples distinct;
    BadLines bad{displayPath, diags};
    int lineNo = 0;
    for (size_t pos = 0; pos < text->size();) {
        size_t nl = text->find('\n', pos);
        if (nl == std::string::npos) nl = text->size();
        const std::string_view line(text->data() + pos, nl - pos);
        pos = nl + 1;
        ++lineNo;
        if (trim(line).empty()) continue;
        const auto fields = splitFields(line);
        if (!columns) {
            columns = headerColumns(line, fields, lineNo, displayPath, diags);
            if (!columns) return {};
        } else if (const auto s = sampleOnLine(fields, *columns, lineNo, earthElevations, bad)) {
            distinct.add(*s, fields, *columns, bad);
        }
    }
    if (!columns) {
        diags.error({displayPath, 0, 0}, "the samples file is empty; expected a header "
                                         "lon,lat,elev and at least 4 rows");
        return {};
    }
    if (bad.count > kMaxReportedLines)
        diags.error({displayPath, 0, 0},
                    fmt::format("{} more bad lines not shown", bad.count - kMaxReportedLines));
    if (!diags.hasErrors()) checkSpread(distinct.samples, displayPath, diags);
    return std::move(distinct.samples);
}

}  // namespace relief::geo
