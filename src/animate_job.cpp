// relief animate: the frames' scenes loaded, the terrain compiled once for
// the frames it serves, a render plan a frame, the tiles rendered (one frame
// first, to tell how long the rest will take), the frames finished as
// stills, the film encoded, all written as one set.
#include "animate_job.h"

#include <chrono>
#include <map>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "animate_flyover.h"
#include "core/atomic_file.h"
#include "core/text_escape.h"
#include "relief/version.h"

namespace relief {

namespace fs = std::filesystem;

namespace {

using Clock = std::chrono::steady_clock;
double secondsSince(Clock::time_point t0) {
    return std::chrono::duration<double>(Clock::now() - t0).count();
}

// "camera.azimuth_deg=90 lighting.datetime=..." : a frame's keys as --set takes them.
std::string setsText(const scene::SceneOverrides& overrides) {
    std::string text;
    for (const auto& [k, v] : overrides) text += (text.empty() ? "" : " ") + k + "=" + v;
    return text;
}

// A frame's scene: the file with the frame's keys set. A key that makes the
// scene wrong is reported at `key`, the [animation] key that set it.
std::optional<LoadedScene> loadFrame(const AnimateJob& job, const scene::AnimationSpec& a, const FilmFrame& f,
                                     const char* key, Diagnostics& diags) {
    scene::SceneOverrides overrides = job.overrides;
    overrides.insert(overrides.end(), f.settings.overrides.begin(), f.settings.overrides.end());
    Diagnostics own;  // the file's warnings were told once, with the scene
    auto loaded = loadScene(job.scenePath, own, overrides);
    if (loaded && own.errorCount() == 0) return loaded;
    const auto first = std::find_if(own.all().begin(), own.all().end(),
                                    [](const Diagnostic& d) { return d.severity == Severity::Error; });
    diags.error(a.locs.at(key), fmt::format("frame {} sets {}: {}", f.settings.number,
                                            terminalText(setsText(f.settings.overrides), 500),
                                            first != own.all().end() ? first->message : "the scene is not valid"));
    return std::nullopt;
}

std::optional<std::vector<LoadedScene>> loadFrames(const AnimateJob& job, const LoadedScene& base,
                                                   const std::vector<FilmFrame>& frames, Diagnostics& diags) {
    std::vector<LoadedScene> scenes;
    for (const auto& f : frames) {
        const scene::AnimationSpec& a = base.scene.animation;
        auto loaded = loadFrame(job, a, f, !a.vary.empty() ? "animation.vary" : "animation", diags);
        if (!loaded) return std::nullopt;
        scenes.push_back(std::move(*loaded));
    }
    return scenes;
}

// The keys the compiled terrain gives the group's frames: the depth, when it
// was chosen for the scene's own view (a frame's own camera would choose
// another, and relief render of the frame's keys must make this terrain);
// and for a flyover each frame's camera over the surface. The frames' scenes
// are loaded again with them.
bool addTerrainKeys(const AnimateJob& job, const SharedTerrain& terrain, const std::vector<size_t>& group,
                    std::vector<LoadedScene>& scenes, std::vector<FilmFrame>& frames, Diagnostics& diags) {
    const scene::SceneSpec& spec = scenes[group.front()].scene;
    const scene::AnimationSpec& a = spec.animation;
    const bool chosenDepth = !spec.subdivision.depthGiven && !spec.subdivision.depthAuto;
    if (!chosenDepth && a.path != scene::CameraPath::Flyover) return true;
    std::vector<scene::SceneOverrides> cameras(group.size());
    if (a.path == scene::CameraPath::Flyover) {
        auto keys = flyoverKeys(a, terrain.refined(), group, diags);
        if (!keys) return false;
        cameras = std::move(*keys);
    }
    for (size_t g = 0; g < group.size(); ++g) {
        const size_t i = group[g];
        auto& overrides = frames[i].settings.overrides;
        if (chosenDepth) overrides.emplace_back("subdivision.depth", std::to_string(terrain.depth()));
        overrides.insert(overrides.end(), cameras[g].begin(), cameras[g].end());
        const char* key = a.path == scene::CameraPath::Flyover ? "animation.path" : "animation";
        auto loaded = loadFrame(job, a, frames[i], key, diags);
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
};

// A compiled terrain's files, hard-linked into a frame's plan (no copy of a 100 MB mesh).
void linkShared(const std::vector<plan::PlanFile>& shared, const fs::path& sharedDir, plan::RenderPlan& plan) {
    for (const auto& f : shared) {
        std::error_code ec;
        fs::create_hard_link(sharedDir / f.name, plan.dir / f.name, ec);
        if (ec) fs::copy_file(sharedDir / f.name, plan.dir / f.name, ec);
        if (ec) throw OutputError(shownPath(plan.dir / f.name), "cannot be written: " + ec.message());
        plan.reads.push_back(f);
    }
}

// One frame's plan: its .pov (the frame's camera, sun and overlays around the shared terrain).
bool planFrame(const AnimateJob& job, const LoadedScene& scene, const SharedTerrain& terrain,
               const std::vector<plan::PlanFile>& shared, const fs::path& sharedDir, const FilmFrame& frame,
               FilmWork& work, Diagnostics& diags) {
    plan::RenderPlan plan;
    plan.dir = work.dir / fmt::format("frame-{:05}.plan", frame.settings.number);
    fs::create_directories(plan.dir);
    linkShared(shared, sharedDir, plan);
    CompileOptions options;
    options.povPath = plan.dir / "frame.pov";
    options.templatesDir = job.templatesDir;
    options.writeAt = [&](const fs::path& final, std::string_view role) {
        plan.pov = {final.filename().string(), final, std::string(role)};
        return final;
    };
    const auto compiled = compileView(scene, terrain, options, diags);
    if (!compiled) return false;
    OutputPaths paths;
    paths.png = plan.dir / "frame.png";  // a label only: finishFrames names the frames kept
    paths.pov = options.povPath;
    paths.sidecar = plan.dir / "frame.json";
    describeRender(plan, *compiled, paths, job.tiles, job.sandbox, job.templatesDir);
    if (!writePlan(plan, diags)) return false;
    work.plans.push_back(std::move(plan));
    return true;
}

// Every frame of one terrain: the terrain compiled (its files in shared-N/), the nights told, a plan a frame.
bool planGroup(const AnimateJob& job, std::vector<LoadedScene>& scenes, const std::vector<size_t>& group,
               int groupIndex, std::vector<FilmFrame>& frames, FilmWork& work, Diagnostics& diags,
               const ProgressFn& progress) {
    const fs::path sharedDir = work.dir / fmt::format("terrain-{}", groupIndex + 1);
    fs::create_directories(sharedDir);
    std::vector<plan::PlanFile> shared;
    CompileOptions options;
    options.povPath = sharedDir / "frame.pov";
    options.templatesDir = job.templatesDir;
    options.threads = job.threads;
    options.progress = progress;
    options.writeAt = [&](const fs::path& final, std::string_view role) {
        shared.push_back({final.filename().string(), final, std::string(role)});
        return sharedDir / final.filename();
    };
    // The terrain does not depend on the sun: compiled with the scene's angles, so that a first
    // frame at night is told by checkNights (naming the frame), not by the still's own check.
    LoadedScene terrainScene = scenes[group.front()];
    terrainScene.scene.look.lighting.sunTime.reset();
    const auto terrain = compileSharedTerrain(terrainScene, options, diags);
    if (!terrain || !checkNights(scenes.front().scene.animation, terrain->net(), group, frames, diags) ||
        !addTerrainKeys(job, *terrain, group, scenes, frames, diags))
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

// The tiles of `plans`, rendered; the outcome says why not.
bool renderPlans(const std::vector<plan::RenderPlan>& plans, size_t from, size_t to, const AnimateJob& job,
                 AnimateOutcome& outcome, Diagnostics& diags, const ProgressFn& progress) {
    std::vector<execute::Task> tasks;
    for (size_t i = from; i < to; ++i)
        for (const auto& t : tasksOf(plans[i])) tasks.push_back(t);
    execute::Options options = job.execution;
    if (options.jobDir.empty()) options.jobDir = plans[from].dir.parent_path() / "slurm";
    const size_t perFrame = std::max<size_t>(1, tasks.size() / std::max<size_t>(1, to - from));
    const execute::Result r = execute::run(tasks, options, [&](const execute::Progress& p) {
        if (!progress) return;
        const size_t done = from + p.done / perFrame;
        const std::string left =
            p.done > 0 && p.done < p.total
                ? fmt::format(", about {:.0f} s left", p.seconds / double(p.done) * double(p.total - p.done))
                : "";
        progress({ProgressEvent::Stage::Tiles,
                  fmt::format("frames: {} of {} rendered, {:.0f} s{}", done, plans.size(), p.seconds, left),
                  static_cast<int>(100 * done / std::max<size_t>(1, plans.size()))});
    });
    if (r.ok) return true;
    outcome.status = r.cancelled ? JobStatus::Cancelled : r.badInput ? JobStatus::BadInput : JobStatus::ToolFailed;
    outcome.toolError = r.error;
    if (r.badInput) diags.error(r.at, r.error);
    return false;
}

// The film's sidecar: what it was made from, every frame's keys (relief render --set of them makes that frame).
std::string filmSidecar(const AnimateJob& job, const LoadedScene& base, const AnimateOutcome& o,
                        const film::VideoRequest& video) {
    nlohmann::ordered_json frames = nlohmann::ordered_json::array();
    for (const auto& f : o.frames) {
        nlohmann::ordered_json set = nlohmann::ordered_json::object();
        for (const auto& [k, v] : f.settings.overrides) set[k] = v;
        nlohmann::ordered_json j = {{"number", f.settings.number}, {"set", set}};
        if (f.settings.sunTime) j["sun_altitude_deg"] = std::round(f.sunAltitudeDeg * 1e4) / 1e4;
        if (f.fileNumber)
            j["file"] = film::frameFileName(f.fileNumber);
        else
            j["left_out"] = "night";
        frames.push_back(j);
    }
    // The command as run, with the working folder's frames and the staged film named as kept.
    film::VideoRequest shown = video;
    shown.frames = job.framesDir.empty() ? fs::path("frames") : job.framesDir;
    shown.output = o.film.filename();
    const std::vector<std::string> command = film::ffmpegCommand(shown);
    nlohmann::ordered_json j = {
        {"relief_version", kVersion},
        {"scene", job.scenePath.string()},
        {"scene_sha1", base.scene.sceneSha1},
        {"film", o.film.filename().string()},
        {"fps", base.scene.animation.fps},
        {"frames_in_film", video.frameCount},
        {"terrains_compiled", o.terrains},
        {"frames", frames},
        {"ffmpeg", {{"version", film::ffmpegVersion()}, {"command", command}}},
        {"seconds",
         {{"compile", o.compileSeconds},
          {"first_frame", o.probeSeconds},
          {"render", o.renderSeconds},
          {"encode", o.encodeSeconds}}},
    };
    return j.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n";
}

}  // namespace

namespace {

// The frames' stills, written into work/frames/ (what ffmpeg reads) and, for --frames, into the set.
bool finishFrames(const AnimateJob& job, const FilmWork& work, const std::vector<FilmFrame>& frames, OutputSet& outputs,
                  Diagnostics& diags) {
    fs::create_directories(work.dir / "frames");
    for (size_t p = 0; p < work.plans.size(); ++p) {
        std::optional<annotate::OverlayRecord> overlays;
        const auto still = stillOfPlan(work.plans[p], overlays, diags);
        if (!still) return false;
        const std::string name = film::frameFileName(frames[work.planFrame[p]].fileNumber);
        const fs::path png = work.dir / "frames" / name;
        writePngAtomically(png, {still->width, still->height, still->channels, false, still->pixels.data()});
        if (job.framesDir.empty()) continue;
        const fs::path kept = outputs.add(job.framesDir / name, "--frames");
        std::error_code ec;
        fs::create_hard_link(png, kept, ec);
        if (ec) fs::copy_file(png, kept, ec);
        if (ec) throw OutputError(shownPath(job.framesDir / name), "cannot be written: " + ec.message());
    }
    return true;
}

// Compiling: the frames' scenes, a terrain for each group of them, a plan a frame.
bool planFilm(const AnimateJob& job, const LoadedScene& base, AnimateOutcome& outcome, FilmWork& work,
              Diagnostics& diags, const ProgressFn& progress) {
    auto scenes = loadFrames(job, base, outcome.frames, diags);
    if (!scenes) return false;
    const auto groups = terrainGroups(outcome.frames);
    outcome.terrains = static_cast<int>(groups.size());
    // Nights are known per terrain; a frame's number among those kept once all are.
    for (size_t g = 0; g < groups.size(); ++g) {
        if (progress)
            progress({ProgressEvent::Stage::Compiling,
                      fmt::format("compiling the terrain{} for {} frame{}",
                                  groups.size() > 1 ? fmt::format(" {} of {}", g + 1, groups.size()) : "",
                                  groups[g].size(), groups[g].size() == 1 ? "" : "s"),
                      -1});
        if (!planGroup(job, *scenes, groups[g], static_cast<int>(g), outcome.frames, work, diags, progress))
            return false;
    }
    numberKeptFrames(outcome.frames);
    if (work.plans.empty()) {
        diags.error(base.scene.animation.locs.at("animation.sun"),
                    "animation.sun: the sun is below the horizon over the terrain's centre at every frame: choose a "
                    "window in daylight");
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
        const auto base = loadScene(job.scenePath, diags, job.overrides);
        if (!base) return outcome;
        const scene::AnimationSpec& a = base->scene.animation;
        if (!a.present) {
            diags.error({job.scenePath.string(), 0, 0},
                        "the scene has no [animation] section: add one, e.g. [animation] frames = 120 and path = "
                        "\"orbit\" (docs/animation.md)");
            return outcome;
        }
        // A frame's camera.position is the flyover's; the scene's own would be overridden unseen.
        if (a.path == scene::CameraPath::Flyover && base->scene.look.camera.position) {
            diags.error(a.locs.at("animation.path"),
                        "animation.path = \"flyover\" moves the eye along the path, but camera.position places "
                        "it: remove camera.position (and camera.look_at; animation.look_at fixes where the camera "
                        "looks)");
            return outcome;
        }
        outcome.film = job.output.empty() ? fs::path("out") / (job.scenePath.stem().string() + ".mp4") : job.output;
        film::VideoRequest video;
        if (!film::videoFormatOf(outcome.film, video.format)) {
            diags.error({outcome.film.string(), 0, 0},
                        "a film is written as .mp4 (H.264), .webm (VP9) or .gif: give "
                        "-o one of them");
            return outcome;
        }
        if (render::findOnPath("ffmpeg").empty()) {
            outcome.status = JobStatus::ToolFailed;
            outcome.toolError = "ffmpeg is not installed, and it encodes the film (Debian: apt-get install ffmpeg)";
            return outcome;
        }
        outcome.sidecar = fs::path(outcome.film).replace_extension(".json");
        OutputSet outputs;
        outputs.add(outcome.film, job.output.empty() ? "the film" : "-o");
        outputs.add(outcome.sidecar, "the sidecar", true);
        outputs.addInput(job.scenePath, "the scene file");
        outputs.addInput(base->scene.samples.path, "samples.path");
        for (auto& settings : film::frameSettings(base->scene)) outcome.frames.push_back({std::move(settings)});

        createParentFolder(outcome.film);
        PrivateFolder workDir(outcome.film.has_parent_path() ? outcome.film.parent_path() : fs::path("."), "film");
        FilmWork work;
        work.dir = workDir.path();
        if (!planFilm(job, *base, outcome, work, diags, progress)) return outcome;
        outcome.compileSeconds = secondsSince(t0);

        // One frame first: how long it took tells how long the rest will.
        const auto r0 = Clock::now();
        if (!renderPlans(work.plans, 0, 1, job, outcome, diags, progress)) return outcome;
        outcome.probeSeconds = secondsSince(r0);
        if (progress && work.plans.size() > 1)
            progress({ProgressEvent::Stage::Rendering,
                      fmt::format("frame 1 rendered in {:.1f} s: {} frames more, about {:.0f} s of rendering "
                                  "(divided among the processes that run at once)",
                                  outcome.probeSeconds, work.plans.size() - 1,
                                  outcome.probeSeconds * double(work.plans.size() - 1)),
                      -1});
        if (!renderPlans(work.plans, 1, work.plans.size(), job, outcome, diags, progress)) return outcome;
        outcome.renderSeconds = secondsSince(r0);

        if (progress) progress({ProgressEvent::Stage::Finishing, "finishing " + outcome.film.string(), -1});
        if (!finishFrames(job, work, outcome.frames, outputs, diags)) return outcome;
        const auto e0 = Clock::now();
        video.frames = work.dir / "frames";
        video.frameCount = static_cast<int>(work.plans.size());
        video.fps = a.fps;
        video.output = outputs.staged(outcome.film);
        if (const std::string error = film::encodeVideo(video); !error.empty()) {
            outcome.status = JobStatus::ToolFailed;
            outcome.toolError = error;
            return outcome;
        }
        outcome.encodeSeconds = secondsSince(e0);
        writeFileAtomically(outputs.staged(outcome.sidecar), filmSidecar(job, *base, outcome, video));
        outputs.commit();
        outcome.status = JobStatus::Ok;
    } catch (const std::runtime_error& e) {
        if (const auto* out = dynamic_cast<const OutputError*>(&e))
            diags.error(out->at(), out->problem());
        else
            diags.error({}, e.what());
        outcome.status = JobStatus::BadInput;
    }
    return outcome;
}

}  // namespace relief
