#include "regress/geometry_check.h"

#include <charconv>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <stdexcept>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "core/atomic_file.h"
#include "core/input_file.h"
#include "core/number_format.h"
#include "core/text_escape.h"
#include "curves/curve_file.h"
#include "measure/surface_curves.h"
#include "pipeline/surface.h"
#include "plot/svg.h"

namespace relief::regress {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

constexpr int kProfileSamples = 200;
constexpr int kGeometryFormat = 1;

// "LON,LAT:LON,LAT": a geodesic's two ends.
std::optional<measure::ProfileLine> profileOf(const std::string& text) {
    double v[4];
    const char* p = text.data();
    const char* const end = text.data() + text.size();
    for (int i = 0; i < 4; ++i) {  // from_chars: the C locale's digits, and no "nan" or "inf"
        while (p != end && *p == ' ') ++p;
        const auto [next, ec] = std::from_chars(p, end, v[i]);
        if (ec != std::errc() || !std::isfinite(v[i])) return std::nullopt;
        p = next;
        if (i == 3) break;
        if (p == end || *p != (i == 1 ? ':' : ',')) return std::nullopt;
        ++p;
    }
    if (p != end || std::fabs(v[0]) > 180 || std::fabs(v[2]) > 180 || std::fabs(v[1]) > 90 || std::fabs(v[3]) > 90)
        return std::nullopt;
    return measure::ProfileLine{text, {v[0], v[1], 0}, {v[2], v[3], 0}};
}

json pointsJson(const std::vector<curves::Point2>& points) {
    json a = json::array();
    for (const auto& p : points) a.push_back({p.x, p.y});
    return a;
}

json curvesJson(const measure::SurfaceCurves& c, double peakLossM) {
    json profiles = json::array(), levels = json::array();
    for (const auto& p : c.profiles) profiles.push_back({{"name", p.name}, {"points", pointsJson(p.points)}});
    for (const auto& l : c.levels) {
        json lines = json::array();
        for (const auto& line : l.lines) lines.push_back(pointsJson(line));
        levels.push_back({{"level", l.level}, {"lines", lines}});
    }
    return {{"relief_geometry", kGeometryFormat}, {"frame", c.frame}, {"peak_loss_m", peakLossM},
            {"profiles", profiles}, {"levels", levels}};
}

struct KeptCurves {
    measure::SurfaceCurves curves;
    double peakLossM = 0;
};

// A kept line, read as a curve file's points are (curves/curve_file.h): at
// least one, finite, within kMaxCoordinate. Nullopt with `problem` set.
std::optional<std::vector<curves::Point2>> keptLine(const json& points, const std::string& name,
                                                    std::string& problem) {
    std::vector<curves::Point2> line;
    if (curves::readPoints(points, name, line, problem) != curves::PointsFault::None) return std::nullopt;
    if (line.empty()) {
        problem = name + " holds no point";
        return std::nullopt;
    }
    return line;
}

const json& arrayAt(const json& j, const char* key) {
    const json& a = j.at(key);
    if (!a.is_array()) throw std::invalid_argument(key);
    return a;
}

// The curves of a geometry file's JSON; nullopt with `problem` set for a
// point that is not one, and json::exception for any other shape.
std::optional<KeptCurves> keptCurvesOf(const json& j, std::string& problem) {
    if (j.at("relief_geometry").get<int>() != kGeometryFormat) throw std::invalid_argument("format");
    KeptCurves k;
    k.curves.frame = j.at("frame").get<std::string>();
    const json& profiles = arrayAt(j, "profiles");
    for (size_t i = 0; i < profiles.size(); ++i) {
        auto line = keptLine(profiles.at(i).at("points"), fmt::format("profiles[{}].points", i), problem);
        if (!line) return std::nullopt;
        k.curves.profiles.push_back({profiles.at(i).at("name").get<std::string>(), std::move(*line)});
    }
    const json& levels = arrayAt(j, "levels");
    for (size_t i = 0; i < levels.size(); ++i) {
        measure::SurfaceCurves::Level level{levels.at(i).at("level").get<double>(), {}};
        const json& lines = arrayAt(levels[i], "lines");
        for (size_t n = 0; n < lines.size(); ++n) {
            auto line = keptLine(lines.at(n), fmt::format("levels[{}].lines[{}]", i, n), problem);
            if (!line) return std::nullopt;
            level.lines.push_back(std::move(*line));
        }
        k.curves.levels.push_back(std::move(level));
    }
    k.peakLossM = j.at("peak_loss_m").get<double>();
    return k;
}

// The kept curves, read as curve files are (the size cap, coordinates within
// kMaxCoordinate). Nullopt with `problem` "no such file" when none are kept;
// with another problem when the file is not a geometry file relief reads (a
// FIFO, too big, not JSON, another shape, a point beyond the limits).
std::optional<KeptCurves> keptCurves(const fs::path& file, std::string& problem) {
    const auto text = readInputFile(file, kMaxCurveBytes, problem);
    if (!text) return std::nullopt;
    const json j = json::parse(*text, nullptr, false);  // no exceptions: a number past 1e308 is discarded too
    if (j.is_discarded()) {
        problem = "it is not JSON";
        return std::nullopt;
    }
    try {
        return keptCurvesOf(j, problem);
    } catch (const std::exception&) {
        problem = "it is not the geometry file relief test writes";
        return std::nullopt;
    }
}

// Both curves and where they are furthest apart, as an SVG beside the report's images.
void plotMove(const fs::path& svg, const std::string& title, const std::vector<std::vector<curves::Point2>>& now,
              const std::vector<std::vector<curves::Point2>>& kept, const measure::CurveMove& move, bool profile) {
    std::vector<plot::SvgCurve> a, b;
    for (const auto& l : kept) a.push_back({"", l, false});
    for (const auto& l : now) b.push_back({"", l, false});
    const std::vector<plot::SvgLayer> layers{{"kept", a, "#888888", true}, {"new", b, "#1f77b4", false}};
    const std::vector<plot::SvgMarker> markers{{move.witness, move.foot, "H = " + measure::formatDistance(move.distanceM)}};
    const plot::SvgAxes axes{true, 1, profile ? "distance along the geodesic (m)" : "x (m)",
                             profile ? "elevation (m)" : "y (m)"};
    writeFileAtomically(svg, plot::plotSvg(title, layers, markers, axes));
}

std::string whereText(const measure::CurveMove& m, bool profile) {
    return profile ? fmt::format("{:.1f} m along the profile, at {:.2f} m", m.witness.x, m.witness.y)
                   : fmt::format("at x {:.1f}, y {:.1f}", m.witness.x, m.witness.y);
}

void checkCurves(const measure::SurfaceCurves& now, const measure::SurfaceCurves* kept, const GeometryChecks& checks,
                 const fs::path& plotDir, const std::string& caseName, std::vector<GeometryResult>& results) {
    auto result = [&](const std::string& name, const std::vector<std::vector<curves::Point2>>& a,
                      const std::vector<std::vector<curves::Point2>>* b, bool profile) {
        GeometryResult r{name, b != nullptr, 0, checks.toleranceM, false, "", {}};
        if (b && kept && kept->frame != now.frame && !profile) {
            r.where = fmt::format("the kept lines are in {}, the surface in {}: bless again", kept->frame, now.frame);
        } else if (b && !profile && (a.empty() || b->empty())) {
            // A level's lines appeared or vanished: no distance to measure, nothing to plot.
            r.pass = a.empty() && b->empty();
            r.distanceM = r.pass ? 0 : std::numeric_limits<double>::infinity();
            r.where = r.pass ? "no lines at this level, now or kept"
                             : fmt::format("{} lines now, {} kept", a.size(), b->size());
        } else if (b) {
            const measure::CurveMove m = profile ? measure::profileMove(a.front(), b->front()) : measure::levelMove(a, *b);
            r.distanceM = m.distanceM;
            r.pass = m.distanceM <= checks.toleranceM;
            r.where = whereText(m, profile);
            r.plot = plotDir / fmt::format("{}.geometry-{}.svg", caseName, results.size() + 1);
            plotMove(r.plot, name, a, *b, m, profile);
        }
        results.push_back(r);
    };
    for (const auto& p : now.profiles) {
        const measure::SurfaceCurves::Profile* k = nullptr;
        if (kept)
            for (const auto& q : kept->profiles)
                if (q.name == p.name) k = &q;
        std::vector<std::vector<curves::Point2>> keptLine;
        if (k) keptLine.push_back(k->points);
        result("profile " + p.name, {p.points}, k ? &keptLine : nullptr, true);
    }
    for (const auto& l : now.levels) {
        const measure::SurfaceCurves::Level* k = nullptr;
        if (kept)
            for (const auto& q : kept->levels)
                if (q.level == l.level) k = &q;
        result(fmt::format("contours at {} m", formatShortest(l.level)), l.lines, k ? &k->lines : nullptr, false);
    }
}

}  // namespace

