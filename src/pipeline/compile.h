#pragma once
// Stage 4 composed: the surface (surface.h) to a render plan's .pov, through
// the view (view.h: placement, camera, sun, made once), the terrain's
// geometry, the marks on it (marks.h), the contours and the overlays' facts;
// or, for a film, a terrain compiled once (SharedTerrain) and a view of it a
// frame.
#include <array>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

#include "annotate/overlay.h"
#include "core/diagnostics.h"
#include "emit/geometry_kind.h"
#include "emit/surface_contours.h"
#include "emit/write_scene.h"
#include "fit/fit_net.h"
#include "fit/prefilter.h"
#include "geo/normalize.h"
#include "measure/peak_loss.h"
#include "pipeline/depth.h"
#include "pipeline/load.h"
#include "pipeline/progress.h"
#include "pipeline/view.h"
#include "subdiv/budget.h"

namespace relief {

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

/// What compiling made, for the record (the .pov's header, the sidecar) and
/// the command line: a summary a stage, no copy of the scene (the record reads
/// it from the LoadedScene) or of the net.
struct NetSummary {
    int rows = 0, cols = 0;
    double dx = 0, dy = 0;           ///< metres
    std::string frame;               ///< the frame, described
    std::string spacingReason;
    size_t sampleCount = 0, filledOutsideHull = 0, filledNodata = 0;
    size_t maskedNodes = 0;          ///< nodes without data
};

/// The surface: the net, the scheme, the depth and why, the refined grid's
/// estimate and geometry, the fit, the peak loss.
struct SurfaceSummary {
    NetSummary net;
    std::string schemeFamily;
    std::string certified;  ///< e.g. "C1 (Hölder ~1.68)"
    int arity = 2;
    double holder = 0;      ///< the scheme's Hölder estimate, next to the observed rates
    int depth = 0;          ///< the scene's, the one depth = "auto" chose, or the still's
    std::string depthReason;
    std::optional<DepthChoice> autoDepth;
    subdiv::OutputEstimate estimate;  ///< the refined grid's size and its mesh's
    emit::GeometryChoice geometry;
    size_t maskedNodes = 0;           ///< refined nodes without data
    std::optional<fit::FitReport> fit;              ///< net.gridding = "fit": what the fit did
    std::optional<fit::PrefilterReport> prefilter;  ///< net.fit = true
    measure::PeakLoss peakLoss;                     ///< the data's peak against the surface's
};

/// The terrain's geometry as written, and what lies on it.
struct TerrainSummary {
    std::filesystem::path heightPng, drapePng;      ///< the height field's PNGs, beside the .pov
    double heightStepM = 0;                         ///< its vertical quantization
    double adaptiveToleranceM = 0, adaptiveTolerancePx = 0;  ///< the adaptive mesh's bound
    long long meshVertices = 0, meshTriangles = 0;  ///< as emitted: masked nodes left out
    emit::SurfaceContours contours;                 ///< [overlay] contours as drawn
    nlohmann::ordered_json layers = nlohmann::ordered_json::array();  ///< what each [[layer]] became
    std::optional<double> drapeImageCoverage;  ///< [texture] image: the share of the surface's nodes it covers
};

/// The view: the sun, the camera both ways, where the terrain sits, what the
/// overlays say.
struct ViewSummary {
    SunFacts sun;
    /// The eye and the point looked at as [lon, lat, height_m], and as an
    /// orbit around the point (azimuth, elevation, distance).
    GeoPoint cameraEye, cameraTarget;
    double cameraAzimuthDeg = 0, cameraElevationDeg = 0, cameraDistanceM = 0;
    double metresPerUnit = 1;
    std::optional<double> baseFloorM;   ///< the block model's floor elevation; unset: no block
    std::array<double, 2> zRangeM{};    ///< the surface's lowest and highest elevation (nodes with data)
    annotate::OverlayFacts overlayFacts;
    int widthPx = 0, heightPx = 0;      ///< the still's
};

/// Whose data and whose image: the scene's credit line, else the one the
/// file's metadata carries (dataCredit, the one rule).
struct Credits {
    std::string data, image;
};

struct CompileResult {
    SurfaceSummary surface;
    TerrainSummary terrain;
    ViewSummary view;
    Credits credits;
    emit::ParameterList parameters;  ///< as recorded in the .pov header
    std::uintmax_t povBytes = 0;
    StageTimes seconds;
};

/// The data's credit: the scene's [samples] attribution, else what the
/// raster's metadata carries (`fromMetadata` says which).
struct DataCredit {
    std::string text;
    bool fromMetadata = false;
};
DataCredit dataCredit(const scene::SamplesSpec& samples, const geo::ControlNet& net);

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
    /// The terrain in the scene: its bounds, in scene units of metresPerUnit.
    const emit::ScenePlacement& placement() const;

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

}  // namespace relief
