#include "cli/cli_common.h"

// relief hausdorff, relief profile, relief compare-geometry: curves and distances in metres.
#include <cmath>
#include <iostream>
#include <memory>

#include <fmt/format.h>

#include "core/text_escape.h"
#include <nlohmann/json.hpp>

#include "core/atomic_file.h"
#include "curves/curve_file.h"
#include "curves/hausdorff.h"
#include "plot/svg.h"
#include "core/number_format.h"
#include "measure/compare_geometry.h"
#include "measure/profile.h"
#include "pipeline/surface.h"

namespace relief::cli {

namespace {

struct HausdorffOptions {
    std::string a, b;
    bool json = false;
};

// `relief hausdorff`: exact h(A, B), h(B, A) and H with witnesses.
int runHausdorff(const HausdorffOptions& o) {
    relief::Diagnostics diags;
    auto fa = relief::curves::readCurveFile(o.a, diags);
    auto fb = relief::curves::readCurveFile(o.b, diags);
    if (!fa || !fb) {
        printDiagnostics(diags, false);
        return code(Exit::BadInput);
    }
    const auto A = relief::curves::toBezier(*fa), B = relief::curves::toBezier(*fb);
    const auto r = relief::curves::hausdorff(A, B);
    auto side = [](const relief::curves::OneSided& s) {
        nlohmann::ordered_json j{{"value", s.value},
                                 {"case", relief::curves::caseName(s.kind)},
                                 {"point", {s.a.x, s.a.y}},
                                 {"param", s.paramA},
                                 {"foot", {s.foot.point.x, s.foot.point.y}},
                                 {"foot_param", s.foot.param}};
        if (s.kind == relief::curves::WitnessCase::OneToTwo)
            j["second_foot"] = {{"point", {s.secondFoot.point.x, s.secondFoot.point.y}},
                                {"param", s.secondFoot.param}};
        return j;
    };
    if (o.json) {
        nlohmann::ordered_json j;
        j["h_ab"] = r.ab.value;
        j["h_ba"] = r.ba.value;
        j["H"] = r.H;
        j["witness_ab"] = side(r.ab);
        j["witness_ba"] = side(r.ba);
        std::cout << j.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) << '\n';
        return code(Exit::Ok);
    }
    auto print = [](const char* name, const relief::curves::OneSided& s, const char* from, const char* to) {
        std::cout << fmt::format("{} = {:.12g}  ({})\n", name, s.value, relief::curves::caseName(s.kind));
        std::cout << fmt::format("    on {}: ({:.12g}, {:.12g}) at parameter {:.12g}\n", from, s.a.x, s.a.y, s.paramA);
        std::cout << fmt::format("    on {}: ({:.12g}, {:.12g}) at parameter {:.12g}\n", to, s.foot.point.x,
                                 s.foot.point.y, s.foot.param);
        if (s.kind == relief::curves::WitnessCase::OneToTwo)
            std::cout << fmt::format("    and    ({:.12g}, {:.12g}) at parameter {:.12g}\n",
                                     s.secondFoot.point.x, s.secondFoot.point.y, s.secondFoot.param);
    };
    print("h(A, B)", r.ab, "A", "B");
    print("h(B, A)", r.ba, "B", "A");
    std::cout << fmt::format("H = {:.12g}\n", r.H);
    return code(Exit::Ok);
}

struct ProfileOptions {
    CommonOptions common;
    std::string from, to;
    int samples = 1001;
    double exaggeration = 0;  ///< plot only; 0 = choose
};


// `relief profile`: the refined and the control-net surface cut along a geodesic.
int runProfile(const ProfileOptions& o) {
    const auto from = parseLonLat(o.from), to = parseLonLat(o.to);
    if (!from || !to) {
        std::cerr << "relief: error: --from and --to take LON,LAT in WGS84 degrees (e.g. "
                     "174.7640,-36.8770), |lat| <= 90, |lon| <= 180\n";
        return code(Exit::BadInput);
    }
    relief::Diagnostics diags;
    relief::scene::SceneOverrides overrides;
    if (!parseOverrides(o.common.sets, overrides)) return code(Exit::BadInput);
    auto loaded = relief::loadScene(o.common.scene, diags, overrides);
    auto surface = loaded ? relief::buildSurface(*loaded, diags) : std::nullopt;
    if (!surface) {
        printDiagnostics(diags, false);
        return code(Exit::BadInput);
    }
    const auto profile = relief::measure::cutProfile(surface->net, surface->refined, *from, *to, o.samples, {}, diags);
    if (!profile) {
        printDiagnostics(diags, false);
        return code(Exit::BadInput);
    }
    const std::string stem = fs::path(o.common.scene).stem().string();
    const fs::path svg = o.common.output.empty() ? fs::path("out") / (stem + "-profile.svg") : fs::path(o.common.output);
    fs::path curveRefined = svg, curveNet = svg;
    curveRefined.replace_extension(".json");
    curveNet.replace_filename(svg.stem().string() + "-net.json");
    createParentFolder(svg);
    double exaggeration = 0;
    const std::string refinedLabel =
        fmt::format("refined: {} depth {} ({})", loaded->resolved.family, surface->depth,
                    relief::subdiv::certifiedClass(loaded->resolved.report));
    relief::writeFileAtomically(svg, relief::measure::profileSvg(*profile,
                                                                 fs::path(o.common.scene).filename().string(),
                                                                 refinedLabel, o.exaggeration, exaggeration));
    relief::writeFileAtomically(curveRefined, relief::curves::curveFileJson(profile->refined));
    relief::writeFileAtomically(curveNet, relief::curves::curveFileJson(profile->control));
    std::cerr << fmt::format("wrote {}, {} (refined) and {} (control net): {} points over {:.1f} m, "
                             "elevation {:.1f}..{:.1f} m\n",
                             svg.string(), curveRefined.string(), curveNet.string(), profile->line.size(),
                             profile->lengthM, profile->zMinM, profile->zMaxM);
    return code(Exit::Ok);
}


struct CompareGeometryOptions {
    std::string a, b;
    std::vector<std::string> setA, setB;
    std::vector<std::string> profiles;  ///< "LON,LAT:LON,LAT"
    std::string levels;                 ///< "100,200,..."
    int samples = 1001;
    int threads = 0;
    bool json = false;
    std::string map;  ///< SVG of both surfaces' contour lines and where each H is reached
};

nlohmann::ordered_json whereJson(const relief::measure::Where& w, const char* pointKeys) {
    nlohmann::ordered_json j{{"on", w.onA ? "a" : "b"}, {"lat", w.latDeg}, {"lon", w.lonDeg}};
    j[pointKeys] = {w.point.x, w.point.y};
    j["nearest_on_other"] = {w.foot.x, w.foot.y};
    return j;
}


// --profile's "LON,LAT:LON,LAT" lines; nullopt after saying which one is not.
std::optional<std::vector<relief::measure::ProfileLine>> parseProfileLines(const std::vector<std::string>& texts) {
    std::vector<relief::measure::ProfileLine> lines;
    for (const auto& text : texts) {
        const auto ends = split(text, ':');
        const auto from = ends.size() == 2 ? parseLonLat(ends[0]) : std::nullopt;
        const auto to = ends.size() == 2 ? parseLonLat(ends[1]) : std::nullopt;
        if (!from || !to) {
            std::cerr << "relief: error: --profile " << relief::terminalText(text, 200)
                      << ": write LON,LAT:LON,LAT in WGS84 degrees, e.g. 174.76,-36.88:174.77,-36.87\n";
            return std::nullopt;
        }
        lines.push_back({text, *from, *to});
    }
    return lines;
}

// --levels' "100,200,..." (none when empty); nullopt after saying it is not a list of elevations.
std::optional<std::vector<double>> parseLevels(const std::string& text) {
    std::vector<double> levels;
    if (text.empty()) return levels;
    for (const auto& v : split(text, ',')) {
        char* end = nullptr;
        const double z = std::strtod(v.c_str(), &end);
        if (end == v.c_str() || *end || !std::isfinite(z)) {
            std::cerr << "relief: error: --levels " << relief::terminalText(text, 200) << ": write elevations in metres, "
                      << "e.g. --levels 100,200,300\n";
            return std::nullopt;
        }
        levels.push_back(z);
    }
    return levels;
}

// What compare-geometry compared: both scenes, as loaded and refined, and the distances.
struct ComparedScenes {
    const relief::LoadedScene &loadedA, &loadedB;
    const relief::Surface &surfaceA, &surfaceB;
    const relief::measure::FramedSurface &a, &b;
    const relief::measure::GeometryComparison& result;
    double worstProfile = 0, worstContour = 0;
};

std::string describeSurface(const relief::LoadedScene& l, const relief::Surface& s) {
    return fmt::format("{}, depth {}, {}", l.resolved.family, s.depth, relief::subdiv::certifiedClass(l.resolved.report));
}

nlohmann::ordered_json comparisonJson(const CompareGeometryOptions& o, const ComparedScenes& c) {
    nlohmann::ordered_json j;
    j["a"] = {{"scene", o.a}, {"surface", describeSurface(c.loadedA, c.surfaceA)}, {"frame", c.a.frame().describe()}};
    j["b"] = {{"scene", o.b}, {"surface", describeSurface(c.loadedB, c.surfaceB)}, {"frame", c.b.frame().describe()}};
    auto profiles = nlohmann::ordered_json::array();
    for (const auto& p : c.result.profiles)
        profiles.push_back({{"name", p.line.name},
                            {"from", {p.line.from.lonDeg, p.line.from.latDeg}},
                            {"to", {p.line.to.lonDeg, p.line.to.latDeg}},
                            {"length_m", p.lengthM},
                            {"H", p.h.H},
                            {"h_ab", p.h.ab.value},
                            {"h_ba", p.h.ba.value},
                            {"where", whereJson(p.where, "distance_elevation_m")}});
    j["profiles"] = profiles;
    auto contours = nlohmann::ordered_json::array();
    for (const auto& l : c.result.contours) {
        nlohmann::ordered_json cj{{"level_m", l.level}, {"lines_a", l.linesA}, {"lines_b", l.linesB},
                                  {"H", jsonNumber(l.h.H)}, {"h_ab", jsonNumber(l.h.ab.value)},
                                  {"h_ba", jsonNumber(l.h.ba.value)}};
        if (std::isfinite(l.h.H) && l.linesA + l.linesB > 0) cj["where"] = whereJson(l.where, "xy_m");
        contours.push_back(cj);
    }
    j["contours"] = contours;
    j["max_profile_H"] = c.worstProfile;
    j["max_contour_H"] = jsonNumber(c.worstContour);
    return j;
}

void printComparison(const CompareGeometryOptions& o, const ComparedScenes& c) {
    using relief::measure::formatDistance;
    std::cout << fmt::format("a: {} ({})\nb: {} ({})\n", o.a, describeSurface(c.loadedA, c.surfaceA), o.b,
                             describeSurface(c.loadedB, c.surfaceB));
    for (const auto& p : c.result.profiles) {
        const auto& w = p.where;
        std::cout << fmt::format("profile {} ({:.1f} km): H = {}  (h(a,b) {}, h(b,a) {})\n", p.line.name,
                                 p.lengthM / 1000, formatDistance(p.h.H), formatDistance(p.h.ab.value),
                                 formatDistance(p.h.ba.value));
        std::cout << fmt::format("    at {:.0f} m along, lat {:.6f} lon {:.6f}: {} at {:.1f} m, nearest {} "
                                 "point ({:.0f} m along) at {:.1f} m\n",
                                 w.point.x, w.latDeg, w.lonDeg, w.onA ? "a" : "b", w.point.y,
                                 w.onA ? "b" : "a", w.foot.x, w.foot.y);
    }
    for (const auto& l : c.result.contours) {
        std::cout << fmt::format("contour {} m: {} line{} in a, {} in b: H = {}", relief::formatShortest(l.level),
                                 l.linesA, l.linesA == 1 ? "" : "s", l.linesB, formatDistance(l.h.H));
        if (l.linesA == 0 || l.linesB == 0) {
            std::cout << (l.linesA + l.linesB == 0 ? " (neither surface reaches it)\n"
                                                   : fmt::format(" (only {} reaches it)\n", l.linesA ? "a" : "b"));
            continue;
        }
        const auto& w = l.where;
        std::cout << fmt::format("  (h(a,b) {}, h(b,a) {})\n    at lat {:.6f} lon {:.6f} (x {:.0f}, y {:.0f} m): "
                                 "{}'s line is {} from {}'s nearest\n",
                                 formatDistance(l.h.ab.value), formatDistance(l.h.ba.value), w.latDeg, w.lonDeg,
                                 w.point.x, w.point.y, w.onA ? "a" : "b", formatDistance(l.h.H), w.onA ? "b" : "a");
    }
    std::cout << fmt::format("largest: {} between profiles, {} between contour lines\n",
                             formatDistance(c.worstProfile), formatDistance(c.worstContour));
}

// `relief compare-geometry`: Hausdorff distances between two scenes' surfaces.
int runCompareGeometry(const CompareGeometryOptions& o) {
    namespace m = relief::measure;
    relief::Diagnostics diags;
    relief::scene::SceneOverrides overA, overB;
    if (!parseOverrides(o.setA, overA) || !parseOverrides(o.setB, overB)) return code(Exit::BadInput);
    auto lines = parseProfileLines(o.profiles);
    if (!lines) return code(Exit::BadInput);
    auto levels = parseLevels(o.levels);
    if (!levels) return code(Exit::BadInput);
    auto loadedA = relief::loadScene(o.a, diags, overA);
    auto loadedB = relief::loadScene(o.b, diags, overB);
    auto surfA = loadedA ? relief::buildSurface(*loadedA, diags, o.threads) : std::nullopt;
    auto surfB = loadedB && surfA ? relief::buildSurface(*loadedB, diags, o.threads) : std::nullopt;
    if (!surfA || !surfB) {
        printDiagnostics(diags, false);
        return code(Exit::BadInput);
    }
    const m::FramedSurface A{o.a, &surfA->refined}, B{o.b, &surfB->refined};
    if (lines->empty()) lines = m::defaultProfiles(A, B);
    if (o.levels.empty()) levels = m::defaultLevels(A, B);
    const auto result = m::compareGeometry(A, B, *lines, *levels, o.samples, diags);
    if (!result) {
        printDiagnostics(diags, false);
        return code(Exit::BadInput);
    }
    printDiagnostics(diags, true);
    if (!o.map.empty()) {
        createParentFolder(o.map);
        relief::writeFileAtomically(o.map, relief::measure::comparisonMapSvg(*result, o.a, o.b, A.frame().describe()));
        std::cerr << "wrote " << o.map << '\n';
    }
    ComparedScenes compared{*loadedA, *loadedB, *surfA, *surfB, A, B, *result};
    for (const auto& p : result->profiles) compared.worstProfile = std::max(compared.worstProfile, p.h.H);
    for (const auto& c : result->contours) compared.worstContour = std::max(compared.worstContour, c.h.H);
    if (o.json) std::cout << comparisonJson(o, compared).dump(2, ' ', false, nlohmann::json::error_handler_t::replace) << '\n';
    else printComparison(o, compared);
    return code(Exit::Ok);
}

}  // namespace

