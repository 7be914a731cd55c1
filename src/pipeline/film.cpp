// relief animate: the frames' scenes loaded, the terrain compiled once for
// the frames it serves, a render plan a frame, the tiles rendered (one frame
// first, to tell how long the rest will take), the frames finished as
// stills, the film encoded, all written as one set.
#include "pipeline/film.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <set>
#include <thread>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "pipeline/film_flyover.h"
#include "pipeline/run_plans.h"
#include "scene/read_scene_table.h"
#include "pipeline/working_folder.h"
#include "core/atomic_file.h"
#include "core/hash.h"
#include "core/number_format.h"
#include "core/stopwatch.h"
#include "core/text_escape.h"
#include "relief/version.h"
#include "subdiv/budget.h"

namespace relief {

namespace fs = std::filesystem;

namespace {

// The film's job and its scene, read once: every frame's spec is read from the document.
struct FilmScene {
    const AnimateJob& job;
    const scene::SceneDocument& document;
};

// "camera.azimuth_deg=90 lighting.datetime=..." : a frame's keys as --set takes them.
std::string setsText(const scene::SceneOverrides& overrides) {
    std::string text;
    for (const auto& [k, v] : overrides) text += (text.empty() ? "" : " ") + k + "=" + v;
    return text;
}

// A frame's scene: the scene read once, with the frame's keys set. A key that
// makes the scene wrong is reported at `key`, the [animation] key that set it.
std::optional<LoadedScene> loadFrame(const FilmScene& film, const scene::AnimationSpec& a, const FilmFrame& f,
                                     const char* key, Diagnostics& diags) {
    scene::SceneOverrides overrides = film.job.overrides;
    overrides.insert(overrides.end(), f.settings.overrides.begin(), f.settings.overrides.end());
    Diagnostics own;  // the file's warnings were told once, with the scene
    auto loaded = loadScene(film.document, own, overrides);
    if (loaded && own.errorCount() == 0) return loaded;
    const auto first = std::find_if(own.all().begin(), own.all().end(),
                                    [](const Diagnostic& d) { return d.severity == Severity::Error; });
    diags.error(a.locs.at(key), fmt::format("frame {} sets {}: {}", f.settings.number,
                                            terminalText(setsText(f.settings.overrides), 500),
                                            first != own.all().end() ? first->message : "the scene is not valid"));
    return std::nullopt;
}

std::optional<std::vector<LoadedScene>> loadFrames(const FilmScene& film, const LoadedScene& base,
                                                   const std::vector<FilmFrame>& frames, Diagnostics& diags) {
    std::vector<LoadedScene> scenes;
    for (const auto& f : frames) {
        const scene::AnimationSpec& a = base.scene.animation;
        auto loaded = loadFrame(film, a, f, !a.vary.empty() ? "animation.vary" : "animation", diags);
        if (!loaded) return std::nullopt;
        scenes.push_back(std::move(*loaded));
    }
    return scenes;
}

// An orbit whose camera the scene frames by itself (no distance, no position):
// one distance for every frame, at which the terrain's bounding sphere fills
// the narrower side of the frame, so that the framing does not breathe as each
// frame's own outline would make it (a frame's fit is tight to what it sees).
// The target is then the terrain's centre in every frame. As a key, so that
// relief render of a frame's keys makes that frame.
std::optional<std::string> steadyOrbitDistance(const scene::SceneSpec& spec, const emit::ScenePlacement& where) {
    const scene::CameraSpec& camera = spec.look.camera;
    // An orthographic orbit keeps its own fit (its height, not a distance, frames it).
    if (spec.animation.path != scene::CameraPath::Orbit || camera.distanceM > 0 || camera.position ||
        camera.projection == scene::Projection::Orthographic)
        return std::nullopt;
    for (const auto& v : spec.animation.vary)
        if (v.key == "camera.distance_m") return std::nullopt;
    const double radiusM = 0.5 * length(where.boundsMax - where.boundsMin) * where.metresPerUnit;
    // A panorama or a sphere stands where the default perspective camera would (emit::placeCamera).
    const bool pinhole = camera.projection == scene::Projection::Perspective;
    const double tanH = std::tan((pinhole ? camera.fovDeg : scene::CameraSpec{}.fovDeg) * std::numbers::pi / 360);
    const double tanNarrow = std::min(tanH, tanH * spec.render.height / spec.render.width);
    const double distanceM = 1.02 * radiusM / std::sin(std::atan(tanNarrow));  // 2 % margin
    return formatShortest(std::ceil(distanceM * 100) / 100);
}

// The keys the compiled terrain gives the group's frames: the depth, when it
// was chosen for the scene's own view (a frame's own camera would choose
// another, and relief render of the frame's keys must make this terrain);
// and for a flyover each frame's camera over the surface. The frames' scenes
// are loaded again with them.
bool addTerrainKeys(const FilmScene& film, const SharedTerrain& terrain, const std::vector<size_t>& group,
                    std::vector<LoadedScene>& scenes, std::vector<FilmFrame>& frames, Diagnostics& diags) {
    const scene::SceneSpec& spec = scenes[group.front()].scene;
    const scene::AnimationSpec& a = spec.animation;
    const bool chosenDepth = !spec.subdivision.depthGiven && !spec.subdivision.depthAuto;
    const auto steady = steadyOrbitDistance(spec, terrain.placement());
    if (!chosenDepth && a.path != scene::CameraPath::Flyover && !steady) return true;
    std::vector<scene::SceneOverrides> cameras(group.size());
    if (a.path == scene::CameraPath::Flyover) {
        auto keys = flyoverKeys(a, terrain.refined(), group, diags);
        if (!keys) return false;
        cameras = std::move(*keys);
    }
    if (steady)
        for (auto& c : cameras) c.emplace_back("camera.distance_m", *steady);
    for (size_t g = 0; g < group.size(); ++g) {
        const size_t i = group[g];
        auto& overrides = frames[i].settings.overrides;
        if (chosenDepth) overrides.emplace_back("subdivision.depth", std::to_string(terrain.depth()));
        overrides.insert(overrides.end(), cameras[g].begin(), cameras[g].end());
        const char* key = a.path == scene::CameraPath::Flyover ? "animation.path" : "animation";
        auto loaded = loadFrame(film, a, frames[i], key, diags);
        if (!loaded) return false;
        scenes[i] = std::move(*loaded);
    }
    return true;
}

// The keys a frame sets that shape the terrain (not only the view): frames
// with the same ones share one compiled terrain.
std::string terrainKeys(const film::FrameSettings& f) {
    std::string keys;
    for (const auto& [k, v] : f.overrides)
        if (!film::changesOnlyTheView(k)) keys += k + "=" + v + "\n";
    return keys;
}

// animation.sun: each frame's sun over the terrain's centre; a frame at night
// is left out (skip_night) or an error naming it.
bool checkNights(const scene::AnimationSpec& a, const geo::ControlNet& net, const std::vector<size_t>& group,
                 std::vector<FilmFrame>& frames, Diagnostics& diags) {
    if (!a.sun) return true;
    for (size_t i : group) {
        FilmFrame& f = frames[i];
        const auto sun = sunOverTerrain(net, f.settings.sunTime->utcSeconds);
        if (!sun) {
            diags.error(a.locs.at("animation.sun"),
                        "animation.sun: the terrain's centre has no longitude and latitude "
                        "in its frame, so the sun cannot be placed over it");
            return false;
        }
        f.sunAltitudeDeg = sun->first.altitudeDeg;
        f.night = !(f.sunAltitudeDeg > 0);
        if (f.night && !a.skipNight) {
            diags.error(a.locs.at("animation.sun"),
                        fmt::format("animation.sun: at frame {} ({}) the sun is {:.1f} degrees below the horizon over "
                                    "the terrain's centre (lon {:.4f}, lat {:.4f}); choose a window in daylight, or "
                                    "set skip_night = true to leave such frames out",
                                    f.settings.number, formatOffsetDateTime(*f.settings.sunTime), -f.sunAltitudeDeg,
                                    sun->second.lonDeg, sun->second.latDeg));
            return false;
        }
    }
    return true;
}

// The film's working folder: the shared terrains' files, a plan a frame, the frames.
struct FilmWork {
    fs::path dir;
    std::vector<plan::RenderPlan> plans;  ///< of the frames kept, in order
    std::vector<size_t> planFrame;        ///< the frame each plan renders
    bool resumed = false;                 ///< by --resume: the folder is the user's to keep, refused or not
};

// A compiled terrain's files, hard-linked into a frame's plan (no copy of a 100 MB mesh).
void linkShared(const std::vector<plan::PlanFile>& shared, const fs::path& sharedDir, plan::RenderPlan& plan) {
    for (const auto& f : shared) {
        linkOrCopy(sharedDir / f.name, plan.dir / f.name);
        plan.reads.push_back(f);
    }
}

// One frame's plan: its .pov (the frame's camera, sun and overlays around the shared terrain).
bool planFrame(const AnimateJob& job, const LoadedScene& scene, const SharedTerrain& terrain,
               const std::vector<plan::PlanFile>& shared, const fs::path& sharedDir, const FilmFrame& frame,
               FilmWork& work, Diagnostics& diags) {
    plan::RenderPlan plan;
    plan.dir = work.dir / film::framePlanName(frame.settings.number);
    fs::create_directories(plan.dir);
    linkShared(shared, sharedDir, plan);
    CompileOptions options;
    options.povPath = plan.dir / "frame.pov";
    options.templatesDir = job.templatesDir;
    options.writeAt = [&](const fs::path& final, std::string_view role) {
        plan.pov = {final.filename().string(), final, std::string(role), ""};
        return final;
    };
    const auto compiled = compileView(scene, terrain, options, diags);
    if (!compiled) return false;
    OutputPaths paths;
    paths.still = plan.dir / "frame.png";  // a label only: finishFrames names the frames kept
    paths.pov = options.povPath;
    paths.sidecar = plan.dir / "frame.json";
    describeRender(plan, scene.scene, *compiled, paths, job.tiles);
    plan::copyTemplates(plan, job.templatesDir);
    work.plans.push_back(std::move(plan));  // written once the film's furniture has its places
    return true;
}

// Every frame of one terrain: the terrain compiled (its files in terrain-N/), the nights told, a plan a frame.
bool planGroup(const FilmScene& film, std::vector<LoadedScene>& scenes, const std::vector<size_t>& group,
               int groupIndex, std::vector<FilmFrame>& frames, FilmWork& work, Diagnostics& diags,
               const ProgressFn& progress) {
    const AnimateJob& job = film.job;
    const fs::path sharedDir = work.dir / fmt::format("terrain-{}", groupIndex + 1);
    fs::create_directories(sharedDir);
    std::vector<plan::PlanFile> shared;
    CompileOptions options;
    options.povPath = sharedDir / "frame.pov";
    options.templatesDir = job.templatesDir;
    options.threads = job.threads;
    options.progress = progress;
    options.writeAt = [&](const fs::path& final, std::string_view role) {
        shared.push_back({final.filename().string(), final, std::string(role), ""});
        return sharedDir / final.filename();
    };
    // The terrain does not depend on the sun: compiled with the scene's angles, so that a first
    // frame at night is told by checkNights (naming the frame), not by the still's own check.
    LoadedScene terrainScene = scenes[group.front()];
    terrainScene.scene.look.lighting.sunTime.reset();
    const auto terrain = compileSharedTerrain(terrainScene, options, diags);
    // Hashed once for every frame's plan: each hard link added moves a file's change time, which
    // fileSha256 would take for a change.
    for (auto& f : shared) {
        std::string problem;
        f.sha256 = fileSha256(sharedDir / f.name, problem);
    }
    if (!terrain || !checkNights(scenes.front().scene.animation, terrain->net(), group, frames, diags) ||
        !addTerrainKeys(film, *terrain, group, scenes, frames, diags))
        return false;
    for (size_t i : group) {
        if (frames[i].night) continue;
        if (!planFrame(job, scenes[i], *terrain, shared, sharedDir, frames[i], work, diags)) return false;
        work.planFrame.push_back(i);
    }
    return true;
}

}  // namespace

namespace {

// The frames grouped by the terrain they need, in the order of their first frame.
std::vector<std::vector<size_t>> terrainGroups(const std::vector<FilmFrame>& frames) {
    std::vector<std::vector<size_t>> groups;
    std::map<std::string, size_t> byKeys;
    for (size_t i = 0; i < frames.size(); ++i) {
        const auto [at, added] = byKeys.emplace(terrainKeys(frames[i].settings), groups.size());
        if (added) groups.emplace_back();
        groups[at->second].push_back(i);
    }
    return groups;
}

// The numbers of the frames kept, 1, 2, ... in film order (nights are known once each terrain is compiled).
void numberKeptFrames(std::vector<FilmFrame>& frames) {
    int n = 0;
    for (auto& f : frames) f.fileNumber = f.night ? 0 : ++n;
}

// The tiles of the frames' plans from..to-1 rendered (the film's Slurm job in its working folder); the
// outcome says why not.
bool renderFrames(const std::vector<plan::RenderPlan>& plans, size_t from, size_t to, const execute::Options& execution,
                  AnimateOutcome& outcome, Diagnostics& diags, const ProgressFn& progress) {
    std::vector<const plan::RenderPlan*> these;
    for (size_t i = from; i < to; ++i) these.push_back(&plans[i]);
    execute::Options options = execution;
    if (options.jobDir.empty()) options.jobDir = plans[from].dir.parent_path() / "slurm";
    const PlansRendered r = renderPlans(these, options, {progress, "frames", from, plans.size(), {}}, diags);
    if (r.status == JobStatus::Ok) return true;
    outcome.status = r.status;
    outcome.toolError = r.error;
    return false;
}

// What the rest of the film will cost, from one frame rendered alone.
struct FilmEstimate {
    size_t framesLeft = 0;
    double secondsLeft = 0;   ///< wall seconds here (core-seconds shared by a cluster's tasks on Slurm)
    double povrayPeakMB = 0;  ///< the probe's largest POV-Ray
    int atOnce = 1;           ///< POV-Rays at once here (Slurm: on their own nodes, 1 each)
    double diskMB = 0;        ///< the frames' PNGs in the working folder (the tiles and the frames)
};

FilmEstimate estimateFilm(const std::vector<plan::RenderPlan>& plans, size_t probe, double probeSeconds,
                          const execute::Options& execution) {
    FilmEstimate e;
    std::uintmax_t probeBytes = 0;
    for (int k = 0; k < plans[probe].tiles; ++k) {
        std::string problem;
        if (const auto r = plan::readTileRecord(plans[probe], k, problem))
            e.povrayPeakMB = std::max(e.povrayPeakMB, r->peakMemoryMB);
        std::error_code ec;
        const auto bytes = fs::file_size(plan::tileImage(plans[probe], k), ec);
        if (!ec) probeBytes += bytes;
    }
    size_t tasksLeft = 0;
    for (size_t i = probe + 1; i < plans.size(); ++i) {
        const size_t missing = plan::missingTiles(plans[i]).size();
        tasksLeft += missing;
        e.framesLeft += missing > 0;
    }
    e.secondsLeft = probeSeconds * double(e.framesLeft);
    if (execution.executor == execute::Executor::Local) {
        const int cores = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
        e.atOnce = static_cast<int>(std::clamp<size_t>(execution.jobs > 0 ? execution.jobs : cores, 1,
                                                       std::max<size_t>(1, tasksLeft)));
    }
    e.diskMB = 2.0 * double(probeBytes) * double(plans.size()) / 1e6;
    return e;
}

// "0.8 MB", "57 MB", "2300 MB".
std::string megabytes(double mb) {
    return mb < 10 ? fmt::format("{:.1f} MB", mb) : fmt::format("{:.0f} MB", mb);
}

std::string estimateText(const FilmEstimate& e, double probeSeconds, const execute::Options& execution) {
    const bool here = execution.executor == execute::Executor::Local;
    return fmt::format("a frame rendered in {:.1f} s (POV-Ray at most {}): {} frame{} more, about {:.0f} s of "
                       "rendering{}, {}; about {} of frames on disk",
                       probeSeconds, megabytes(e.povrayPeakMB), e.framesLeft, e.framesLeft == 1 ? "" : "s",
                       e.secondsLeft, here ? "" : " (divided among the cluster's tasks)",
                       here ? fmt::format("{} POV-Ray{} at once ({})", e.atOnce, e.atOnce == 1 ? "" : "s",
                                          megabytes(e.povrayPeakMB * e.atOnce))
                            : megabytes(e.povrayPeakMB) + " a task",
                       megabytes(e.diskMB));
}

// [limits] against the estimate: the film's rendering time, and the memory its POV-Rays hold at once here.
// A resumed film's limits and frames are its record's: only where it renders can change.
bool withinFilmLimits(const FilmEstimate& e, double probeSeconds, const scene::LimitsSpec& limits,
                      const execute::Options& execution, bool resumed, Diagnostics& diags) {
    const double total = probeSeconds + e.secondsLeft;
    if (limits.maxFilmS > 0 && total > limits.maxFilmS) {
        diags.error(limits.locs.at("limits.max_film_s"),
                    fmt::format("the film would take about {:.0f} s to render (a frame {:.1f} s, {} more) > "
                                "limits.max_film_s = {}: {}",
                                total, probeSeconds, e.framesLeft, formatShortest(limits.maxFilmS),
                                resumed ? "share the rest out (--jobs, --executor slurm), or make the film again "
                                          "with a higher limit"
                                        : "raise the limit, render fewer or smaller frames (animation.frames, "
                                          "render.width), or share them out (--jobs, --executor slurm)"));
        return false;
    }
    const double budgetMB = subdiv::Budget::of(limits).maxMemoryMB;  // the job's own figure
    if (execution.executor == execute::Executor::Local && e.atOnce > 1 && e.povrayPeakMB * e.atOnce > budgetMB) {
        diags.error(limits.locs.at("limits.max_memory_mb"),
                    fmt::format("{} POV-Rays at once would hold about {:.0f} MB (a frame's POV-Ray {:.0f} MB) > "
                                "limits.max_memory_mb = {:.0f}: give --jobs {} or fewer",
                                e.atOnce, e.povrayPeakMB * e.atOnce, e.povrayPeakMB, budgetMB,
                                std::max(1, int(budgetMB / std::max(1.0, e.povrayPeakMB)))));
        return false;
    }
    return true;
}

// The film's sidecar: what it was made from, every frame's keys (relief render --set of them makes that frame).
// `frameNodes`: a frame's nodes (plan::tileNodes of its plan), by frame.
std::string filmSidecar(const film::FilmRecord& record, const AnimateOutcome& o, const film::VideoRequest& video,
                        const FilmEstimate& estimate, const std::vector<std::vector<std::string>>& frameNodes) {
    nlohmann::ordered_json frames = nlohmann::ordered_json::array();
    std::map<std::string, int> framesOn;  // a node's name: the frames it rendered (a tile of)
    for (size_t i = 0; i < record.frames.size(); ++i) {
        const auto& f = record.frames[i];
        nlohmann::ordered_json set = nlohmann::ordered_json::object();
        for (const auto& [k, v] : f.settings.overrides) set[k] = v;
        nlohmann::ordered_json j = {{"number", f.settings.number}, {"set", set}};
        if (f.settings.sunTime) j["sun_altitude_deg"] = std::round(f.sunAltitudeDeg * 1e4) / 1e4;
        if (f.fileNumber)
            j["file"] = film::frameFileName(f.fileNumber);
        else
            j["left_out"] = "night";
        if (i < frameNodes.size() && !frameNodes[i].empty()) {
            j["nodes"] = frameNodes[i];
            for (const std::string& n : std::set<std::string>(frameNodes[i].begin(), frameNodes[i].end())) ++framesOn[n];
        }
        frames.push_back(j);
    }
    // The command as run, with the working folder's frames and the staged film named as kept.
    const std::vector<std::string> command = film::ffmpegCommand(video);
    nlohmann::ordered_json j = {
        {"relief_version", kVersion},
        {"scene", record.scene.string()},
        {"scene_sha1", record.sceneSha1},
        {"film", record.film.filename().string()},
        {"fps", record.fps},
        {"frames_in_film", video.frameCount},
        {"terrains_compiled", record.terrains},
        {"frames", frames},
        {"nodes", framesOn},
        {"ffmpeg", {{"version", film::ffmpegVersion()}, {"command", command}}},
        {"estimate",
         {{"render_s", std::round(estimate.secondsLeft * 10) / 10},
          {"povray_peak_memory_mb", estimate.povrayPeakMB},
          {"povrays_at_once", estimate.atOnce}}},
        {"seconds",
         {{"compile", record.compileSeconds},
          {"first_frame", o.probeSeconds},
          {"render", o.renderSeconds},
          {"encode", o.encodeSeconds}}},
    };
    return j.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n";
}

// The frames' stills, written into work/frames/ (what ffmpeg reads) and, for --frames, into the set.
bool finishFrames(const film::FilmRecord& record, const FilmWork& work, OutputSet& outputs, Diagnostics& diags) {
    makeOwnFolder(work.dir / "frames");
    for (size_t p = 0; p < work.plans.size(); ++p) {
        std::optional<annotate::OverlayRecord> overlays;
        const auto still = stillOfPlan(work.plans[p], overlays, diags);
        if (!still) return false;
        const std::string name = film::frameFileName(static_cast<int>(p) + 1);
        const fs::path png = work.dir / "frames" / name;
        writePngAtomically(png, {still->width, still->height, still->channels, false, still->pixels.data()});
        if (record.framesDir.empty()) continue;
        linkOrCopy(png, outputs.staged(record.framesDir / name));
    }
    return true;
}

// The furniture at the same places in every frame (annotate::steadyPlaces), each
// frame's key overlay.place saying them, so that relief render of a frame's
// keys makes that frame.
void keepFurnitureSteady(film::FilmRecord& record, FilmWork& work) {
    std::vector<annotate::FrameOverlays> frames;
    for (const auto& p : work.plans)
        if (p.overlays) frames.push_back({&p.overlaySpec, &p.overlayFacts});
    if (frames.empty()) return;
    const auto places = annotate::steadyPlaces(frames, work.plans.front().width, work.plans.front().height);
    if (places.empty()) return;
    std::string table;  // items and places are relief's own names (kFurnitureItems, kFurniturePlaces)
    for (const auto& [item, where] : places) table += (table.empty() ? "{ " : ", ") + item + " = \"" + where + "\"";
    table += " }";
    for (size_t i = 0; i < work.plans.size(); ++i) {
        work.plans[i].overlaySpec.places = places;
        record.frames[work.planFrame[i]].settings.overrides.emplace_back("overlay.place", table);
    }
}

// Compiling: the frames' scenes, a terrain for each group of them, a plan a frame.
bool planFilm(const FilmScene& film, const LoadedScene& base, film::FilmRecord& record, FilmWork& work,
              Diagnostics& diags, const ProgressFn& progress) {
    auto scenes = loadFrames(film, base, record.frames, diags);
    if (!scenes) return false;
    const auto groups = terrainGroups(record.frames);
    record.terrains = static_cast<int>(groups.size());
    // Nights are known per terrain; a frame's number among those kept once all are.
    for (size_t g = 0; g < groups.size(); ++g) {
        if (progress)
            progress({ProgressEvent::Stage::Compiling,
                      fmt::format("compiling the terrain{} for {} frame{}",
                                  groups.size() > 1 ? fmt::format(" {} of {}", g + 1, groups.size()) : "",
                                  groups[g].size(), groups[g].size() == 1 ? "" : "s"),
                      -1});
        if (!planGroup(film, *scenes, groups[g], static_cast<int>(g), record.frames, work, diags, progress))
            return false;
    }
    numberKeptFrames(record.frames);
    if (work.plans.empty()) {
        diags.error(base.scene.animation.locs.at("animation.sun"),
                    "animation.sun: the sun is below the horizon over the terrain's centre at every frame: choose a "
                    "window in daylight");
        return false;
    }
    // The plans in film order (planned a terrain at a time).
    std::vector<size_t> order(work.plans.size());
    for (size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return work.planFrame[a] < work.planFrame[b]; });
    FilmWork sorted{work.dir, {}, {}};
    for (size_t i : order) {
        sorted.plans.push_back(std::move(work.plans[i]));
        sorted.planFrame.push_back(work.planFrame[i]);
    }
    work = std::move(sorted);
    keepFurnitureSteady(record, work);
    for (auto& plan : work.plans)
        if (!writePlan(plan, diags)) return false;
    return true;
}

// The film's outputs, declared before any work: the film, --frames' PNGs, the sidecar last.
void declareFilmOutputs(const film::FilmRecord& record, OutputSet& outputs) {
    outputs.add(record.film, record.filmGiven ? "-o" : "the film");
    if (!record.framesDir.empty())
        for (const auto& f : record.frames)
            if (f.fileNumber) outputs.add(record.framesDir / film::frameFileName(f.fileNumber), "--frames");
    outputs.add(record.sidecar, "the sidecar", true);
    outputs.addInput(record.scene, "the scene file");
}

// A whole film's working folder: its record reads back and its first kept frame's plan is there
// (frames left out at night have none).
bool isFilmFolder(const fs::path& dir) {
    Diagnostics unused;
    const auto record = film::readFilmRecord(dir, unused);
    if (!record) return false;
    std::error_code ec;
    for (const auto& f : record->frames)
        if (f.fileNumber) return fs::is_directory(dir / film::framePlanName(f.settings.number), ec);
    return false;
}

const WorkingFolderKind kFilmFolder{"the film's working folder", "a film's working folder", "give -o another name",
                                    isFilmFolder};

// The working folder's frames rendered (one alone first: how long it took
// tells how long the rest will, and the record's [limits] may refuse that),
// finished, encoded; the film, its sidecar and --frames moved into place, the
// folder removed. A film not made keeps the folder (outcome.workDir) to
// resume; one refused keeps it only when resumed, with the frames rendered.
void makeFilm(const film::FilmRecord& record, FilmWork& work, const execute::Options& execution,
              OutputSet& outputs, AnimateOutcome& outcome, Diagnostics& diags, const ProgressFn& progress) {
    outcome.workDir = work.dir;
    const auto r0 = Clock::now();
    size_t probe = 0;
    while (probe < work.plans.size() && plan::missingTiles(work.plans[probe]).empty()) ++probe;
    FilmEstimate estimate;
    if (probe < work.plans.size()) {
        if (probe > 0 && progress)
            progress({ProgressEvent::Stage::Rendering,
                      fmt::format("{} of {} frames were rendered before", probe, work.plans.size()), -1});
        if (!renderFrames(work.plans, probe, probe + 1, execution, outcome, diags, progress)) return;
        outcome.probeSeconds = secondsSince(r0);
        estimate = estimateFilm(work.plans, probe, outcome.probeSeconds, execution);
        if (progress && estimate.framesLeft > 0)
            progress({ProgressEvent::Stage::Rendering, estimateText(estimate, outcome.probeSeconds, execution), -1});
        if (!withinFilmLimits(estimate, outcome.probeSeconds, record.limits, execution, work.resumed, diags)) {
            outcome.status = JobStatus::BadInput;
            if (work.resumed) return;  // to resume again, e.g. with fewer --jobs
            outcome.workDir.clear();  // refused: nothing is kept
            std::error_code ec;
            fs::remove_all(work.dir, ec);
            return;
        }
        if (!renderFrames(work.plans, probe + 1, work.plans.size(), execution, outcome, diags, progress)) return;
    }
    outcome.renderSeconds = secondsSince(r0);

    if (progress) progress({ProgressEvent::Stage::Finishing, "finishing " + shownPath(record.film).string(), -1});
    if (!finishFrames(record, work, outputs, diags)) return;
    const auto e0 = Clock::now();
    film::VideoRequest video;
    film::videoFormatOf(record.film, video.format);
    video.workDir = work.dir;
    video.frameCount = static_cast<int>(work.plans.size());
    video.fps = record.fps;
    video.output = outputs.staged(record.film);
    if (const std::string error = film::encodeVideo(video); !error.empty()) {
        outcome.status = JobStatus::ToolFailed;
        outcome.toolError = error;
        return;
    }
    outcome.encodeSeconds = secondsSince(e0);
    std::vector<std::vector<std::string>> frameNodes(record.frames.size());
    for (size_t p = 0; p < work.plans.size(); ++p) frameNodes[work.planFrame[p]] = plan::tileNodes(work.plans[p]);
    writeFileAtomically(outputs.staged(record.sidecar), filmSidecar(record, outcome, video, estimate, frameNodes));
    outputs.commit();
    outcome.status = JobStatus::Ok;
    std::error_code ec;
    fs::remove_all(work.dir, ec);
    outcome.workDir.clear();
}

// Any failure of the film's files, told at the file it concerns.
void reportFilmFailure(const std::runtime_error& e, AnimateOutcome& outcome, Diagnostics& diags) {
    if (const auto* out = dynamic_cast<const OutputError*>(&e))
        diags.error(out->at(), out->problem());
    else
        diags.error({}, e.what());
    outcome.status = JobStatus::BadInput;
}

// The record of a film about to be planned: its names, from the job and the scene.
film::FilmRecord filmRecordOf(const AnimateJob& job, const LoadedScene& base, const fs::path& film) {
    film::FilmRecord r;
    r.scene = job.scenePath;
    r.sceneSha1 = base.scene.sceneSha1;
    r.fps = base.scene.animation.fps;
    r.film = fs::absolute(film);
    r.sidecar = fs::absolute(fs::path(film).replace_extension(".json"));
    r.framesDir = job.framesDir.empty() ? fs::path() : fs::absolute(job.framesDir);
    r.filmGiven = !job.output.empty();
    r.limits = base.scene.limits;
    for (auto& settings : film::frameSettings(base.scene)) r.frames.push_back({std::move(settings)});
    return r;
}

// The scene's film, before it is compiled: an error when it cannot be made.
bool filmCanBeMade(const AnimateJob& job, const LoadedScene& base, const fs::path& film, AnimateOutcome& outcome,
                   Diagnostics& diags) {
    const scene::AnimationSpec& a = base.scene.animation;
    if (!a.present) {
        diags.error({job.scenePath.string(), 0, 0},
                    "the scene has no [animation] section: add one, e.g. [animation] frames = 120 and path = "
                    "\"orbit\" (docs/animation.md)");
        return false;
    }
    // A frame's camera.position is the flyover's; the scene's own would be overridden unseen.
    if (a.path == scene::CameraPath::Flyover && base.scene.look.camera.position) {
        diags.error(a.locs.at("animation.path"),
                    "animation.path = \"flyover\" moves the eye along the path, but camera.position places "
                    "it: remove camera.position (and camera.look_at; animation.look_at fixes where the camera "
                    "looks)");
        return false;
    }
    film::VideoFormat format;
    if (!film::videoFormatOf(film, format)) {
        diags.error({film.string(), 0, 0}, "a film is written as .mp4 (H.264), .webm (VP9) or .gif: give -o one of them");
        return false;
    }
    if (render::findOnPath("ffmpeg").empty()) {
        outcome.status = JobStatus::ToolFailed;
        outcome.toolError = "ffmpeg is not installed, and it encodes the film (Debian: apt-get install ffmpeg)";
        return false;
    }
    return true;
}

}  // namespace

