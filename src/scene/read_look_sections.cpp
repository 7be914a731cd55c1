// The sections that say how the terrain looks: its exaggeration, colours,
// light, camera, block, water, haze and the report's overlays.
#include <algorithm>
#include <cmath>
#include <charconv>
#include <cstdlib>

#include <fmt/format.h>

#include "core/input_file.h"
#include "core/number_format.h"
#include "core/text_escape.h"
#include "scene/color_ramp.h"
#include "scene/cpt_palette.h"
#include "scene/read_sections.h"

namespace relief::scene {

void readVertical(Section& s, const SceneFile&, SceneSpec& scene) {
    if (auto e = s.number("exaggeration", 0, 100, "(unitless factor)", true)) scene.look.vertical.exaggeration = *e;
}

namespace {

// texture.cpt: a GMT palette file beside the scene, in place of a ramp.
void readCpt(Section& s, const SceneFile& f, ColorRamp& ramp) {
    const auto c = s.string("cpt");
    if (!c) return;
    const std::filesystem::path cptPath = f.path.parent_path() / *c;
    std::optional<std::string> cptText;
    std::string problem;
    if (s.find("ramp"))
        s.error("cpt", "give either texture.ramp or texture.cpt, not both");
    else if (!(cptText = readInputFile(cptPath, kMaxPaletteBytes, problem)))
        s.error("cpt", problem == "no such file" ? fmt::format("texture.cpt: file \"{}\" not found (looked for {})",
                                                                printableExcerpt(*c), printableExcerpt(cptPath.string(), 200))
                                                  : fmt::format("texture.cpt = \"{}\": {}", printableExcerpt(*c), problem));
    else if (auto stops = parseCpt(*cptText, cptPath.string(), f.diags)) {
        ramp.preset = "custom";
        ramp.stops = std::move(*stops);
        ramp.cptPath = *c;
    }
}

// texture.mode and the rock's colour and slopes.
void readColouring(Section& s, TextureSpec& texture) {
    using Colouring = TextureSpec::Colouring;
    if (auto m = s.named<Colouring>("mode", kTextureModeNames)) texture.colouring = *m;
    if (auto v = s.string("rock_color"); v && !parseHexColor(*v, texture.rockColour))
        s.error("rock_color", fmt::format("texture.rock_color = \"{}\" must be a colour \"#rrggbb\"", printableExcerpt(*v)));
    if (auto v = s.number("rock_from_deg", 0, 90, "degrees of slope", false, true)) texture.rockFromDeg = *v;
    if (auto v = s.number("rock_to_deg", 0, 90, "degrees of slope", true)) texture.rockToDeg = *v;
    if (!(texture.rockToDeg > texture.rockFromDeg))
        s.error(s.find("rock_to_deg") ? "rock_to_deg" : "rock_from_deg",
                fmt::format("texture.rock_to_deg ({}) must be above texture.rock_from_deg ({})",
                            formatShortest(texture.rockToDeg), formatShortest(texture.rockFromDeg)));
}

// texture.image: a georeferenced image draped on the surface.
void readDrapeImage(Section& s, const SceneFile& f, TextureSpec& texture) {
    if (auto v = s.text("image_attribution")) texture.drapeImageAttribution = *v;
    const auto v = s.string("image");
    if (!v) return;
    const std::filesystem::path image = f.path.parent_path() / *v;
    const std::string problem = inputFileProblem(image);
    if (s.find("mode") && texture.colouring != TextureSpec::Colouring::Elevation)
        s.error("image", "texture.image colours the surface by itself: leave out texture.mode");
    else if (problem == "no such file")
        s.error("image", fmt::format("texture.image: file \"{}\" not found (looked for {})", printableExcerpt(*v),
                                     printableExcerpt(image.string(), 200)));
    else if (!problem.empty())
        s.error("image", fmt::format("texture.image = \"{}\": {}", printableExcerpt(*v), problem));
    else {
        texture.colouring = TextureSpec::Colouring::Image;
        texture.drapeImage = image;
        texture.drapeImageText = *v;
    }
}

// One entry of texture.stops, { elev_m = <metres>, color = "#rrggbb" }, above the one before.
void readStop(const toml::node& item, const SceneFile& f, ColorRamp& ramp) {
    const toml::table* st = item.as_table();
    ColorStop stop{};
    auto elev = st ? st->get("elev_m") : nullptr;
    auto color = st ? st->get("color") : nullptr;
    std::optional<double> e = elev ? elev->value<double>() : std::nullopt;
    std::optional<std::string> c = color ? color->value_exact<std::string>() : std::nullopt;
    if (!e || !c || !parseHexColor(*c, stop.rgb)) {
        f.diags.error(locOf(f.name, item.source()),
                      "each texture.stops entry must be { elev_m = <metres>, color = \"#rrggbb\" }");
        return;
    }
    stop.elevM = *e;
    if (!ramp.stops.empty() && stop.elevM <= ramp.stops.back().elevM)
        f.diags.error(locOf(f.name, item.source()),
                      fmt::format("texture.stops: elev_m = {} m must be above the previous stop ({} m); list stops "
                                  "bottom to top",
                                  formatShortest(stop.elevM), formatShortest(ramp.stops.back().elevM)));
    ramp.stops.push_back(stop);
}

// texture.stops: the colours of ramp = "custom".
void readStops(Section& s, const SceneFile& f, ColorRamp& ramp) {
    s.markKnown("stops");
    const toml::node* stopsNode = s.find("stops");
    if (stopsNode && !ramp.cptPath.empty()) {
        s.error("stops", "texture.stops and texture.cpt both give the colours: keep one");
    } else if (!ramp.cptPath.empty()) {
        // the palette file's stops
    } else if (stopsNode && ramp.preset != "custom") {
        s.error("stops", "texture.stops is only used with ramp = \"custom\"; add "
                         "ramp = \"custom\" or remove the stops");
    } else if (ramp.preset == "custom") {
        const toml::array* a = stopsNode ? stopsNode->as_array() : nullptr;
        if (!a || a->size() < 2)
            f.diags.error(stopsNode ? locOf(f.name, stopsNode->source()) : s.loc(),
                          "ramp = \"custom\" needs texture.stops = [{ elev_m = 0, color = "
                          "\"#rrggbb\" }, ...] with at least 2 stops");
        else
            for (const toml::node& item : *a) readStop(item, f, ramp);
    }
}

}  // namespace

void readTexture(Section& s, const SceneFile& f, SceneSpec& scene) {
    TextureSpec& texture = scene.look.texture;
    std::vector<std::string> ramps = rampPresetNames();
    ramps.push_back("custom");
    if (auto r = s.choice("ramp", ramps)) texture.ramp.preset = *r;
    readCpt(s, f, texture.ramp);
    readColouring(s, texture);
    readDrapeImage(s, f, texture);
    readStops(s, f, texture.ramp);
}

// lighting.datetime: a string, or TOML's own offset date-time (written without quotes).
std::optional<std::string> dateTimeText(const toml::node& n) {
    std::optional<std::string> text = n.value_exact<std::string>();
    if (const auto* native = n.as_date_time()) {
        const toml::date_time& t = native->get();
        text = fmt::format("{:04}-{:02}-{:02}T{:02}:{:02}:{:02}", t.date.year, t.date.month, t.date.day, t.time.hour,
                           t.time.minute, t.time.second);
        if (t.offset)
            *text += t.offset->minutes == 0
                         ? std::string("Z")
                         : fmt::format("{}{:02}:{:02}", t.offset->minutes < 0 ? '-' : '+',
                                       std::abs(t.offset->minutes) / 60, std::abs(t.offset->minutes) % 60);
    }
    return text;
}

void readLighting(Section& s, const SceneFile&, SceneSpec& scene) {
    LightingSpec& lighting = scene.look.lighting;
    if (auto v = s.number("sun_azimuth_deg", 0, 360, "degrees (compass bearing)", false, true))
        lighting.sunAzimuthDeg = *v;
    if (auto v = s.number("sun_altitude_deg", 0, 90, "degrees", true)) lighting.sunAltitudeDeg = *v;
    if (auto v = s.number("sun_diameter_deg", 0, 10, "degrees", true)) lighting.sunDiameterDeg = *v;
    s.markKnown("datetime");
    const toml::node* n = s.find("datetime");
    if (!n) return;
    const std::optional<std::string> text = dateTimeText(*n);
    std::string why = "it must be a date and time with its UTC offset";
    if (text) lighting.sunTime = parseOffsetDateTime(*text, why);
    if (!lighting.sunTime)
        s.error("datetime",
                fmt::format("lighting.datetime{}: {}", text ? " = \"" + printableExcerpt(*text) + "\"" : "", why));
    else
        lighting.sunTimeText = *text;
    for (const char* angle : {"sun_azimuth_deg", "sun_altitude_deg"})
        if (lighting.locs.has(std::string("lighting.") + angle))
            s.warning(angle, fmt::format("lighting.{} is not used: lighting.datetime places the sun", angle));
}

namespace {

// camera.fov_deg as the projection takes it: a perspective's up to 170
// degrees, a panorama's up to 360 (180 unless given), none for a sphere.
void readFieldOfView(Section& s, std::optional<double> fov, CameraSpec& camera) {
    if (camera.projection == Projection::Panoramic) camera.fovDeg = fov.value_or(180);
    else if (fov) camera.fovDeg = *fov;
    if (camera.projection == Projection::Perspective && camera.fovDeg > 170)
        s.error("fov_deg", fmt::format("camera.fov_deg = {} is wider than a perspective camera takes (170): for a "
                                       "wider view use camera.projection = \"panoramic\"",
                                       formatShortest(camera.fovDeg)));
    if (camera.projection == Projection::Spherical && fov)
        s.warning("fov_deg", "camera.fov_deg is not used: a spherical camera sees the whole sphere (360 x 180 degrees)");
}

}  // namespace

void readCamera(Section& s, const SceneFile&, SceneSpec& scene) {
    CameraSpec& camera = scene.look.camera;
    if (auto v = s.number("azimuth_deg", 0, 360, "degrees (compass bearing)", false, true)) camera.azimuthDeg = *v;
    if (auto v = s.number("elevation_deg", 0, 90, "degrees", true)) camera.elevationDeg = *v;
    if (auto v = s.number("distance_m", 0, 1e8, "m", true)) camera.distanceM = *v;
    const auto fov = s.number("fov_deg", 1, 360, "degrees");
    if (auto p = s.named<Projection>("projection")) camera.projection = *p;
    readFieldOfView(s, fov, camera);
    camera.position = s.lonLatHeight("position");
    camera.lookAt = s.lonLatHeight("look_at");
    if (camera.lookAt && !camera.position)
        s.error("look_at", "camera.look_at needs camera.position (the eye, [lon, lat, height_m])");
    for (const char* orbit : {"azimuth_deg", "elevation_deg", "distance_m"})
        if (camera.position && camera.locs.has(std::string("camera.") + orbit))
            s.warning(orbit, fmt::format("camera.{} is not used: camera.position places the eye", orbit));
}

void readBase(Section& s, const SceneFile&, SceneSpec& scene) {
    s.markKnown("thickness_m");
    const toml::node* n = s.find("thickness_m");
    if (!n) return;
    if (auto b = n->value_exact<bool>()) scene.look.base.enabled = *b;
    else if (auto v = s.number("thickness_m", 0, 1e5, "metres (or false: no block)", true))
        scene.look.base.thicknessM = *v;
}

void readWater(Section& s, const SceneFile&, SceneSpec& scene) {
    WaterSpec& water = scene.look.water;
    if (auto v = s.number("level_m", kLowestElevationM, kHighestElevationM, "metres above sea level")) water.levelM = *v;
    if (auto v = s.string("color"); v && !parseHexColor(*v, water.colour))
        s.error("color", fmt::format("water.color = \"{}\" must be a colour \"#rrggbb\"", printableExcerpt(*v)));
    if (auto v = s.number("transparency", 0, 1, "0 (opaque) to 1 (clear)")) water.transparency = *v;
}

void readAtmosphere(Section& s, const SceneFile&, SceneSpec& scene) {
    if (auto v = s.number("haze", 0, 1, "0 (none) to 1 (thick)")) scene.look.atmosphere.haze = *v;
}

namespace {

// overlay.contours: an inline table, { interval_m = 50, index_every = 5, color = "#3e3426" }.
std::optional<ContourSpec> contoursOf(const toml::node& n) {
    const toml::table* t = n.as_table();
    ContourSpec contours;
    bool ok = t != nullptr && t->contains("interval_m");
    for (auto&& [k, v] : t ? *t : toml::table{}) {
        const std::string key(k.str());
        if (key == "interval_m") {
            const auto d = v.value<double>();
            ok = ok && d && *d > 0 && std::isfinite(*d);
            if (d) contours.intervalM = *d;
        } else if (key == "index_every") {
            const auto i = v.value_exact<int64_t>();
            ok = ok && i && *i >= 0 && *i <= 100;
            if (i) contours.indexEvery = static_cast<int>(*i);
        } else if (key == "color") {
            const auto c = v.value_exact<std::string>();
            ok = ok && c && parseHexColor(*c, contours.colour);
        } else {
            ok = false;
        }
    }
    return ok ? std::optional(contours) : std::nullopt;
}

// overlay.graticule: "auto", or { step_deg = 0.01, color = "#080808", width_px = 1.2 }.
std::optional<GraticuleSpec> graticuleOf(const toml::node& n) {
    GraticuleSpec g;
    if (n.value_exact<std::string>() == std::optional<std::string>("auto")) return g;
    const toml::table* t = n.as_table();
    bool ok = t != nullptr;
    for (auto&& [k, v] : t ? *t : toml::table{}) {
        const std::string key(k.str());
        const auto d = v.value<double>();
        if (key == "step_deg") {
            ok = ok && d && *d >= 1.0 / 3600 && *d <= 30;
            if (d) g.stepDeg = *d;
        } else if (key == "width_px") {
            ok = ok && d && *d >= 0.5 && *d <= 20;
            if (d) g.widthPx = *d;
        } else if (key == "color") {
            const auto c = v.value_exact<std::string>();
            ok = ok && c && parseHexColor(*c, g.colour);
        } else {
            ok = false;
        }
    }
    return ok ? std::optional(g) : std::nullopt;
}

// overlay.place: an inline table, { legend = "top-left", north_arrow = "off" }.
// False with the error at the key when an item or a place is not one relief knows.
bool readPlaces(Section& s, OverlaySpec& overlay) {
    s.markKnown("place");
    const toml::node* n = s.find("place");
    if (!n) return true;
    const auto choices = [](const std::vector<std::string>& names) {
        std::string out;
        for (const auto& name : names) out += (out.empty() ? "\"" : ", \"") + name + "\"";
        return out;
    };
    const toml::table* t = n->as_table();
    if (!t) {
        s.error("place", fmt::format("overlay.place must be a table {{ <item> = \"<place>\" }}; items: {}",
                                     choices(kFurnitureItems)));
        return false;
    }
    for (auto&& [k, v] : *t) {
        const std::string item(k.str());
        const auto where = v.value_exact<std::string>();
        if (std::find(kFurnitureItems.begin(), kFurnitureItems.end(), item) == kFurnitureItems.end()) {
            s.error("place", fmt::format("overlay.place.{}: no such item; the items are {}", printableExcerpt(item),
                                         choices(kFurnitureItems)));
            return false;
        }
        if (!where || std::find(kFurniturePlaces.begin(), kFurniturePlaces.end(), *where) == kFurniturePlaces.end()) {
            s.error("place", fmt::format("overlay.place.{} must be one of {}", item, choices(kFurniturePlaces)));
            return false;
        }
        if (*where != "auto") overlay.places[item] = *where;
    }
    return true;
}

// overlay.scale_bar_length: "2 km", "500 m", "1 mi", "2000 ft".
void readScaleBarLength(Section& s, OverlaySpec& overlay) {
    static const std::vector<LengthUnit> kUnits = {{"m", 1}, {"km", 1000}, {"ft", kFootM}, {"mi", kMileM}};
    const auto v = s.string("scale_bar_length");
    if (!v) return;
    // from_chars: the C locale's number whatever the user's (a German "2,5 km" is not 2.5).
    double length = 0;
    const auto [end, ec] = std::from_chars(v->data(), v->data() + v->size(), length);
    const std::string unit = ec == std::errc() ? std::string(end + (end < v->data() + v->size() && *end == ' '),
                                                             v->data() + v->size())
                                               : "";
    const bool parsed = ec == std::errc() && std::isfinite(length) && length > 0 && length <= 1e7;
    const auto u = std::find_if(kUnits.begin(), kUnits.end(), [&](const LengthUnit& x) { return x.name == unit; });
    if (!parsed || u == kUnits.end()) {
        s.error("scale_bar_length", fmt::format("overlay.scale_bar_length = \"{}\" must be a length and a unit: "
                                                "\"500 m\", \"2 km\", \"2000 ft\" or \"1 mi\"",
                                                printableExcerpt(*v)));
        return;
    }
    overlay.scaleBarUnit = *u;
    overlay.scaleBarLength = length;
    overlay.scaleBarImperial = u->name == "ft" || u->name == "mi";
}

// overlay.frame: a map's frame, around the view a map is made from (straight
// down, orthographic). The camera keys the scene leaves out are set so; one it
// gives otherwise is an error naming it.
void readMapFrame(Section& s, SceneSpec& scene) {
    OverlaySpec& overlay = scene.overlay;
    if (auto v = s.boolean("frame")) overlay.frame = *v;
    if (auto v = s.choice("frame_units", {"degrees", "metres"})) overlay.frameMetres = *v == "metres";
    if (!overlay.frame) return;
    CameraSpec& camera = scene.look.camera;
    const KeyLocations& given = camera.locs;
    constexpr const char* kWhy = "overlay.frame draws a map's frame around a view from straight above";
    if (camera.position)
        s.error("frame", fmt::format("{}: camera.position puts the eye at a place; remove it (or the frame)", kWhy));
    else if (given.has("camera.elevation_deg") && camera.elevationDeg != 90)
        s.error("frame", fmt::format("{}: camera.elevation_deg = {}; set it to 90, or leave it out",
                                     kWhy, formatShortest(camera.elevationDeg)));
    else if (given.has("camera.distance_m"))
        s.error("frame", fmt::format("{}, the map filling the room its annotations leave: camera.distance_m would "
                                     "size it instead; leave it out", kWhy));
    else if (given.has("camera.projection") && camera.projection != Projection::Orthographic)
        s.error("frame", fmt::format("{}: camera.projection is not \"orthographic\"; set it so, or leave it out", kWhy));
    camera.elevationDeg = 90;
    camera.projection = Projection::Orthographic;
}

}  // namespace

void readOverlay(Section& s, const SceneFile&, SceneSpec& scene) {
    OverlaySpec& overlay = scene.overlay;
    if (auto v = s.boolean("enabled")) overlay.enabled = *v ? OverlaySpec::Enabled::On : OverlaySpec::Enabled::Off;
    if (auto v = s.text("title")) overlay.title = *v;
    if (auto v = s.text("subtitle")) overlay.subtitle = *v;
    if (auto v = s.text("credits")) overlay.credits = *v;
    if (auto v = s.boolean("legend")) overlay.legend = *v;
    if (auto v = s.boolean("scale_bar")) overlay.scaleBar = *v;
    if (auto v = s.boolean("north_arrow")) overlay.northArrow = *v;
    readPlaces(s, overlay);
    if (auto v = s.number("text_scale", 0.5, 3, "(times the automatic size)")) overlay.textScale = *v;
    if (auto v = s.text("legend_title")) overlay.legendTitle = *v;
    if (auto v = s.choice("legend_units", {"m", "ft"})) overlay.legendFeet = *v == "ft";
    if (auto v = s.choice("scale_bar_units", {"metric", "imperial"})) overlay.scaleBarImperial = *v == "imperial";
    readScaleBarLength(s, overlay);
    readMapFrame(s, scene);
    s.markKnown("graticule");
    if (const toml::node* n = s.find("graticule")) {
        if (auto graticule = graticuleOf(*n)) overlay.graticule = graticule;
        else
            s.error("graticule", "overlay.graticule must be \"auto\" or { step_deg = <degrees, 1/3600 to 30> } with "
                                 "optional width_px = <0.5 to 20> and color = \"#rrggbb\"");
    }
    s.markKnown("contours");
    const toml::node* n = s.find("contours");
    if (!n) return;
    if (auto contours = contoursOf(*n)) overlay.contours = contours;
    else
        s.error("contours", "overlay.contours must be { interval_m = <metres> } with optional index_every "
                            "= <n> (every n-th line heavier, 0: none) and color = \"#rrggbb\"");
}

}  // namespace relief::scene