void addGeometryCommands(CLI::App& app, std::vector<Command>& out) {
    auto hd = std::make_shared<HausdorffOptions>();
    CLI::App* hdCmd = app.add_subcommand(
        "hausdorff", "exact Hausdorff distance between two planar curves (paper 003): h(A,B), "
                     "h(B,A), H, the witness points and which of the four cases each is");
    hdCmd->add_option("a", hd->a, "curve file A (docs/curve-format.md)")->required();
    hdCmd->add_option("b", hd->b, "curve file B")->required();
    hdCmd->add_flag("--json", hd->json, "one JSON object with h_ab, h_ba, H and the witnesses");
    out.push_back({hdCmd, [hd] { return runHausdorff(*hd); }});

    auto profile = std::make_shared<ProfileOptions>();
    CLI::App* profileCmd = app.add_subcommand(
        "profile", "cut the refined surface (and the control net) along the geodesic between two "
                   "points: a curve file (distance, elevation in metres) and an SVG plot");
    profileCmd->add_option("scene", profile->common.scene, "scene file (TOML)")->required();
    profileCmd->add_option("--from", profile->from, "start: LON,LAT (WGS84 degrees)")->required();
    profileCmd->add_option("--to", profile->to, "end: LON,LAT")->required();
    profileCmd->add_option("--samples", profile->samples, "points along the line (default 1001)")
        ->check(CLI::Range(2, 1000000));
    profileCmd->add_option("--exaggeration", profile->exaggeration, "vertical exaggeration of the plot (default: chosen)")
        ->check(CLI::Range(0.0, 1000.0));
    profileCmd->add_option("-o,--output", profile->common.output,
                           "SVG (default out/<scene>-profile.svg); curve files beside it");
    profileCmd->add_option("--set", profile->common.sets, "override a scene key: section.key=value");
    out.push_back({profileCmd, [profile] { return runProfile(*profile); }});

    auto cg = std::make_shared<CompareGeometryOptions>();
    CLI::App* cgCmd = app.add_subcommand(
        "compare-geometry", "how far two scenes' refined surfaces are apart, in metres and where: "
                            "exact Hausdorff distance between matching profiles and between contour "
                            "lines at the same elevations");
    cgCmd->add_option("a", cg->a, "scene file a (TOML)")->required();
    cgCmd->add_option("b", cg->b, "scene file b (may be a again, with --set-b)")->required();
    cgCmd->add_option("--set-a", cg->setA, "override a key of scene a: section.key=value; repeatable");
    cgCmd->add_option("--set-b", cg->setB, "override a key of scene b: section.key=value; repeatable");
    cgCmd->add_option("--profile", cg->profiles,
                      "LON,LAT:LON,LAT, a geodesic to compare along; repeatable (default: west-east and "
                      "south-north through the centre of the common area)");
    cgCmd->add_option("--levels", cg->levels,
                      "contour elevations in metres, e.g. 500,1000,1500 (default: about five round "
                      "levels both surfaces reach)");
    cgCmd->add_option("--samples", cg->samples, "points per profile (default 1001)")->check(CLI::Range(2, 1000000));
    cgCmd->add_option("--threads", cg->threads, "refiner threads (0: all cores)")->check(CLI::Range(0, 256));
    cgCmd->add_flag("--json", cg->json, "one JSON object: profiles and contours with H, h_ab, h_ba and where");
    cgCmd->add_option("--map", cg->map, "also write an SVG map: both surfaces' contour lines, the profiles, "
                                        "and where each level's H is reached");
    out.push_back({cgCmd, [cg] { return runCompareGeometry(*cg); }});
}

}  // namespace relief::cli