AnimateOutcome runAnimateJob(const AnimateJob& job, Diagnostics& diags, const ProgressFn& progress) {
    AnimateOutcome outcome;
    const auto t0 = Clock::now();
    try {
        if (progress) progress({ProgressEvent::Stage::Reading, "reading " + job.scenePath.string(), -1});
        // The scene read once: every frame's spec is read from it, with the frame's keys.
        const auto document = readSceneDocument(job.scenePath, diags);
        const auto base = document ? loadScene(*document, diags, job.overrides) : std::nullopt;
        if (!base) return outcome;
        outcome.film = job.output.empty() ? fs::path("out") / (job.scenePath.stem().string() + ".mp4") : job.output;
        outcome.sidecar = fs::path(outcome.film).replace_extension(".json");
        if (!filmCanBeMade(job, *base, outcome.film, outcome, diags)) return outcome;
        film::FilmRecord record = filmRecordOf(job, *base, outcome.film);
        OutputSet outputs;
        outputs.add(record.film, record.filmGiven ? "-o" : "the film");
        outputs.add(record.sidecar, "the sidecar", true);
        outputs.addInput(job.scenePath, "the scene file");
        outputs.addInput(base->scene.samples.path, "samples.path");

        createParentFolder(outcome.film);
        const fs::path parent = outcome.film.has_parent_path() ? outcome.film.parent_path() : fs::path(".");
        PrivateFolder building(parent, "film");
        const auto lock = plan::PlanLock::take(building.path());  // held while the film is made; it moves with the folder
        FilmWork work;
        work.dir = building.path();
        const bool planned = planFilm({job, *document}, *base, record, work, diags, progress);
        outcome.frames = record.frames;
        if (!planned) return outcome;
        // --frames' PNGs are declared once it is known which frames are kept.
        if (!record.framesDir.empty())
            for (const auto& f : record.frames)
                if (f.fileNumber) outputs.add(record.framesDir / film::frameFileName(f.fileNumber), "--frames");
        outcome.terrains = record.terrains;
        record.compileSeconds = outcome.compileSeconds = secondsSince(t0);
        film::writeFilmRecord(record, work.dir);
        const fs::path asked = parent / (outcome.film.stem().string() + ".film");
        const auto named = nameWorkingFolder(work.dir, asked, kFilmFolder, diags);
        if (!named) return outcome;
        work.dir = *named;
        for (auto& p : work.plans) p.dir = work.dir / p.dir.filename();
        makeFilm(record, work, job.execution, outputs, outcome, diags, progress);
    } catch (const std::runtime_error& e) {
        reportFilmFailure(e, outcome, diags);
    }
    return outcome;
}

