#pragma once
// The stages composed:
//
//   scene file --scene::readScene--> SceneSpec (one spec per stage)
//     SchemeSpec      --subdiv::resolveScheme--> ResolvedScheme   (loadScene)
//     SamplesSpec, FrameSpec, NetSpec, limits --geo::controlNet--> ControlNet (a GeoGrid)
//     ControlNet, depth --subdiv::refineGrid--> refined GeoGrid    (buildSurface)
//     GeoGrid, LookSpec, GeometrySpec --emit::buildMesh or quantizeHeights--> Mesh or HeightField --emit::writeScene--> .pov
//     .pov, RenderSpec --render::renderPov--> PNG                  (runSceneJob)
//
// Each stage is a free function in its own folder that takes its spec and
// returns a plain value. This header declares what composes them: loadScene
// and buildSurface (pipeline.cpp: the scene and its samples to a refined
// surface), compileScene (compile.cpp: the surface to a render plan's .pov),
// the job (job.cpp: compile, render the tiles, finish) and the sidecar
// (sidecar.cpp).
#include <array>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <string_view>
#include <vector>
#include <optional>
#include <string>

#include "annotate/overlay.h"
#include "core/diagnostics.h"
#include "core/output_set.h"
#include "core/png_file.h"
#include "execute/execute.h"
#include "plan/plan.h"
#include "emit/geometry_kind.h"
#include "emit/surface_contours.h"
#include "emit/write_scene.h"
#include "geo/normalize.h"
#include "geo/sun_position.h"
#include "fit/fit_net.h"
#include "fit/prefilter.h"
#include "measure/auto_depth.h"
#include "measure/peak_loss.h"
#include "render/povray.h"

#include <nlohmann/json.hpp>
#include "scene/scene_spec.h"
#include "subdiv/budget.h"
#include "subdiv/resolve.h"

