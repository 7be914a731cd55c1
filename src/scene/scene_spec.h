#pragma once
// Stage 1 of 6. Input: a scene file (TOML). Output: SceneSpec, one typed spec
// per stage, every value validated, defaults filled in, and the source location
// of every key kept in the spec that holds it, so the stage that finds a
// problem reports it at the key that caused it.
//
// One section, one spec (and one reader, scene/read_sections.h):
//   [samples]                  -> SamplesSpec      geo (the control net)
//   [frame]                    -> FrameSpec        geo
//   [net]                      -> NetSpec          geo
//   [subdivision]              -> SubdivisionSpec  subdiv::resolveScheme, the depth
//   [limits]                   -> LimitsSpec       the output budget
//   [vertical] [texture] [lighting] [camera] [base] [water] [atmosphere]
//                              -> VerticalSpec ... AtmosphereSpec, read together by emit as LookSpec
//   [geometry]                 -> GeometrySpec     emit (the terrain's kind)
//   [render]                   -> RenderSpec       emit (aspect), render
//   [overlay]                  -> OverlaySpec      annotate
//   [animation]                -> AnimationSpec    relief animate (each frame a set of overrides)
// The names of the enums' values are in scene/enum_names.h.
#include <array>
#include <filesystem>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "core/date_time.h"
#include "core/source_loc.h"
#include "core/types.h"