AnimateOutcome resumeFilm(const fs::path& workDir, const execute::Options& execution, const fs::path& framesDir,
                          Diagnostics& diags, const ProgressFn& progress) {
    AnimateOutcome outcome;
    try {
        auto record = film::readFilmRecord(workDir, diags);
        if (!record) return outcome;
        if (record->framesKept && framesDir.empty()) {
            diags.error({(workDir / "film.json").string(), 0, 0},
                        "the film's first run kept its frames (--frames), and its record names no folder outside its "
                        "own: give --frames DIR again to say where they go");
            return outcome;
        }
        record->framesDir = framesDir.empty() ? fs::path() : fs::absolute(framesDir);
        const auto lock = plan::PlanLock::take(workDir, diags);
        if (!lock) return outcome;
        outcome.film = record->film;
        outcome.sidecar = record->sidecar;
        outcome.frames = record->frames;
        outcome.terrains = record->terrains;
        outcome.compileSeconds = record->compileSeconds;
        FilmWork work;
        work.dir = fs::absolute(workDir);
        work.resumed = true;
        for (size_t i = 0; i < record->frames.size(); ++i) {
            if (!record->frames[i].fileNumber) continue;
            const fs::path planDir = work.dir / film::framePlanName(record->frames[i].settings.number);
            makeOwnFolder(planDir);  // a link planted in its place would send the frame's tiles elsewhere
            auto plan = plan::readPlan(planDir, diags);
            if (!plan) return outcome;
            work.plans.push_back(std::move(*plan));
            work.planFrame.push_back(i);
        }
        OutputSet outputs;
        declareFilmOutputs(*record, outputs);
        makeFilm(*record, work, execution, outputs, outcome, diags, progress);
    } catch (const std::runtime_error& e) {
        reportFilmFailure(e, outcome, diags);
    }
    return outcome;
}

}  // namespace relief
