#include "cli/cli_common.h"

// relief hausdorff, relief profile, relief compare-geometry: distances in metres.
#include <cmath>
#include <iostream>
#include <memory>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "core/atomic_file.h"
#include "curves/curve_file.h"
#include "curves/hausdorff.h"
#include "emit/svg.h"
#include "geo/profile.h"
#include "pipeline.h"

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
        std::cout << j.dump(2) << '\n';
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
    double lon1, lat1, lon2, lat2;
    if (!parseLonLat(o.from, lon1, lat1) || !parseLonLat(o.to, lon2, lat2)) {
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
    const auto& net = surface->net;
    const auto line = relief::geo::geodesicProfile(net.frame, lat1, lon1, lat2, lon2, o.samples);
    relief::curves::CurveFile refined{"polyline", false, {}}, control{"polyline", false, {}};
    for (const auto& p : line) {
        const auto zr = relief::geo::sampleLattice(surface->refined, net.x0, net.y0, surface->refinedDx,
                                                   surface->refinedDy, p.x, p.y);
        const auto zc = relief::geo::sampleLattice(net.grid, net.x0, net.y0, net.dx, net.dy, p.x, p.y);
        if (!zr || !zc) {
            std::cerr << fmt::format("relief: error: the profile leaves the net {:.0f} m from the start "
                                     "(lat {:.6f}, lon {:.6f}); the net covers x {:.0f}..{:.0f} m, y "
                                     "{:.0f}..{:.0f} m in {}: choose points inside it\n",
                                     p.distanceM, p.latDeg, p.lonDeg, net.x0,
                                     net.x0 + (net.grid.cols - 1) * net.dx, net.y0,
                                     net.y0 + (net.grid.rows - 1) * net.dy, net.frame.describe());
            return code(Exit::BadInput);
        }
        refined.points.push_back({p.distanceM, *zr});
        control.points.push_back({p.distanceM, *zc});
    }
    const std::string stem = fs::path(o.common.scene).stem().string();
    const fs::path svg = o.common.output.empty() ? fs::path("out") / (stem + "-profile.svg") : fs::path(o.common.output);
    fs::path curveRefined = svg, curveNet = svg;
    curveRefined.replace_extension(".json");
    curveNet.replace_filename(svg.stem().string() + "-net.json");
    ensureParent(svg);
    double zmin = 1e300, zmax = -1e300;
    for (const auto& p : refined.points) zmin = std::min(zmin, p.y), zmax = std::max(zmax, p.y);
    const double length = line.back().distanceM;
    // Plot: relief about a third of the length unless asked otherwise.
    const double ve = o.exaggeration > 0 ? o.exaggeration
                                         : std::max(1.0, std::round(0.3 * length / std::max(zmax - zmin, 1e-9)));
    relief::emit::SvgAxes axes{true, ve, "distance along the geodesic (m)", "elevation (m)"};
    const std::string title = fmt::format("{}: profile, {:.0f} m, vertical exaggeration {:g}",
                                          fs::path(o.common.scene).filename().string(), length, ve);
    relief::writeFileAtomically(
        svg, relief::emit::curvesSvg(title, {"control net (bilinear)", control.points, false},
                                     {{fmt::format("refined: {} depth {} ({})", loaded->schemeFamily,
                                                   surface->depth, relief::certifiedClass(loaded->report)),
                                       refined.points, false}},
                                     axes));
    relief::writeFileAtomically(curveRefined, relief::curves::curveFileJson(refined));
    relief::writeFileAtomically(curveNet, relief::curves::curveFileJson(control));
    std::cerr << fmt::format("wrote {}, {} (refined) and {} (control net): {} points over {:.1f} m, "
                             "elevation {:.1f}..{:.1f} m\n",
                             svg.string(), curveRefined.string(), curveNet.string(), line.size(), length,
                             zmin, zmax);
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
    profileCmd->add_option("--exaggeration", profile->exaggeration, "vertical exaggeration of the plot (default: chosen)");
    profileCmd->add_option("-o,--output", profile->common.output,
                           "SVG (default out/<scene>-profile.svg); curve files beside it");
    profileCmd->add_option("--set", profile->common.sets, "override a scene key: section.key=value");
    out.push_back({profileCmd, [profile] { return runProfile(*profile); }});
}

}  // namespace relief::cli