namespace relief::scene {

/// The deepest subdivision a scene may ask for (and depth = "auto" may choose).
inline constexpr int kMaxDepth = 8;
/// The most coefficients subdivision.mask may have (the papers' masks have at
/// most a dozen; the analysis grows as the cube of the length).
inline constexpr size_t kMaxMaskCoefficients = 64;
/// The longest text a scene may put on the still (title, credits, attributions).
inline constexpr size_t kMaxTextBytes = 1000;

/// Where the keys of a spec were written: `section.key` -> location. A key
/// the file does not give falls back to its section's header, then the file.
struct KeyLocations {
    std::string file;                               ///< the scene file, as given
    std::map<std::string, SourceLoc> sections;      ///< "net" -> the [net] header
    std::map<std::string, SourceLoc> keys;          ///< "net.spacing_m" -> the key
    std::set<std::string> known;                    ///< every key the reader reads in these sections
    std::set<std::string> wholeNumbers;             ///< the known keys read as integers (render.width, ...)
    /// The location of `qualifiedKey` ("section.key"), else of its section, else the file.
    /// A key the reader does not know is a typo in relief (a test over the sources finds them).
    SourceLoc at(const std::string& qualifiedKey) const;
    bool has(const std::string& qualifiedKey) const { return keys.count(qualifiedKey) > 0; }
    bool knows(const std::string& qualifiedKey) const { return known.count(qualifiedKey) > 0; }
};

/// The frame's projection: a UTM zone, the local tangent plane at the data's
/// centre, or a raster DEM's own projected CRS in metres (no reprojection).
enum class FrameKind { Utm, Local, Raster };
enum class Gridding { Linear, InverseDistance, Nearest, Fit };
/// A fitted net's nodes that no sample reaches (farther than
/// fit::kUnsupportedSpacings mean spacings from every sample): shown as the
/// fit makes them (with a warning when they are a tenth of the net or more),
/// their colour washed out (emit::kFadeColour) the farther they are, or left
/// out of the surface as nodata is.
enum class Unsupported { Show, Fade, Mask };
/// A camera's projection. Panoramic: a vertical cylinder about the eye
/// (POV-Ray's cylinder 1), fov_deg of it across the still, the horizon level
/// and its pixels square there. Spherical: the whole sphere about the eye as
/// an equirectangular image (POV-Ray's spherical, 360 x 180 degrees).
enum class Projection { Perspective, Orthographic, Panoramic, Spherical };

/// A colour of a ramp at an elevation.
struct ColorStop {
    double elevM = 0;  ///< metres above the WGS84 ellipsoid datum of the samples
    LinearRgb rgb;
};

struct ColorRamp {
    std::string preset;            ///< name, or "custom"
    std::vector<ColorStop> stops;  ///< custom stops (sorted by elevM), empty for presets
    std::string cptPath;           ///< the GMT palette the stops came from (as written), if any
};

/// `section.key` = value pairs applied on top of a scene file (relief sweep's
/// --vary, relief test's resolution, --set). Values are typed as TOML would:
/// an integer, a float, true/false, else a string (fractions such as "7/32"
/// stay strings, which every numeric key accepts).
using SceneOverrides = std::vector<std::pair<std::string, std::string>>;

/// How a raster is resampled onto the net (GDAL's warper).
enum class Resample { Bilinear, Cubic, Average, Nearest };
/// What becomes of net nodes without data (outside the raster, or its nodata):
/// left out of the mesh (Mask), filled from their neighbours (Fill), or an error.
enum class NodataPolicy { Mask, Fill, Error };

/// The Earth's elevations, with a margin: the Challenger Deep (-10,935 m) and
/// Everest (8,849 m). A value outside is a unit or a file error.
inline constexpr double kLowestElevationM = -11100, kHighestElevationM = 8900;
/// elevations = "any" have a bound too: heights become single-precision
/// vertices in scene units, and beyond 1e7 m (a thousand times any planet's
/// relief) they are a unit or a file error, not terrain.
inline constexpr double kAnyElevationLimitM = 1e7;

/// [samples]: where the elevation data are: a `lon,lat,elev` CSV of scattered
/// samples, or any raster DEM GDAL opens (recognised by GDAL, not by name).
struct SamplesSpec {
    std::filesystem::path path;   ///< resolved against the scene file's folder
    std::string pathAsWritten;    ///< for messages and the .pov header
    /// `path` may be a folder: the raster tiles in it (geo::rasterTilesIn), mosaicked.
    /// path = [...]: adjacent raster tiles mosaicked into one (geo/raster_mosaic.h);
    /// `path` is the first, `pathAsWritten` all of them. Empty for one file.
    std::vector<std::filesystem::path> tiles;
    std::string attribution;      ///< the data's credit line, as its licence asks (header, sidecar)
    /// Elevations must lie within the Earth's (kLowestElevationM..kHighestElevationM),
    /// unless the scene says the data are not terrain in metres (elevations = "any":
    /// other planets, synthetic surfaces).
    bool earthElevations = true;
    // Rasters only:
    int band = 1;                 ///< the band holding elevations
    std::string crs;              ///< "" = the raster's own; e.g. "EPSG:2193" for one without
    Resample resample = Resample::Bilinear;
    std::string verticalUnit;     ///< "" = the raster's own; "m", "ft" or "us-ft" for one that does not say
    NodataPolicy nodata = NodataPolicy::Mask;
    KeyLocations locs;
};

/// [frame]: the projected frame the net is built in. A scene that names no
/// kind (nor a zone) over one raster DEM in a projected CRS in metres, of
/// scale within 0.2 % of true over the raster, takes the raster's
/// own CRS (its cells need no reprojection); other data take UTM.
struct FrameSpec {
    FrameKind kind = FrameKind::Utm;
    std::string utmZone = "auto";  ///< "auto" or e.g. "60S"
    KeyLocations locs;
};

/// [net]: the rectangular control net the samples are gridded onto.
struct NetSpec {
    int rows = 0, cols = 0;        ///< 0 when spacing is given
    double spacingM = 0;           ///< 0 when rows/cols are given
    std::optional<FrameBox> extentM;  ///< in the frame (written xmin, ymin, xmax, ymax)
    /// WGS84 degrees (written lon_min, lat_min, lon_max, lat_max): the net
    /// covers the largest box of the frame inside this window
    std::optional<LonLatBox> extentLonLat;
    Gridding gridding = Gridding::Linear;
    /// gridding = "fit": the weight of the smoothness penalty against the
    /// samples (dimensionless); unset: chosen by cross-validation (fit/fit_net.h).
    std::optional<double> smoothing;
    /// gridding = "fit": the membrane's pull against the thin plate, in the
    /// samples' mean spacing (dimensionless, 0: none); unset: chosen by
    /// cross-validation (fit/fit_net.h) among 0 and the powers of two from 1/4 to 8
    /// (0 when smoothing is given).
    std::optional<double> tension;
    /// gridding = "fit": what becomes of the nodes no sample reaches.
    Unsupported unsupported = Unsupported::Show;
    /// The net prefiltered so that the scheme's surface passes through the
    /// net's own values at its nodes (an approximating scheme keeps the
    /// data's peaks); gridding = "fit" already fits the surface.
    bool fit = false;
    /// Not a key: set by the pipeline when subdivision.depth = "auto", which
    /// measures the net's own curves before the fit, so a net to be fitted is
    /// gridded linearly first (else each node's nearest sample: a staircase,
    /// but all the depth chosen for the still needs, and no triangulation).
    bool linearBeforeFit = false;
    KeyLocations locs;
};

/// The scheme as the user named it: a family and parameters, a preset, or a
/// mask. subdiv::resolveScheme turns it into a Scheme. Keys (for `locs`):
/// "subdivision.scheme", ".preset", ".mask", and one per parameter.
struct SchemeSpec {
    std::string name = "dlg4";     ///< family, "mask", or "" when a preset names it
    std::map<std::string, double> params;  ///< as written (missing ones: the family's defaults)
    std::string preset;            ///< a named special case ("hassan"), or ""
    int maskArity = 0;             ///< name = "mask": the user's own mask
    std::optional<int> maskFirst;  ///< exponent of the first mask coefficient (default: centred)
    std::vector<double> mask;
    bool allowNonconvergent = false;
    KeyLocations locs;
};

/// [subdivision]: the scheme and how deep to refine.
struct SubdivisionSpec {
    SchemeSpec scheme;
    int depth = 0;                 ///< when depthGiven
    bool depthGiven = false;       ///< an integer depth in the scene; neither it nor "auto":
                                   ///< the depth is chosen for the still (buildSurface)
    bool depthAuto = false;        ///< depth = "auto": the smallest depth whose last
                                   ///< level moves the rows and columns by <= toleranceM
    double toleranceM = 0;
    KeyLocations locs;
};

/// [limits]: the output budget, checked before refining.
struct LimitsSpec {
    double maxTriangles = 20e6;
    double maxSdlMB = 2048;
    double maxParseS = 120;
    double maxMemoryMB = 0;  ///< 0 = three quarters of this machine's memory
    double maxFilmS = 0;     ///< a film's estimated rendering, wall seconds; 0 = no limit
    double maxLayerVertices = 1e7;  ///< read from one [[layer]]'s file
    KeyLocations locs;
};

/// [camera]
struct CameraSpec {
    double azimuthDeg = 200;    ///< compass bearing of the camera from the terrain centre
    double elevationDeg = 35;   ///< above the horizontal
    double distanceM = 0;       ///< 0: fit the terrain in view
    double fovDeg = 40;         ///< across the still: perspective up to 170, panoramic up to 360 (default 180)
    Projection projection = Projection::Perspective;
    /// Placed by geography instead: [lon, lat, height above sea level in m]
    /// for the eye and (optional; else the terrain's centre) the point looked at.
    std::optional<GeoPoint> position, lookAt;
    KeyLocations locs;
};

/// [base]: the terrain as a solid block, side walls down to a flat floor
/// (a block model), or a floating surface.
struct BaseSpec {
    bool enabled = true;
    std::optional<double> thicknessM;  ///< below the lowest elevation, true metres; unset: a tenth of the relief
    KeyLocations locs;
};

/// [water]: a water surface over the terrain's extent.
struct WaterSpec {
    std::optional<double> levelM;  ///< unset: no water
    LinearRgb colour{0.05, 0.18, 0.32};     ///< #3f7699 in sRGB
    double transparency = 0.35;             ///< 0 opaque .. 1 clear
    KeyLocations locs;
};

/// [vertical]
struct VerticalSpec {
    double exaggeration = 1.0;
    KeyLocations locs;
};

/// [texture]: what colours the surface.
struct TextureSpec {
    ColorRamp ramp{"terrain", {}, {}};
    /// [texture] mode and image.
    enum class Colouring {
        Elevation,  ///< the ramp over elevation
        Slope,      ///< pale on flat ground to rock on steep
        Blend,      ///< the ramp, turning to rock where the ground is steep
        Image,      ///< a georeferenced image draped on the surface
    };
    Colouring colouring = Colouring::Elevation;
    LinearRgb rockColour{0.159, 0.130, 0.100};      ///< #6f6559 in sRGB
    double rockFromDeg = 30, rockToDeg = 45;        ///< slopes where rock starts and takes over
    std::filesystem::path drapeImage;               ///< Colouring::Image: the raster, resolved against the scene
    std::string drapeImageText;                     ///< as written
    std::string drapeImageAttribution;              ///< [texture] image_attribution: the image's credit line
    KeyLocations locs;
};

/// [lighting]
struct LightingSpec {
    double sunAzimuthDeg = 315;  ///< compass bearing the light comes from
    double sunAltitudeDeg = 30;  ///< low enough that ridges cast the shadows that make them read (docs/scene-format.md)
    /// The sun's angular diameter, for render.quality = "high" (soft shadows);
    /// the real sun's by default.
    double sunDiameterDeg = 0.53;
    /// datetime: the sun is placed where it was then, over the terrain's
    /// centre (compileScene), in place of the two angles.
    std::optional<OffsetDateTime> sunTime;
    std::string sunTimeText;  ///< as written in the scene
    KeyLocations locs;
};

/// [atmosphere]
struct AtmosphereSpec {
    double haze = 0;  ///< in [0, 1]: distance fog, 0 none
    KeyLocations locs;
};

/// How the terrain looks: the specs of [vertical], [texture], [lighting],
/// [camera], [base], [water] and [atmosphere], which emit/ reads together.
struct LookSpec {
    VerticalSpec vertical;
    TextureSpec texture;
    LightingSpec lighting;
    CameraSpec camera;
    BaseSpec base;
    WaterSpec water;
    AtmosphereSpec atmosphere;
};

/// What is behind the terrain: the sky gradient, one colour, or nothing (a
/// PNG with alpha, for a report's own background).
enum class Background { Sky, Colour, Transparent };

/// [render]: the still.
/// [render] quality: how much work a still's light gets. Draft: no
/// antialiasing. Report: one sun's hard shadows over an even ambient light,
/// antialiased. High: the sun as a disc of lighting.sun_diameter_deg (soft
/// shadows), the sky's light on each node by its sky-view factor (dark in
/// gullies, full on ridges), and finer antialiasing.
enum class Quality { Draft, Report, High };

/// What each quality level does: a row a level.
struct QualityLevel {
    Quality quality;
    bool antialias;             ///< with render.antialias: both must be on
    double antialiasThreshold;  ///< POV-Ray's +A
    int antialiasDepth;         ///< POV-Ray's +R
    bool softSun;               ///< the sun an area light of lighting.sun_diameter_deg
    bool skyLight;              ///< each node's colour times its sky-view factor
};
inline constexpr QualityLevel kQualityLevels[] = {
    {Quality::Draft, false, 0.3, 3, false, false},
    {Quality::Report, true, 0.3, 3, false, false},
    {Quality::High, true, 0.1, 4, true, true},
};
inline const QualityLevel& qualityLevel(Quality q) {
    for (const QualityLevel& level : kQualityLevels)
        if (level.quality == q) return level;
    return kQualityLevels[1];
}

struct RenderSpec {
    int width = 800;
    int height = 600;
    bool antialias = true;
    Quality quality = Quality::Report;
    Background background = Background::Sky;
    LinearRgb backgroundColour;  ///< Background::Colour
    std::string output;  ///< "" = out/<scene stem>.png; .png, .pdf or .svg
    double timeoutS = 0; ///< POV-Ray stopped after this long; 0 = no limit
    /// The still's resolution for print: a PNG's pHYs chunk, a PDF's or SVG's
    /// page size (the pixels at this many a inch). Unset: none in a PNG,
    /// kDocumentDpi for a PDF or SVG.
    std::optional<double> dpi;
    static constexpr double kDocumentDpi = 300;
    KeyLocations locs;
};

/// [overlay]: what is drawn over the still for a report (annotate/).
/// [overlay] contours: contour lines drawn on the terrain's surface.
struct ContourSpec {
    double intervalM = 50;      ///< between lines, true metres
    int indexEvery = 5;         ///< every n-th line (from 0 m) is an index contour, drawn heavier
    LinearRgb colour{0.05, 0.035, 0.02};  ///< #3e3426 in sRGB
};

/// [overlay] graticule: lines of longitude and latitude lying on the surface,
/// labelled where they leave the terrain at the still's edges.
struct GraticuleSpec {
    double stepDeg = 0;  ///< 0: "auto", about five lines over the terrain's larger span
    LinearRgb colour{0.03, 0.03, 0.03};
    double widthPx = 1.2;
};

/// The furniture's items, as overlay.place names them (the title holds the subtitle).
inline const std::vector<std::string> kFurnitureItems = {"title",     "north_arrow", "credits",
                                                         "scale_bar", "legend",      "layer_legend"};
/// Where overlay.place may put an item: a corner, the middle of an edge, or nowhere.
inline const std::vector<std::string> kFurniturePlaces = {"auto",  "top-left",    "top",    "top-right",
                                                          "left",  "right",       "bottom-left",
                                                          "bottom", "bottom-right", "off"};

/// The international foot and mile, in metres.
inline constexpr double kFootM = 0.3048, kMileM = 1609.344;

/// A length unit of the scale bar and the legend: its name and metres.
struct LengthUnit {
    std::string name;  ///< "m", "km", "ft", "mi"
    double metres = 1;
};

struct OverlaySpec {
    enum class Enabled { Auto, On, Off };
    Enabled enabled = Enabled::Auto;  ///< Auto: on for stills at least kMinAutoWidthPx wide
    static constexpr int kMinAutoWidthPx = 480;
    std::string title, subtitle;
    std::optional<std::string> credits;  ///< unset: the samples' attribution
    bool legend = true, scaleBar = true, northArrow = true;
    /// Each item the author placed (kFurnitureItems) at one of kFurniturePlaces;
    /// an item not named here is placed automatically.
    std::map<std::string, std::string> places;
    double textScale = 1;           ///< every text's size times this
    std::string legendTitle;        ///< "": the colouring's ("Elevation (m)")
    bool legendFeet = false;        ///< the elevation legend's ticks in feet
    bool scaleBarImperial = false;  ///< the scale bar's automatic length in feet and miles
    std::optional<LengthUnit> scaleBarUnit;  ///< with scaleBarLength: the bar's length as written
    double scaleBarLength = 0;               ///< in scaleBarUnit; 0: chosen (about a fifth of the still)
    std::optional<ContourSpec> contours;  ///< unset: none
    std::optional<GraticuleSpec> graticule;  ///< unset: none
    /// A map's frame around a still from straight above (orthographic): a
    /// neat line, ticks and annotations outside the map on its four sides.
    bool frame = false;
    bool frameMetres = false;  ///< the frame's annotations in the frame's metres, not longitude and latitude
    KeyLocations locs;
};

/// What the terrain becomes in the .pov. Mesh2: every refined node a vertex
/// (exact, the reference). Adaptive: a mesh2 of the refined surface within a
/// tolerance (emit/adaptive_mesh.h). HeightField: the refined lattice as a
/// 16-bit PNG POV-Ray reads in a fraction of the time (heights quantized to
/// 1/65535 of their range). Auto: chosen by emit::chooseGeometry.
enum class GeometryKind { Auto, Mesh2, Adaptive, HeightField };

/// [geometry]
struct GeometrySpec {
    GeometryKind kind = GeometryKind::Auto;
    double tolerancePx = 0.1;  ///< adaptive: the largest vertical error, in pixels at the nearest terrain
    double toleranceM = 0;     ///< adaptive: the same in metres, instead; 0 = use tolerancePx
    KeyLocations locs;
};

/// What moves in a film's frames. Orbit: the camera's azimuth turns around
/// the terrain's centre (elevation and distance as [camera] says, or varied).
/// Flyover: the eye along a smooth path through waypoints or a track's line.
enum class CameraPath { Still, Orbit, Flyover };

/// [animation]: the frames of `relief animate`, each the scene with a few
/// keys set (camera.azimuth_deg, lighting.datetime, overlay.subtitle, the
/// varied keys), so that `relief render --set ...` of a frame's keys makes
/// that frame's still.
struct AnimationSpec {
    static constexpr int kMaxFrames = 10000;
    bool present = false;  ///< the scene has an [animation] section
    int frames = 0;        ///< required
    double fps = 30;
    CameraPath path = CameraPath::Still;
    std::optional<double> azimuthFromDeg, azimuthToDeg;  ///< orbit; unset: camera.azimuth_deg, a full turn on
    /// sun = { from, to }: the sun at each frame's time, from the ephemeris.
    struct SunWindow {
        OffsetDateTime from, to;
    };
    std::optional<SunWindow> sun;
    bool skipNight = false;  ///< frames with the sun below the horizon left out, not an error
    bool counter = false;    ///< "frame k of n" added to the overlay's subtitle
    /// vary = { "section.key" = [from, to] }: a numeric key eased between two values.
    struct Varied {
        std::string key;
        double from = 0, to = 0;
        bool wholeNumber = false;  ///< the key takes integers (render.width): each frame's value rounded
    };
    std::vector<Varied> vary;
    /// path = "flyover": the eye through waypoints, or along the first line of
    /// a vector file, at constant ground speed (film/flyover.h).
    struct Flyover {
        std::vector<GeoPoint> waypoints;  ///< [lon, lat, height_m] or [lon, lat] (the height then unused)
        bool waypointHeights = false;     ///< the waypoints give heights above sea level (three numbers)
        std::filesystem::path track;      ///< a vector file GDAL reads, resolved against the scene's folder
        std::string trackAsWritten;       ///< animation.track as the scene gives it
        std::string trackLayer;           ///< its layer; "" = the first with a line
        /// The eye this far above the ground under it; unset with heights: the
        /// waypoints' own, else a twentieth of the terrain's diagonal.
        std::optional<double> heightAboveTerrainM;
        std::optional<double> lookAheadM;  ///< looks at the ground this far ahead; unset: max(path / 10, 4 x height)
        std::optional<GeoPoint> lookAt;    ///< looks here instead, [lon, lat, elev_m]
    };
    Flyover flyover;
    KeyLocations locs;
};

/// [[layer]]: one layer of a vector file, drawn on the terrain: points as
/// markers standing on the surface with labels beside them, lines as ribbons
/// lying on it, polygons as their outlines and an optional tint.
enum class MarkerKind { Pin, Dot, Flag, None };

struct LayerSpec {
    static constexpr int kMaxLayers = 64;
    static constexpr double kMinLabelPx = 10;  ///< no label a reader cannot read
    std::filesystem::path path;       ///< resolved against the scene file's folder
    std::string pathAsWritten;
    std::string layer;                ///< the file's layer; "" = its first holding a feature
    std::string crs;                  ///< the CRS of a file that declares none (EPSG:2193, a WKT, a PROJ string)
    std::string labelField;           ///< label = "name": each point's label is this attribute's value
    std::string labelText;            ///< label_text = "Summit": every point's label
    std::string legend;               ///< the legend's entry for the layer; "" = none
    MarkerKind marker = MarkerKind::Pin;
    double markerSizePx = 20;         ///< a marker's height on the still
    double labelSizePx = 13;
    double widthPx = 2.5;             ///< lines and outlines, at the centre of the view
    std::vector<double> dashPx;       ///< [on, off] along lines; empty: solid
    LinearRgb colour;                 ///< markers, lines, outlines
    std::optional<LinearRgb> fill;    ///< polygons: a tint laid over the surface's colour
    double fillOpacity = 0.35;
    int number = 0;                   ///< 1-based, in the scene's order (messages, the sidecar)
    KeyLocations locs;
};

/// The whole scene file: one spec per stage, and where it came from.
struct SceneSpec {
    std::filesystem::path sceneFile;  ///< as given
    std::string sceneSha1;            ///< hash of the scene file's bytes
    std::string madeForData;          ///< the scene's text when sceneFile is elevation data (relief made it)
    SceneOverrides overrides;         ///< applied on top of the file

    SamplesSpec samples;
    FrameSpec frame;
    NetSpec net;
    SubdivisionSpec subdivision;
    LookSpec look;
    GeometrySpec geometry;
    RenderSpec render;
    OverlaySpec overlay;
    LimitsSpec limits;
    AnimationSpec animation;
    std::vector<LayerSpec> layers;  ///< [[layer]], drawn in this order
};

}  // namespace relief::scene
