#include "pipeline.h"

#include <chrono>
#include <cmath>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "core/atomic_file.h"
#include "core/number_format.h"
#include "emit/mesh.h"
#include "geo/samples.h"
#include "measure/auto_depth.h"
#include "relief/version.h"
#include "scene/read_scene.h"
#include "subdiv/refine.h"

namespace relief {

namespace {

using Clock = std::chrono::steady_clock;
double secondsSince(Clock::time_point t0) {
    return std::chrono::duration<double>(Clock::now() - t0).count();
}

}  // namespace

std::string depthLabel(const scene::SceneDesc& scene) {
    return scene.depthAuto ? fmt::format("depth auto (tolerance_m = {})", formatShortest(scene.toleranceM))
                           : fmt::format("depth {}", scene.depth);
}

namespace {
std::string levelSeries(const measure::DepthChoice& choice) {
    std::string steps;
    for (const auto& l : choice.levels)
        steps += fmt::format("{}{}: {:.3g} m", steps.empty() ? "" : ", ", l.level, l.distanceM);
    return steps;
}
}  // namespace

std::string autoDepthSummary(const measure::DepthChoice& choice, double toleranceM) {
    const std::string steps = levelSeries(choice);
    return fmt::format("depth {} chosen: the largest change per level (Hausdorff, net rows and "
                       "columns) was {}; tolerance {} m",
                       choice.depth, steps, formatShortest(toleranceM));
}

std::string certifiedClass(const subdiv::SchemeReport& r) {
    return r.smoothness < 0 ? fmt::format("convergence not proven (Hölder ~{:.2f})", r.holder)
                            : fmt::format("C{} (Hölder ~{:.2f})", r.smoothness, r.holder);
}

namespace {

const char* name(scene::Gridding g) {
    switch (g) {
        case scene::Gridding::Linear: return "linear";
        case scene::Gridding::InverseDistance: return "invdist";
        case scene::Gridding::Nearest: return "nearest";
    }
    return "?";
}

emit::ParameterList describe(const scene::SceneDesc& s, const geo::ControlNet& net,
                             const LoadedScene& loaded, int depth,
                             const subdiv::OutputEstimate& est, double metresPerUnit) {
    emit::ParameterList p;
    auto add = [&](std::string k, std::string v) { p.emplace_back(std::move(k), std::move(v)); };
    add("relief", kVersion);
    add("scene", s.sceneFile.string());
    add("scene_sha1", s.sceneSha1);
    for (const auto& [k, v] : s.overrides) add("override " + k, v);
    add("samples.path", s.samplesPathAsWritten);
    add("samples.count", std::to_string(net.sampleCount));
    add("frame", net.frame.describe());
    add("net.size", fmt::format("{} rows x {} cols", net.grid.rows, net.grid.cols));
    add("net.spacing_m", fmt::format("{} x {}", formatShortest(net.dx), formatShortest(net.dy)));
    add("net.origin_m", fmt::format("{}, {}", formatShortest(net.x0), formatShortest(net.y0)));
    add("net.gridding", name(s.gridding));
    add("net.filled_outside_hull", std::to_string(net.filledOutsideHull));
    add("vertical.exaggeration", formatShortest(s.exaggeration));
    std::string params;
    for (const auto& [k, v] : loaded.schemeParams)
        params += fmt::format("{}{} = {}", params.empty() ? "" : ", ", k, formatShortest(v));
    if (loaded.schemeFamily == "mask")
        for (double v : s.mask) params += fmt::format("{}{}", params.empty() ? "mask " : ", ", formatShortest(v));
    add("subdivision.scheme", loaded.schemeFamily);
    if (!s.preset.empty()) add("subdivision.preset", s.preset);
    add("subdivision.params", params);
    add("subdivision.certified", certifiedClass(loaded.report));
    add("subdivision.boundary", "point reflection");
    add("subdivision.depth", s.depthAuto ? fmt::format("{} (auto, tolerance_m = {})", depth,
                                                       formatShortest(s.toleranceM))
                                         : std::to_string(depth));
    add("refined.size", fmt::format("{} rows x {} cols", est.rows, est.cols));
    add("refined.vertices", fmt::format("{:.0f}", est.vertices));
    add("refined.triangles", fmt::format("{:.0f}", est.triangles));
    add("texture.ramp", s.ramp.preset);
    add("lighting.sun", fmt::format("azimuth {} deg, altitude {} deg",
                                    formatShortest(s.sunAzimuthDeg),
                                    formatShortest(s.sunAltitudeDeg)));
    add("camera", fmt::format("{}, azimuth {} deg, elevation {} deg, distance {}, fov {} deg",
                              s.projection == scene::Projection::Perspective ? "perspective"
                                                                             : "orthographic",
                              formatShortest(s.cameraAzimuthDeg),
                              formatShortest(s.cameraElevationDeg),
                              s.cameraDistanceM > 0 ? formatShortest(s.cameraDistanceM) + " m"
                                                    : std::string("fit"),
                              formatShortest(s.fovDeg)));
    add("render", fmt::format("{} x {}, antialias {}", s.width, s.height,
                              s.antialias ? "on" : "off"));
    add("scene_unit_m", formatShortest(metresPerUnit));
    return p;
}

}  // namespace

std::filesystem::path defaultPngPath(const std::filesystem::path& scenePath,
                                     const std::string& sceneOutput) {
    if (!sceneOutput.empty()) return sceneOutput;
    return std::filesystem::path("out") / (scenePath.stem().string() + ".png");
}

OutputPaths outputPathsFor(const std::filesystem::path& png) {
    OutputPaths p;
    p.png = png;
    p.pov = png;
    p.pov.replace_extension(".pov");
    p.sidecar = png;
    p.sidecar.replace_extension(".json");
    return p;
}

std::optional<LoadedScene> loadScene(const std::filesystem::path& scenePath,
                                     Diagnostics& diags, const scene::SceneOverrides& overrides) {
    const auto t0 = Clock::now();
    auto desc = scene::readScene(scenePath, diags, overrides);
    if (!desc) return std::nullopt;
    LoadedScene loaded;
    loaded.schemeFamily = desc->scheme;
    std::map<std::string, double> params = desc->schemeParams;
    auto paramLocs = desc->schemeParamLocs;
    bool ok = true;
    if (!desc->preset.empty()) {
        std::map<std::string, double> familyParams;
        std::string family;
        ok = subdiv::resolvePreset(desc->preset, desc->presetLoc, params, paramLocs, diags,
                                   family, familyParams);
        if (ok && !desc->scheme.empty() && desc->scheme != family) {
            diags.error(desc->presetLoc,
                        fmt::format("preset \"{}\" is a case of scheme \"{}\", not \"{}\"; remove "
                                    "subdivision.scheme or the preset",
                                    desc->preset, family, desc->scheme));
            ok = false;
        }
        loaded.schemeFamily = family;
        params = familyParams;
        paramLocs.clear();
    }
    std::optional<subdiv::Scheme> scheme;
    if (ok && loaded.schemeFamily == "mask") {
        if (!params.empty())
            diags.error(paramLocs.begin()->second,
                        fmt::format("scheme = \"mask\" takes no parameter \"{}\"",
                                    params.begin()->first));
        else if (!desc->mask.empty())
            scheme = subdiv::schemeFromMask(
                desc->maskArity,
                desc->maskFirst.value_or(-(static_cast<int>(desc->mask.size()) - 1) / 2),
                desc->mask, desc->maskLoc, diags);
    } else if (ok) {
        scheme = subdiv::makeScheme(loaded.schemeFamily, desc->schemeLoc, params, paramLocs,
                                    diags, &loaded.schemeParams);
    }
    if (diags.hasErrors() || !scheme) return std::nullopt;
    loaded.scheme = std::move(*scheme);
    loaded.report = subdiv::analyzeScheme(loaded.scheme);
    if (loaded.report.smoothness < 0 && !desc->allowNonconvergent)
        diags.warning(desc->schemeLoc,
                      fmt::format("scheme \"{}\" with these parameters is not proven to converge "
                                  "(relief check says why): the terrain will look rough and "
                                  "fractal-like; set subdivision.allow_nonconvergent = true if "
                                  "that is what you want",
                                  loaded.schemeFamily));
    loaded.scene = std::move(*desc);
    loaded.seconds = secondsSince(t0);
    return loaded;
}

std::optional<CompileResult> compileScene(const LoadedScene& loaded,
                                          const CompileOptions& options, Diagnostics& diags) {
    CompileResult result;
    const scene::SceneDesc& desc = loaded.scene;
    result.times.readScene = loaded.seconds;

    auto tmpl = emit::loadSceneTemplate(options.templatesDir, diags);
    if (!tmpl) return std::nullopt;
    auto surface = buildSurface(loaded, diags, options.threads);
    if (!surface) return std::nullopt;
    result.estimate = surface->estimate;
    result.times.normalize = surface->normalizeSeconds;
    result.times.subdivide = surface->subdivideSeconds;
    const geo::ControlNet* net = &surface->net;
    const Grid& refined = surface->refined;

    const auto t0 = Clock::now();
    const emit::Mesh mesh = emit::buildMesh(refined, desc);
    result.refinedRows = refined.rows;
    result.arity = loaded.scheme.arity;
    result.holder = loaded.report.holder;
    result.refinedCols = refined.cols;
    result.metresPerUnit = mesh.metresPerUnit;
    result.depth = surface->depth;
    result.autoDepth = surface->autoDepth;
    result.parameters = describe(desc, *net, loaded, surface->depth, result.estimate, mesh.metresPerUnit);

    if (!options.dumpNetPath.empty()) {
        const bool asc = options.dumpNetPath.extension() == ".asc";
        if (asc && std::abs(net->dx - net->dy) > 1e-9 * net->dx) {
            diags.error({options.dumpNetPath.string(), 0, 0},
                        fmt::format("an ESRI ASCII grid needs square cells, but the net's "
                                    "spacing is {} x {} m; set net.spacing_m or dump to .csv",
                                    formatShortest(net->dx), formatShortest(net->dy)));
            return std::nullopt;
        }
    }
    if (!emit::writeScene(options.povPath, *tmpl, mesh, desc, result.parameters, diags))
        return std::nullopt;
    if (!options.dumpNetPath.empty())
        writeFileAtomically(options.dumpNetPath, options.dumpNetPath.extension() == ".asc"
                                                     ? geo::netToAsciiGrid(*net)
                                                     : geo::netToCsv(*net));
    result.times.emit = secondsSince(t0);
    std::error_code ec;
    result.povBytes = std::filesystem::file_size(options.povPath, ec);
    result.scene = desc;
    result.net = std::move(surface->net);
    return result;
}

std::optional<Surface> buildSurface(const LoadedScene& loaded, Diagnostics& diags, int threads) {
    const auto& desc = loaded.scene;
    auto t0 = Clock::now();
    const auto samples = geo::readSamples(desc.samplesPath, desc.samplesPathAsWritten, diags);
    if (diags.hasErrors()) return std::nullopt;
    auto net = geo::normalize(desc, samples, diags);
    if (!net) return std::nullopt;
    Surface s;
    s.normalizeSeconds = secondsSince(t0);
    const subdiv::Budget budget{desc.maxTriangles, desc.maxSdlMB, desc.maxParseS};
    s.depth = desc.depth;
    t0 = Clock::now();
    if (desc.depthAuto) {
        // The deepest level the budget allows bounds the search; when not
        // even level 1 fits, the budget check below says so.
        const int maxDepth = subdiv::deepestWithinBudget(loaded.scheme, net->grid.rows, net->grid.cols,
                                                         budget, scene::kMaxDepth);
        s.depth = 1;
        if (maxDepth > 0) {
            s.autoDepth = measure::chooseDepth(loaded.scheme, *net, desc.toleranceM, maxDepth, threads);
            const auto& last = s.autoDepth->levels.back();
            if (!s.autoDepth->reached) {
                diags.error(desc.toleranceLoc,
                            fmt::format("subdivision.tolerance_m = {} m is not reached within the output "
                                        "budget: level {} (the deepest [limits] allow) still moves {} by "
                                        "{:.3g} m (per level: {}); raise tolerance_m or [limits], or set "
                                        "a fixed depth",
                                        formatShortest(desc.toleranceM), last.level, last.curve,
                                        last.distanceM, levelSeries(*s.autoDepth)));
                return std::nullopt;
            }
            s.depth = s.autoDepth->depth;
        }
    }
    s.estimate = subdiv::estimateOutput(loaded.scheme, net->grid.rows, net->grid.cols, s.depth);
    if (!subdiv::checkBudget(s.estimate, budget, desc.depthAuto ? desc.depthLoc : desc.schemeLoc,
                             s.depth, diags))
        return std::nullopt;
    s.refined = subdiv::refineGrid(loaded.scheme, net->grid, s.depth, threads);
    s.subdivideSeconds = secondsSince(t0);
    const double factor = std::pow(loaded.scheme.arity, s.depth);
    s.refinedDx = net->dx / factor;
    s.refinedDy = net->dy / factor;
    s.net = std::move(*net);
    return s;
}

RenderOutcome renderSceneFile(const RenderJob& job, Diagnostics& diags,
                              const render::ProgressFn& progress) {
    RenderOutcome outcome;
    auto say = [&](const std::string& line) {
        if (progress) progress(line);
    };
    say("reading " + job.scenePath.string());
    auto loaded = loadScene(job.scenePath, diags, job.overrides);
    if (!loaded) return outcome;
    outcome.schemeFamily = loaded->schemeFamily;
    outcome.certified = certifiedClass(loaded->report);
    outcome.paths = outputPathsFor(job.png.empty()
                                       ? defaultPngPath(job.scenePath, loaded->scene.output)
                                       : job.png);
    CompileOptions copts;
    copts.povPath = outcome.paths.pov;
    copts.templatesDir = job.templatesDir;
    copts.dumpNetPath = job.dumpNetPath;
    copts.threads = job.threads;
    for (const auto& p : {outcome.paths.pov, job.dumpNetPath})
        if (!p.empty() && p.has_parent_path()) std::filesystem::create_directories(p.parent_path());
    say(fmt::format("compiling {} ({}, {})", job.scenePath.string(), loaded->schemeFamily,
                    depthLabel(loaded->scene)));
    outcome.compiled = compileScene(*loaded, copts, diags);
    if (!outcome.compiled) return outcome;

    render::RenderRequest req;
    req.pov = outcome.paths.pov;
    req.png = outcome.paths.png;
    req.width = loaded->scene.width;
    req.height = loaded->scene.height;
    req.antialias = loaded->scene.antialias;
    req.includeDirs = {job.templatesDir};
    req.threads = job.threads;
    outcome.render = render::renderPov(req, [&](const std::string& line) { say("povray: " + line); });
    if (!outcome.render.ok) {
        outcome.status = JobStatus::ToolFailed;
        return outcome;
    }
    writeFileAtomically(outcome.paths.sidecar,
                        sidecarJson(*outcome.compiled, outcome.paths, &outcome.render));
    outcome.status = JobStatus::Ok;
    return outcome;
}

std::string sidecarJson(const CompileResult& c, const OutputPaths& paths,
                        const render::RenderResult* render) {
    using nlohmann::ordered_json;
    ordered_json j;
    j["relief_version"] = kVersion;
    j["inputs"] = {{"scene", c.scene.sceneFile.string()},
                   {"scene_sha1", c.scene.sceneSha1},
                   {"samples", c.scene.samplesPath.string()},
                   {"sample_count", c.net.sampleCount}};
    ordered_json params = ordered_json::object();
    for (const auto& [k, v] : c.parameters) params[k] = v;
    j["parameters"] = params;
    j["net"] = {{"rows", c.net.grid.rows},
                {"cols", c.net.grid.cols},
                {"dx_m", c.net.dx},
                {"dy_m", c.net.dy},
                {"frame", c.net.frame.describe()},
                {"filled_outside_hull", c.net.filledOutsideHull}};
    j["refined"] = {{"rows", c.refinedRows},
                    {"cols", c.refinedCols},
                    {"vertices", static_cast<long long>(c.refinedRows) * c.refinedCols},
                    {"triangles", 2LL * (c.refinedRows - 1) * (c.refinedCols - 1)},
                    {"pov_bytes", c.povBytes}};
    ordered_json times = {{"read_scene", c.times.readScene},
                          {"normalize", c.times.normalize},
                          {"subdivide", c.times.subdivide},
                          {"emit", c.times.emit}};
    if (render) {
        times["povray_parse"] = render->parseSeconds;
        times["povray_trace"] = render->traceSeconds;
        times["povray_wall"] = render->wallSeconds;
        j["povray_command"] = render->command;
    }
    if (c.autoDepth) {
        ordered_json levels = ordered_json::array();
        const int arity = c.arity;
        for (size_t i = 0; i < c.autoDepth->levels.size(); ++i) {
            const auto& l = c.autoDepth->levels[i];
            ordered_json level = {{"level", l.level},
                                  {"hausdorff_m", l.distanceM},
                                  {"curve", l.curve},
                                  {"where_m", {l.x, l.y, l.z}},
                                  {"seconds", l.seconds}};
            const double rate = measure::observedRate(*c.autoDepth, i, arity);
            if (std::isfinite(rate)) level["rate"] = rate;
            levels.push_back(level);
        }
        j["auto_depth"] = {{"tolerance_m", c.scene.toleranceM},
                           {"depth", c.depth},
                           {"holder_estimate", c.holder},
                           {"levels", levels}};
    }
    j["seconds"] = times;
    j["outputs"] = {{"pov", paths.pov.string()}};
    if (render) j["outputs"]["png"] = paths.png.string();
    return j.dump(2) + "\n";
}

}  // namespace relief
