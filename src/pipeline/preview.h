#pragma once
// relief preview: what the browser page shows of a scene (the model relief
// export makes, the still's camera, sun, water and frame, all in the model's
// axes), and the [camera] keys of a view chosen there, written into the scene
// file so that relief render makes the still of exactly that view.
#include <filesystem>
#include <optional>
#include <span>
#include <utility>
#include <vector>
#include <string>

#include <nlohmann/json.hpp>

#include "core/diagnostics.h"
#include "core/types.h"
#include "emit/mesh.h"
#include "geo/geo_grid.h"
#include "pipeline/progress.h"
#include "scene/scene_spec.h"

namespace relief {

/// The preview's triangle budget: a model the page loads and draws at once
/// (a .glb of about 12 MB), the adaptive mesh's bound said where it is over.
inline constexpr long long kDefaultPreviewTriangles = 500'000;

struct PreviewJob {
    std::filesystem::path scenePath;  ///< a scene file, or a DEM alone
    scene::SceneOverrides overrides;  ///< --set
    long long maxTriangles = kDefaultPreviewTriangles;
    int threads = 0;
};

/// What the page shows. The model's axes are glTF's: x east, y up, z south,
/// metres from the scene's origin (scene units times where.metresPerUnit),
/// heights exaggerated as the still draws them.
struct PreviewScene {
    std::string glb;       ///< the model, as relief export writes a .glb
    nlohmann::json page;   ///< the still's size, camera, sun, water, the model's facts (see preview.cpp)
    emit::ScenePlacement where;
    geo::Frame frame;
    /// A DEM previewed alone: "Use this view" writes relief init's scene for
    /// it (with the view's camera) to this path; empty for a scene file.
    std::filesystem::path newScenePath;
    std::string newSceneText;  ///< that scene, before the camera keys
};

/// The scene's preview; nullopt after an error, reported in `diags`.
std::optional<PreviewScene> previewScene(const PreviewJob& job, Diagnostics& diags, const ProgressFn& progress = {});

/// A view chosen on the page, in the model's axes: the eye, the point looked
/// at, and the field of view across the still (POV-Ray's angle; three.js's
/// vertical fov is taken to it by the page).
struct PageView {
    Vec3 eye, target;
    double fovDeg = 40;
};

/// The [camera] keys that place the still's camera at `view`: position and
/// look_at as [lon, lat, height] (heights true metres, the exaggeration taken
/// out as the scene puts it back), fov_deg, as TOML values formatted to round
/// trip. nullopt, after an error, where a point has no longitude and latitude
/// in the scene's frame.
struct CameraKeys {
    GeoPoint position, lookAt;
    double fovDeg = 0;
    /// (key, TOML value) in the order a scene writes them.
    std::vector<std::pair<std::string, std::string>> toml() const;
};
std::optional<CameraKeys> cameraKeysOf(const PreviewScene& preview, const PageView& view, Diagnostics& diags);

/// The [camera] keys a view replaces, commented out when it is used: the orbit's.
inline constexpr const char* kOrbitCameraKeys[] = {"azimuth_deg", "elevation_deg", "distance_m"};

/// The [animation] keys of a flyover through `keyframes`: path = "flyover",
/// waypoints = their eyes as [lon, lat, height], and look_at = their target
/// when all have one (an orbit-like path; else the flyover looks ahead).
/// nullopt, after an error, for fewer than two keyframes or two in a row at
/// one place. A film needs `frames`: kFlyoverFramesPerLeg a leg, where the
/// scene gives none (flyoverDefaultsOf).
std::optional<std::vector<std::pair<std::string, std::string>>> flyoverKeysOf(const PreviewScene& preview,
                                                                              std::span<const PageView> keyframes,
                                                                              Diagnostics& diags);
inline constexpr int kFlyoverFramesPerLeg = 48;  // two seconds at 24 frames a second
std::vector<std::pair<std::string, std::string>> flyoverDefaultsOf(size_t keyframes);
/// The [animation] keys a flyover's replaces, commented out: an orbit's, a track's.
inline constexpr const char* kReplacedAnimationKeys[] = {"azimuth_from_deg", "azimuth_to_deg", "track", "track_layer",
                                                         "height_above_terrain_m", "look_ahead_m", "look_at"};

/// Writes `keys` into table `table` of the scene file `scenePath` (its
/// comments, order and other keys kept; `retired` commented out; the file
/// before beside it as <name>.bak; written atomically; `defaults` added
/// where the table lacks them), or, for a DEM
/// previewed alone, into the new scene `preview` names. Returns the path
/// written; nullopt after an error.
std::optional<std::filesystem::path> writeSceneKeys(
    const PreviewScene& preview, const std::filesystem::path& scenePath, const std::string& table,
    const std::vector<std::pair<std::string, std::string>>& keys, std::span<const char* const> retired,
    Diagnostics& diags, const std::vector<std::pair<std::string, std::string>>& defaults = {});

}  // namespace relief