namespace relief {

/// Stage 1 and the scheme: everything the scene file says, checked.
struct LoadedScene {
    scene::SceneSpec scene;
    subdiv::ResolvedScheme resolved;
    double seconds = 0;
};

/// Reads and validates the scene file and resolves its scheme, reporting every
/// problem at once. Nothing is written.
std::optional<LoadedScene> loadScene(const std::filesystem::path& scenePath, Diagnostics& diags,
                                     const scene::SceneOverrides& overrides = {});

/// "depth 3" or "depth auto (tolerance_m = 5)".
std::string depthLabel(const scene::SubdivisionSpec& subdivision);

/// For depth = "auto": "depth 4 chosen: level 1 moved the terrain 220 m, ..., 4: 4.1 m <= 5 m".
std::string autoDepthSummary(const measure::DepthChoice& choice, double toleranceM);

/// The output budget of a scene's [limits].
subdiv::Budget budgetOf(const scene::LimitsSpec& limits);

/// Where an error of the output budget belongs: subdivision.depth = "auto",
/// the scheme (a depth the scene gives), else the key that sized the net (or
/// the samples file, when relief chose both the net and the depth).
SourceLoc budgetKey(const scene::SceneSpec& spec);

/// The most nodes the control net may have under a scene's [limits].
geo::NetBudget netBudgetOf(const scene::LimitsSpec& limits);

/// What a job is doing, for the command line to show.
struct ProgressEvent {
    enum class Stage { Reading, Compiling, Rendering, Tiles, Finishing } stage = Stage::Reading;
    std::string text;  ///< e.g. "reading scenes/default.toml", "gridding 458845 samples",
                       ///< POV-Ray's "Rendered 5120 of 480000 pixels (1%)"
    int percent = -1;  ///< of the task `text` names, 0..100; -1 when it has none
};
using ProgressFn = std::function<void(const ProgressEvent&)>;

/// Stages 2 and 3: the control net and the refined surface (metres, in the
/// net's frame), refused with a diagnostic when over the output budget. Used
/// by compileScene and by measurements such as profiles.
struct Surface {
    geo::ControlNet net;
    geo::GeoGrid refined;  ///< the net refined `depth` times: same frame and extent
    subdiv::OutputEstimate estimate;  ///< of the chosen geometry
    emit::GeometryChoice geometry;
    int depth = 0;            ///< the scene's, the one depth = "auto" chose, or the still's
    std::string depthReason;  ///< "subdivision.depth", the auto summary, or how the still chose it
    std::optional<measure::DepthChoice> autoDepth;  ///< the change per level, for depth = "auto"
    double normalizeSeconds = 0, subdivideSeconds = 0;  ///< subdivide includes choosing the depth
    std::optional<fit::FitReport> fit;              ///< net.gridding = "fit"
    std::optional<fit::PrefilterReport> prefilter;  ///< net.fit = true
    Vec3 dataPeak;                                  ///< the highest sample (or node) the data have
    measure::PeakLoss peakLoss;                     ///< of the refined surface against dataPeak
};
/// What buildSurface will make, without refining: the net, the depth and why,
/// the geometry and its cost, checked against [limits] (a net whose work is
/// over them is refused before its heights are read). What `relief info`
/// and `relief init` show; `refined` is empty.
///
/// The depth, when the scene gives none, is chosen for the still: the
/// shallowest whose refined spacing is within sqrt(arity) of one pixel where
/// the terrain is nearest the camera, lowered until [limits] allow it.
std::optional<Surface> planSurface(const LoadedScene& loaded, Diagnostics& diags, int threads = 0,
                                   const ProgressFn& progress = {});
/// `progress` (may be empty) hears how far the gridding is.
std::optional<Surface> buildSurface(const LoadedScene& loaded, Diagnostics& diags, int threads = 0,
                                    const ProgressFn& progress = {});

struct CompileOptions {
    std::filesystem::path povPath;       ///< the .pov's final name (its PNGs are named after it)
    /// Where to write a file compiling makes, given its final name and role
    /// ("the .pov", "the height field's PNG", "--dump-net"): a path in the
    /// run's output set, or in a render plan's folder.
    std::function<std::filesystem::path(const std::filesystem::path& finalPath, std::string_view role)> writeAt;
    std::filesystem::path templatesDir;
    std::filesystem::path dumpNetPath;   ///< optional: .csv (x,y,z) or .asc (ESRI ASCII grid)
    std::filesystem::path dumpSurfacePath;  ///< optional: the refined surface, .csv or .asc
    int threads = 0;                     ///< refiner threads; 0 = all cores
    ProgressFn progress;                 ///< may be empty
};

struct StageTimes {
    double readScene = 0, normalize = 0, subdivide = 0, emit = 0;  ///< seconds
};

struct CompileResult {
    scene::SceneSpec scene;
    std::string schemeFamily;
    std::string certified;  ///< e.g. "C1 (Hölder ~1.68)"
    geo::ControlNet net;    ///< the control net (its grid is kept; it is small)
    subdiv::OutputEstimate estimate;  ///< the refined grid's size and its mesh's
    int depth = 0;                    ///< the scene's, the one depth = "auto" chose, or the still's
    std::string depthReason;          ///< Surface::depthReason
    std::optional<measure::DepthChoice> autoDepth;
    int arity = 2;
    double holder = 0;  ///< the scheme's Hölder estimate, next to the observed rates
    double metresPerUnit = 1;
    emit::ParameterList parameters;  ///< as recorded in the .pov header
    StageTimes times;
    std::uintmax_t povBytes = 0;
    emit::GeometryChoice geometry;
    std::filesystem::path heightPng, drapePng;      ///< the height field's PNGs, beside the .pov
    double heightStepM = 0;                         ///< its vertical quantization
    double adaptiveToleranceM = 0, adaptiveTolerancePx = 0;  ///< the adaptive mesh's bound
    long long meshVertices = 0, meshTriangles = 0;  ///< as emitted: masked nodes left out
    size_t maskedNodes = 0;                         ///< refined nodes without data
    /// Where the light comes from, as the sidecar's "sun" says it: a true
    /// bearing and the apparent altitude, computed from [lighting] datetime
    /// over the terrain's centre or taken from the scene's angles.
    struct Sun {
        double azimuthDeg = 0, altitudeDeg = 0;
        bool fromDatetime = false;
        std::string datetime;          ///< as written in the scene
        double lonDeg = 0, latDeg = 0; ///< where it was computed (fromDatetime)
    } sun;
    emit::SurfaceContours contours;             ///< [overlay] contours as drawn
    std::optional<fit::FitReport> fit;              ///< net.gridding = "fit": what the fit did
    std::optional<fit::PrefilterReport> prefilter;  ///< net.fit = true
    measure::PeakLoss peakLoss;                     ///< the data's peak against the surface's
    nlohmann::ordered_json layers = nlohmann::ordered_json::array();  ///< what each [[layer]] became (sidecar)
    std::optional<double> drapeImageCoverage;  ///< [texture] image: the share of the surface's nodes it covers
    std::string dataAttribution;   ///< the samples' credit: the scene's, else the raster's metadata's
    std::string imageAttribution;  ///< [texture] image's credit: the scene's, else the image's metadata's
    std::optional<double> baseFloorM;   ///< the block model's floor elevation; unset: no block
    std::array<double, 2> zRangeM{};    ///< the surface's lowest and highest elevation (nodes with data)
    annotate::OverlayFacts overlayFacts;            ///< what the still's overlays say
    /// The camera both ways: the eye and the point looked at as [lon, lat,
    /// height_m], and as an orbit around the point (azimuth, elevation, distance).
    GeoPoint cameraEye, cameraTarget;
    double cameraAzimuthDeg = 0, cameraElevationDeg = 0, cameraDistanceM = 0;
};

/// Runs stages 2-4 and writes the .pov, the files it reads (and the net
/// dump, if asked) where `options.writeAt` says: the surface, the view
/// (placement, camera and sun, once), the terrain's geometry, the contours,
/// the overlays' facts, the .pov. Nothing is written when a stage fails.
std::optional<CompileResult> compileScene(const LoadedScene& loaded,
                                          const CompileOptions& options, Diagnostics& diags);

/// The terrain compiled once for many views (a film's frames): the surface,
/// its geometry and contours written as SDL files (terrain.inc, base.inc,
/// contours.inc beside the .pov)
/// that each view's .pov includes, and the PNGs they read, all through
/// `options.writeAt`. The geometry's choices that depend on the camera (the
/// depth for the still, the adaptive mesh's tolerance, the contours' width)
/// are made for the scene's own [camera].
class SharedTerrain {
public:
    struct State;
    explicit SharedTerrain(std::unique_ptr<State> state);
    SharedTerrain(SharedTerrain&&) noexcept;
    ~SharedTerrain();
    const geo::ControlNet& net() const;
    /// The net refined to the depth rendered: the surface the frames show.
    const geo::GeoGrid& refined() const;
    int depth() const;  ///< the subdivision depth refined() has

private:
    std::unique_ptr<State> state_;
    friend std::optional<CompileResult> compileView(const LoadedScene&, const SharedTerrain&, const CompileOptions&,
                                                    Diagnostics&);
};
std::optional<SharedTerrain> compileSharedTerrain(const LoadedScene& loaded, const CompileOptions& options,
                                                  Diagnostics& diags);
/// One view of a shared terrain: `frame` is the terrain's scene with other
/// keys of [camera], [lighting], [overlay] and [atmosphere]; its .pov is
/// written at options.writeAt(options.povPath, "the .pov").
std::optional<CompileResult> compileView(const LoadedScene& frame, const SharedTerrain& terrain,
                                         const CompileOptions& options, Diagnostics& diags);

/// The sun over the terrain's centre at an instant, and that centre; nullopt
/// when the centre has no longitude and latitude in the net's frame.
std::optional<std::pair<geo::SunPosition, GeoPoint>> sunOverTerrain(const geo::ControlNet& net,
                                                                    std::int64_t utcSeconds);

/// Output paths derived from a scene: the .pov and the .json sidecar sit
/// beside the still (or stand in for it when only compiling).
struct OutputPaths {
    std::filesystem::path still, pov, sidecar;  ///< still: .png, .pdf or .svg
};
OutputPaths outputPathsFor(const std::filesystem::path& still);

/// One scene file to a .pov and its sidecar, or all the way to a PNG: what
/// `relief compile`, `relief render`, `relief test` and `relief sweep` do.
struct SceneJob {
    enum class Until { Pov, Png };
    Until until = Until::Png;
    std::filesystem::path scenePath;
    scene::SceneOverrides overrides;
    /// The PNG (Until::Png) or the .pov (Until::Pov) to write; "" = the
    /// scene's [render] output, else out/<scene>.png (a .pov: out/<scene>.pov).
    std::filesystem::path output;
    std::filesystem::path templatesDir;
    std::filesystem::path dumpNetPath;
    std::filesystem::path dumpSurfacePath;  ///< the refined surface rendered (--dump-surface)
    int threads = 0;            ///< refiner threads; 0 = all cores
    bool stillOnly = false;     ///< keep the PNG alone (relief test): no .pov, PNGs or sidecar beside it
    /// Where the outputs are declared and staged. Null: a set of the job's
    /// own, committed when the job succeeds. Given (relief sweep): the caller
    /// commits it with its own outputs, so that the whole sweep appears at once.
    OutputSet* outputs = nullptr;
    // Until::Png: the render plan and how its tiles are rendered.
    int tiles = 1;                          ///< strips of the still, each rendered on its own
    std::filesystem::path planDir;          ///< "" = <still>.plan beside the still
    bool keepPlan = false;                  ///< leave the plan after a render that succeeded
    execute::Options execution;             ///< here or on Slurm, how many at once, POV-Ray sandboxed or not
};

enum class JobStatus { Ok, BadInput, ToolFailed, Cancelled };

struct JobOutcome {
    JobStatus status = JobStatus::BadInput;
    OutputPaths paths;
    std::optional<CompileResult> compiled;
    render::RenderResult render;     ///< POV-Ray's timings (summed over the tiles) and error text (Until::Png)
    std::optional<annotate::OverlayRecord> overlays;  ///< what was drawn over the still
    std::filesystem::path plan;      ///< a render's plan, kept when the render did not finish (--resume)
    int tiles = 0;                   ///< the tiles rendered by this run
};

/// Loads, compiles and (Until::Png) renders; writes the .pov, the JSON sidecar
/// and the PNG as one set (core/output_set.h: nothing when a stage fails),
/// creating the output folders. Diagnostics go to `diags` (an output that
/// cannot be written too), progress to `progress` (may be empty). A render
/// compiles into a plan (planJob), renders its tiles (execute::run) and
/// finishes it (finishJob).
JobOutcome runSceneJob(const SceneJob& job, Diagnostics& diags, const ProgressFn& progress);

/// A job compiled into its render plan, not yet rendered.
struct PlannedJob {
    SceneJob job;
    JobOutcome outcome;                 ///< status Ok when planned; paths, compiled
    std::optional<plan::RenderPlan> plan;
    std::unique_ptr<OutputSet> ownOutputs;  ///< job.outputs, unless the caller gave a set
    std::optional<plan::PlanLock> lock;     ///< the plan is this job's while it renders
    OutputSet& outputs() { return job.outputs ? *job.outputs : *ownOutputs; }
};

/// Loads the scene, declares the outputs, compiles into the plan's folder
/// (made whole, then named; a stale plan there is replaced) and writes its
/// plan.json. outcome.status says how it went.
PlannedJob planJob(const SceneJob& job, Diagnostics& diags, const ProgressFn& progress);

/// A working folder kept beside an output until the output is made: a render
/// plan, a film's frames. Which folders of that name a run may replace.
struct WorkingFolderKind {
    std::string_view what;   ///< "the render plan"
    std::string_view aKind;  ///< "a render plan"
    std::string_view fix;    ///< "give --plan"
    bool (*ours)(const std::filesystem::path& dir);  ///< a whole folder of this kind, relief's
};

/// Names `building` (made whole in a private folder) `asked`, or the next
/// free `asked`-N while a running relief holds that one; a folder of the kind
/// a run left (nobody's now) is replaced, anything else there is in the way.
/// The absolute name, or nullopt with the error at the name.
std::optional<std::filesystem::path> nameWorkingFolder(const std::filesystem::path& building,
                                                       const std::filesystem::path& asked,
                                                       const WorkingFolderKind& kind, Diagnostics& diags);

/// The render plan's fields for a compiled scene: the still's size and
/// POV-Ray's options, where the still and sidecar go, the overlays and their
/// facts, the sidecar so far (compiling into plan.dir adds its files).
void describeRender(plan::RenderPlan& plan, const CompileResult& compiled, const OutputPaths& paths, int tiles);

/// The plan's tiles stitched into the still's pixels, no overlays; nullopt with the reason.
std::optional<PngImage8> stitchedStill(const plan::RenderPlan& plan, Diagnostics& diags);

/// The still of a plan whose tiles are rendered: the tiles stitched, the
/// overlays drawn (`overlays` says what they show); nullopt with the reason.
std::optional<PngImage8> stillOfPlan(const plan::RenderPlan& plan, std::optional<annotate::OverlayRecord>& overlays,
                                     Diagnostics& diags);

/// The plan's tiles still to render, as tasks for execute::run.
std::vector<execute::Task> tasksOf(const plan::RenderPlan& plan);

/// A plan whose tiles are rendered, finished: the tiles stitched, the
/// overlays drawn, the still, the .pov, its PNGs and the sidecar (with every
/// tile's record) written into `outputs`; `commit`: and moved into place, the
/// plan removed (unless `keepPlan`). False with the reason in `diags`.
bool finishPlan(const plan::RenderPlan& plan, OutputSet& outputs, bool stillOnly, bool commit, bool keepPlan,
                JobOutcome& outcome, Diagnostics& diags);

/// `relief render --resume PLAN`: the plan's missing tiles rendered, then finished.
JobOutcome resumePlan(const std::filesystem::path& planDir, const execute::Options& execution, bool keepPlan,
                      Diagnostics& diags, const ProgressFn& progress);

/// The JSON sidecar: inputs, parameters, net size, vertex and triangle
/// counts, time per stage, what the compile made; finishPlan adds the
/// render's (POV-Ray's seconds, every tile's record, what the overlays show).
/// Every string UTF-8: a name that is not is written with U+FFFD.
nlohmann::ordered_json sidecarJson(const CompileResult& compiled, const OutputPaths& paths);

/// Warns (once a run) when the sidecar of `compiled`, its .pov at `pov`,
/// will write a name or text with U+FFFD (not UTF-8), naming the first.
void warnIfSidecarNotUtf8(const CompileResult& compiled, const std::filesystem::path& pov, Diagnostics& diags);

/// The sidecar's text: the JSON, indented, a line feed at the end.
std::string sidecarText(const nlohmann::ordered_json& sidecar);

}  // namespace relief