GeometryChecks readGeometryChecks(const toml::table& t, const std::string& file, Diagnostics& diags) {
    GeometryChecks g;
    const auto at = [&](const char* key) { return locOf(file, t.get(key)->source()); };
    if (const toml::node* p = t.get("profile")) {
        std::vector<std::string> texts;
        if (auto s = p->value_exact<std::string>()) texts.push_back(*s);
        else if (const toml::array* a = p->as_array())
            for (const auto& e : *a)
                if (auto s = e.value_exact<std::string>()) texts.push_back(*s);
        if (texts.empty()) diags.error(at("profile"), "profile must be \"LON,LAT:LON,LAT\" or a list of them");
        for (const auto& text : texts) {
            if (auto line = profileOf(text)) g.profiles.push_back(*line);
            else
                diags.error(at("profile"), fmt::format("profile \"{}\" is not \"LON,LAT:LON,LAT\" (degrees)",
                                                       printableExcerpt(text, 100)));
        }
    }
    if (const toml::node* l = t.get("levels")) {
        const toml::array* a = l->as_array();
        for (size_t i = 0; a && i < a->size(); ++i)
            if (auto v = (*a)[i].value<double>(); v && std::isfinite(*v)) g.levels.push_back(*v);
        if (!a || g.levels.size() != a->size() || g.levels.empty())
            diags.error(at("levels"), "levels must be a list of elevations in metres, e.g. [100, 150]");
    }
    for (const auto& [key, out] : {std::pair{"tolerance_m", &g.toleranceM}}) {
        if (const toml::node* n = t.get(key)) {
            const auto v = n->value<double>();
            if (v && *v >= 0 && std::isfinite(*v)) *out = *v;
            else diags.error(at(key), fmt::format("{} must be a distance in metres, 0 or more", key));
        }
    }
    if (const toml::node* n = t.get("peak_loss_tolerance_m")) {
        const auto v = n->value<double>();
        if (v && *v >= 0 && std::isfinite(*v)) g.peakLossToleranceM = *v;
        else diags.error(at("peak_loss_tolerance_m"), "peak_loss_tolerance_m must be a distance in metres, 0 or more");
    }
    if ((t.get("tolerance_m")) && g.profiles.empty() && g.levels.empty())
        diags.error(at("tolerance_m"), "tolerance_m is for geometry checks: give profile or levels");
    return g;
}

