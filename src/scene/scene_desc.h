#pragma once
// Stage 1 of 5. Input: a scene file (TOML). Output: SceneDesc, every value
// validated, with defaults filled in and the source location of each key kept.
#include <array>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/source_loc.h"

namespace relief::scene {

/// The deepest subdivision a scene may ask for (and depth = "auto" may choose).
inline constexpr int kMaxDepth = 8;

enum class FrameKind { Utm, Local };
enum class Gridding { Linear, InverseDistance, Nearest };
enum class Projection { Perspective, Orthographic };

struct ColorStop {
    double elevM;       ///< metres above the WGS84 ellipsoid datum of the samples
    double r, g, b;     ///< linear 0..1 components of an sRGB colour
};

struct ColorRamp {
    std::string preset;            ///< name, or "custom"
    std::vector<ColorStop> stops;  ///< custom stops (sorted by elevM), empty for presets
};

/// `section.key` = value pairs applied on top of a scene file (relief sweep's
/// --vary, relief test's resolution, --set). Values are typed as TOML would:
/// an integer, a float, true/false, else a string (fractions such as "7/32"
/// stay strings, which every numeric key accepts).
using SceneOverrides = std::vector<std::pair<std::string, std::string>>;

struct SceneDesc {
    std::filesystem::path sceneFile;  ///< as given
    std::string sceneSha1;            ///< hash of the scene file's bytes
    SceneOverrides overrides;         ///< applied on top of the file

    // [samples]
    std::filesystem::path samplesPath;  ///< resolved against the scene file's folder
    std::string samplesPathAsWritten;
    SourceLoc samplesLoc;

    // [frame]
    FrameKind frame = FrameKind::Utm;
    std::string utmZone = "auto";  ///< "auto" or e.g. "60S"
    SourceLoc utmZoneLoc;

    // [net]
    int netRows = 0, netCols = 0;  ///< 0 when spacing is given
    double netSpacingM = 0;        ///< 0 when rows/cols are given
    std::optional<std::array<double, 4>> extentM;  ///< xmin, ymin, xmax, ymax in the frame
    Gridding gridding = Gridding::Linear;
    SourceLoc netLoc;

    // [vertical]
    double exaggeration = 1.0;

    // [subdivision]
    std::string scheme = "dlg4";
    std::map<std::string, double> schemeParams;  ///< as written (missing ones: scheme defaults)
    std::map<std::string, SourceLoc> schemeParamLocs;
    SourceLoc schemeLoc;
    std::string preset;             ///< a named special case ("hassan"), or ""
    SourceLoc presetLoc;
    int maskArity = 0;              ///< scheme = "mask": the user's own mask
    std::optional<int> maskFirst;   ///< exponent of the first mask coefficient (default: centred)
    std::vector<double> mask;
    SourceLoc maskLoc;
    bool allowNonconvergent = false;
    int depth = 3;                  ///< when depthAuto: set by the subdivision stage
    SourceLoc depthLoc;
    bool depthAuto = false;         ///< depth = "auto": the smallest depth whose last
                                    ///< level moves the rows and columns by <= toleranceM
    double toleranceM = 0;
    SourceLoc toleranceLoc;

    // [limits]
    double maxTriangles = 20e6;
    double maxSdlMB = 2048;
    double maxParseS = 120;

    // [texture]
    ColorRamp ramp{"terrain", {}};

    // [lighting]
    double sunAzimuthDeg = 315;   ///< compass bearing the light comes from
    double sunAltitudeDeg = 45;

    // [camera]
    double cameraAzimuthDeg = 200;   ///< compass bearing of the camera from the terrain centre
    double cameraElevationDeg = 35;  ///< above the horizontal
    double cameraDistanceM = 0;      ///< 0: fit the terrain in view
    double fovDeg = 40;
    Projection projection = Projection::Perspective;

    // [render]
    int width = 800;
    int height = 600;
    bool antialias = true;
    std::string output;  ///< "" = out/<scene stem>.png
};

}  // namespace relief::scene
