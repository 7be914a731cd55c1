#include "curves/curve_file.h"

#include <cmath>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "core/input_file.h"
#include "core/number_format.h"

namespace relief::curves {

PointsFault readPoints(const nlohmann::json& points, const std::string& name, std::vector<Point2>& out,
                       std::string& problem) {
    out.clear();
    if (!points.is_array()) {
        problem = fmt::format("{} must be a list of points [[x, y], ...]", name);
        return PointsFault::NotPoints;
    }
    for (size_t i = 0; i < points.size(); ++i) {
        const nlohmann::json& p = points[i];
        if (!p.is_array() || p.size() != 2 || !p[0].is_number() || !p[1].is_number()) {
            problem = fmt::format("{}[{}] must be [x, y] with two numbers", name, i);
            return PointsFault::NotPoints;
        }
        const Point2 q{p[0].get<double>(), p[1].get<double>()};
        if (!std::isfinite(q.x) || !std::isfinite(q.y)) {
            problem = fmt::format("{}[{}] is not finite", name, i);
            return PointsFault::NotPoints;
        }
        // Distances square the coordinates and the exact Hausdorff distance
        // solves polynomials in them: far below 1e308, whatever the input.
        if (std::fabs(q.x) > kMaxCoordinate || std::fabs(q.y) > kMaxCoordinate) {
            problem = fmt::format("{}[{}] = [{}, {}] is beyond the {:.0e} a coordinate may be (in metres, 1e15 is a "
                                  "thousand times the distance to the Sun)",
                                  name, i, formatShortest(q.x), formatShortest(q.y), kMaxCoordinate);
            return PointsFault::BeyondRange;
        }
        out.push_back(q);
    }
    return PointsFault::None;
}

std::optional<CurveFile> readCurveFile(const std::filesystem::path& path, Diagnostics& diags) {
    const std::string file = path.string();
    std::string problem;
    const auto read = readInputFile(path, kMaxCurveBytes, problem);
    if (!read) {
        diags.error({file, 0, 0}, "cannot read the curve file: " + problem);
        return std::nullopt;
    }
    const std::string& text = *read;
    nlohmann::json j;
    try {
        j = nlohmann::json::parse(text);
    } catch (const nlohmann::json::parse_error& e) {
        // nlohmann reports a byte offset: turn it into line and column.
        int line = 1, col = 1;
        for (size_t i = 0; i + 1 < e.byte && i < text.size(); ++i) {
            if (text[i] == '\n') ++line, col = 1;
            else ++col;
        }
        diags.error({file, line, col}, "invalid JSON; expected {\"type\": \"polyline\", "
                                       "\"closed\": false, \"points\": [[x, y], ...]}");
        return std::nullopt;
    } catch (const nlohmann::json::out_of_range&) {
        // A number too large for a double (found by fuzzing: 1e1114846).
        diags.error({file, 0, 0}, "a number in the curve file is out of range (beyond about 1e308)");
        return std::nullopt;
    }
    CurveFile c;
    if (!j.is_object()) {
        diags.error({file, 1, 1}, "a curve file is a JSON object with \"points\"");
        return std::nullopt;
    }
    if (j.contains("type")) {
        if (!j["type"].is_string()) {
            diags.error({file, 0, 0}, "\"type\" must be \"polyline\", \"bezier\" or \"bspline3\"");
            return std::nullopt;
        }
        c.type = j["type"].get<std::string>();
        if (c.type != "polyline" && c.type != "bezier" && c.type != "bspline3") {
            diags.error({file, 0, 0}, fmt::format("unknown curve type \"{}\"; use \"polyline\", "
                                                  "\"bezier\" or \"bspline3\"",
                                                  c.type));
            return std::nullopt;
        }
    }
    if (j.contains("closed")) {
        if (!j["closed"].is_boolean()) {
            diags.error({file, 0, 0}, "\"closed\" must be true or false");
            return std::nullopt;
        }
        c.closed = j["closed"].get<bool>();
    }
    if (!j.contains("points") || !j["points"].is_array()) {
        diags.error({file, 0, 0}, "missing \"points\": [[x, y], ...]");
        return std::nullopt;
    }
    if (const PointsFault fault = readPoints(j["points"], "points", c.points, problem); fault != PointsFault::None) {
        diags.error({file, 0, 0}, fault == PointsFault::BeyondRange ? problem + ": give the curve in smaller units"
                                                                     : problem);
        return std::nullopt;
    }
    if (c.type == "bezier" && c.points.size() > kMaxBezierDegree + 1) {
        diags.error({file, 0, 0}, fmt::format("a bezier curve of {} points is of degree {}, more than the {} relief "
                                              "reads: give it as a polyline or a bspline3 of pieces",
                                              c.points.size(), c.points.size() - 1, kMaxBezierDegree));
        return std::nullopt;
    }
    const size_t need = c.type == "bspline3" ? (c.closed ? 3 : 4) : c.type == "bezier" ? 1 : 1;
    if (c.points.size() < need) {
        diags.error({file, 0, 0}, fmt::format("a {}{} curve needs at least {} points, found {}",
                                              c.closed ? "closed " : "", c.type, need,
                                              c.points.size()));
        return std::nullopt;
    }
    return c;
}

std::string curveFileJson(const CurveFile& c) {
    std::string out = fmt::format("{{\"type\": \"{}\", \"closed\": {}, \"points\": [", c.type,
                                  c.closed ? "true" : "false");
    for (size_t i = 0; i < c.points.size(); ++i)
        out += fmt::format("{}\n  [{}, {}]", i ? "," : "", formatShortest(c.points[i].x),
                           formatShortest(c.points[i].y));
    out += "\n]}\n";
    return out;
}

}  // namespace relief::curves