std::string checkGeometry(const fs::path& scenePath, const std::vector<std::pair<std::string, std::string>>& overrides,
                          const GeometryChecks& checks, const fs::path& referenceDir, const fs::path& newCurves,
                          const fs::path& plotDir, const std::string& caseName, std::vector<GeometryResult>& results) {
    // No kept curves: the case is new, and --update keeps the new ones. Kept
    // curves that cannot be read are an error, never taken for none: --update
    // would replace them unseen.
    std::string problem;
    const fs::path keptFile = referenceDir / kGeometryFile;
    const auto kept = keptCurves(keptFile, problem);
    if (!kept && problem != "no such file")
        return fmt::format("{}: {}; remove it, and relief test --update keeps the new curves there", keptFile.string(),
                           problem);
    Diagnostics diags;
    const auto loaded = loadScene(scenePath, diags, overrides);
    auto surface = loaded ? buildSurface(*loaded, diags, 1) : std::nullopt;
    const auto now = surface ? measure::surfaceCurves(surface->refined, checks.profiles, checks.levels, kProfileSamples,
                                                      {scenePath.string(), 0, 0}, diags)
                             : std::nullopt;
    if (!now) {
        for (const auto& d : diags.all())
            if (d.severity == Severity::Error) return formatDiagnostic(d);
        return "the surface cannot be measured";
    }
    writeFileAtomically(newCurves, curvesJson(*now, surface->peakLoss.lossM).dump(1) + "\n");
    checkCurves(*now, kept ? &kept->curves : nullptr, checks, plotDir, caseName, results);
    if (checks.peakLossToleranceM) {
        GeometryResult r{"peak loss", kept.has_value(), 0, *checks.peakLossToleranceM, false, "", {}};
        if (kept) {
            r.distanceM = std::abs(surface->peakLoss.lossM - kept->peakLossM);
            r.pass = r.distanceM <= r.toleranceM;
            r.where = fmt::format("now {:.3f} m, kept {:.3f} m", surface->peakLoss.lossM, kept->peakLossM);
        }
        results.push_back(r);
    }
    return "";
}

}  // namespace relief::regress
