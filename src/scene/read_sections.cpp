// The sections that say what the terrain is: its data, its frame and net,
// its subdivision and limits, its geometry and the still.
#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "core/input_file.h"
#include "core/text_escape.h"
#include "scene/color_ramp.h"
#include "scene/read_scene.h"
#include "scene/read_sections.h"

namespace relief::scene {

namespace {

// One file of samples.path, resolved against the scene's folder and checked; `written` gathers the names.
// A folder, when `folderToo`: its raster tiles (geo reads which they are).
std::filesystem::path samplesFile(Section& s, const SceneFile& f, const std::string& p, std::string& written,
                                  bool folderToo = false) {
    written += (written.empty() ? "" : ", ") + p;
    const std::filesystem::path path = f.path.parent_path() / p;
    std::error_code ec;
    if (folderToo && std::filesystem::is_directory(path, ec)) return path;
    if (const std::string problem = inputFileProblem(path); problem == "no such file")
        s.error("path", fmt::format("samples.path: file \"{}\" not found (looked "
                                    "for {}; the path is relative to the scene file)",
                                    printableExcerpt(p, 200), printableExcerpt(path.string(), 200)));
    else if (!problem.empty())
        s.error("path", fmt::format("samples.path = \"{}\": {}", printableExcerpt(p, 200), problem));
    return path;
}

// path = ["n55w004.hgt", "n55w003.hgt", ...]: raster tiles of one DEM.
void readTiles(Section& s, const SceneFile& f, const toml::array& list, SamplesSpec& samples) {
    s.markKnown("path");
    constexpr size_t kMaxTiles = 10000;  // geo::kMaxTiles
    if (list.empty() || list.size() > kMaxTiles || !list.is_homogeneous(toml::node_type::string)) {
        s.error("path", fmt::format("samples.path must be a file, or a list of 1 to {} raster tiles as strings "
                                    "(path = [\"a.tif\", \"b.tif\"])",
                                    kMaxTiles));
        return;
    }
    for (const auto& tile : list)
        samples.tiles.push_back(samplesFile(s, f, *tile.value<std::string>(), samples.pathAsWritten));
    samples.path = samples.tiles.front();
    if (samples.tiles.size() == 1) samples.tiles.clear();
}

}  // namespace

void readSamples(Section& s, const SceneFile& f, SceneSpec& scene) {
    SamplesSpec& samples = scene.samples;
    if (!s.present()) {
        f.diags.error({f.name, 0, 0}, "missing section [samples]: give path = \"dem.tif\" (any raster GDAL "
                                      "reads) or \"data.csv\" (columns lon,lat,elev)");
    } else {
        s.require("path", "the elevations: a raster GDAL reads or a CSV of samples (columns "
                          "lon,lat,elev), relative to the scene file");
        if (const toml::node* list = s.find("path"); list && list->is_array())
            readTiles(s, f, *list->as_array(), samples);
        else if (auto p = s.string("path"))
            samples.path = samplesFile(s, f, *p, samples.pathAsWritten, true);
    }
    if (auto a = s.text("attribution")) samples.attribution = *a;
    if (auto e = s.choice("elevations", {"earth", "any"})) samples.earthElevations = *e == "earth";
    if (auto b = s.integer("band", 1, 65535, "(1 = the first band)")) samples.band = *b;
    if (auto c = s.string("crs")) samples.crs = *c;
    if (auto r = s.named<Resample>("resample")) samples.resample = *r;
    if (auto u = s.choice("vertical_unit", {"m", "ft", "us-ft"})) samples.verticalUnit = *u;
    if (auto n = s.named<NodataPolicy>("nodata")) samples.nodata = *n;
}

void readFrame(Section& s, const SceneFile&, SceneSpec& scene) {
    if (auto k = s.named<FrameKind>("kind")) scene.frame.kind = *k;
    if (auto z = s.string("zone")) {
        scene.frame.utmZone = *z;
        if (scene.frame.kind != FrameKind::Utm)
            s.error("zone", "frame.zone is only used with kind = \"utm\"; remove it");
    }
}

namespace {

// net.rows and net.cols, or net.spacing_m; 64 x 64 nodes when neither.
void readNetSize(Section& s, const SceneFile& f, NetSpec& net) {
    auto rows = s.integer("rows", 4, 100000, "nodes");
    auto cols = s.integer("cols", 4, 100000, "nodes");
    auto spacing = s.number("spacing_m", 0, 1e7, "m", true);
    if (spacing && (s.find("rows") || s.find("cols"))) {
        s.error("spacing_m", "give either net.spacing_m or net.rows and net.cols, not both");
    } else if (spacing) {
        net.spacingM = *spacing;
    } else if (rows && cols) {
        net.rows = *rows;
        net.cols = *cols;
    } else if (s.find("rows") || s.find("cols")) {
        if (!s.find("rows") || !s.find("cols")) f.diags.error(s.loc(), "net: give both rows and cols (or spacing_m alone)");
    } else {
        net.rows = 64;  // default: 64 x 64 nodes over the samples' extent
        net.cols = 64;
    }
}

}  // namespace

void readNet(Section& s, const SceneFile& f, SceneSpec& scene) {
    NetSpec& net = scene.net;
    readNetSize(s, f, net);
    if (auto e = s.box("extent_m", "[xmin, ymin, xmax, ymax] in metres")) {
        if (!((*e)[2] > (*e)[0] && (*e)[3] > (*e)[1]))
            s.error("extent_m", "net.extent_m needs xmin < xmax and ymin < ymax (metres)");
        else
            net.extentM = FrameBox{(*e)[0], (*e)[1], (*e)[2], (*e)[3]};
    }
    if (auto box = s.box("extent_lonlat", "[lon_min, lat_min, lon_max, lat_max] in WGS84 degrees")) {
        const auto& w = *box;
        if (!(w[2] > w[0] && w[3] > w[1] && w[0] >= -180 && w[2] <= 180 && w[1] >= -90 && w[3] <= 90))
            s.error("extent_lonlat", "net.extent_lonlat needs -180 <= lon_min < lon_max <= 180 and "
                                     "-90 <= lat_min < lat_max <= 90 (degrees)");
        else if (s.find("extent_m"))
            s.error("extent_lonlat", "give either net.extent_m or net.extent_lonlat, not both");
        else
            net.extentLonLat = LonLatBox{w[0], w[1], w[2], w[3]};
    }
    if (auto g = s.named<Gridding>("gridding")) net.gridding = *g;
    if (auto v = s.number("smoothing", 0, 1e6, "(the penalty's weight: 0 fits the samples as closely as the net can)"))
        net.smoothing = *v;
    if (net.smoothing && net.gridding != Gridding::Fit)
        s.error("smoothing", "net.smoothing weighs a fit: it needs net.gridding = \"fit\"");
    if (auto v = s.number("tension", 0, 100, "(the membrane's pull against the thin plate, per mean sample spacing: 0 none)"))
        net.tension = *v;
    if (net.tension && net.gridding != Gridding::Fit)
        s.error("tension", "net.tension pulls a fit: it needs net.gridding = \"fit\"");
    if (auto u = s.named<Unsupported>("unsupported")) net.unsupported = *u;
    if (s.find("unsupported") && net.gridding != Gridding::Fit)
        s.error("unsupported", "net.unsupported says what becomes of the nodes a fit's samples do not reach: it "
                               "needs net.gridding = \"fit\"");
    if (auto v = s.boolean("fit")) net.fit = *v;
    if (net.fit && net.gridding == Gridding::Fit)
        s.error("fit", "net.fit = true prefilters a net so that the surface passes through it; net.gridding = "
                       "\"fit\" already fits the surface to the samples: give one of them");
}

namespace {

// subdivision.depth: levels, or "auto" with tolerance_m.
void readDepth(Section& s, const SceneFile& f, SubdivisionSpec& sub) {
    if (const toml::node* d = s.find("depth"); d && d->value_exact<std::string>()) {
        s.markKnown("depth");
        if (*d->value_exact<std::string>() == "auto")
            sub.depthAuto = true;
        else
            s.error("depth", fmt::format("subdivision.depth must be an integer number of levels in "
                                         "[0, {}] or \"auto\" (with tolerance_m)",
                                         kMaxDepth));
    } else if (auto n = s.integer("depth", 0, kMaxDepth, "levels")) {
        sub.depth = *n;
        sub.depthGiven = true;
    }
    if (auto t = s.number("tolerance_m", 0, 1e6, "m", true)) sub.toleranceM = *t;
    if (sub.depthAuto && sub.toleranceM <= 0 && !s.find("tolerance_m"))
        s.error("depth", "subdivision.depth = \"auto\" needs subdivision.tolerance_m, the "
                         "largest change in metres one more level may make (e.g. "
                         "tolerance_m = 1)");
    if (!sub.depthAuto && s.find("tolerance_m"))
        f.diags.warning(s.keyLoc("tolerance_m"), "subdivision.tolerance_m is ignored: it is used "
                                                 "only with depth = \"auto\"");
}

// scheme = "mask": its coefficients, arity and first exponent (checked by subdiv::resolveScheme).
void readMask(Section& s, const SceneFile& f, SchemeSpec& scheme) {
    if (auto a = s.integer("arity", 2, 3, "(2 = binary, 3 = ternary)")) scheme.maskArity = *a;
    if (auto first = s.integer("mask_first", -1000, 1000, "(exponent of the first coefficient)"))
        scheme.maskFirst = *first;
    s.markKnown("mask");
    if (const toml::node* m = s.find("mask")) {
        const toml::array* a = m->as_array();
        bool ok = a && !a->empty();
        const bool tooLong = ok && a->size() > kMaxMaskCoefficients;  // kept out of the scheme's analysis
        for (size_t i = 0; ok && !tooLong && i < a->size(); ++i) {
            std::optional<double> v = (*a)[i].value<double>();
            if (!v)
                if (auto str = (*a)[i].value_exact<std::string>()) v = parseFraction(*str);
            if (v && std::isfinite(*v)) scheme.mask.push_back(*v);
            else ok = false;
        }
        if (!ok)
            s.error("mask", "subdivision.mask must be a list of numbers or fractions (the "
                            "coefficients a_k of the scheme's symbol)");
        else if (tooLong)
            s.error("mask", fmt::format("subdivision.mask has {} coefficients, more than the {} a scheme's mask "
                                        "may have (its smoothness analysis grows as the cube of the length)",
                                        a->size(), kMaxMaskCoefficients));
    }
    if (scheme.name != "mask" && (s.find("mask") || s.find("arity") || s.find("mask_first")))
        f.diags.error(s.keyLoc(s.find("mask") ? "mask" : s.find("arity") ? "arity" : "mask_first"),
                      "subdivision.mask, arity and mask_first are only used with scheme = \"mask\"");
}

// Every other key is one of the scheme's parameters, a number or a fraction;
// the scheme (subdiv::resolveScheme) says which it takes.
void readSchemeParameters(Section& s, const SceneFile& f, SubdivisionSpec& sub) {
    static const std::set<std::string> kOwnKeys = {"scheme", "depth",      "tolerance_m", "preset",
                                                   "mask",   "arity",      "mask_first",  "allow_nonconvergent"};
    if (!s.table()) return;
    for (auto&& [k, v] : *s.table()) {
        const std::string key(k.str());
        if (kOwnKeys.count(key)) continue;
        s.markKnown(key);
        // A parameter is reported at its key, not its value: the value may be fine and the name wrong.
        sub.locs.keys["subdivision." + key] = locOf(f.name, k.source());
        std::optional<double> value;
        if (auto i = v.value_exact<int64_t>()) value = static_cast<double>(*i);
        else if (auto d = v.value_exact<double>()) value = *d;
        else if (auto str = v.value_exact<std::string>()) value = parseFraction(*str);
        if (!value || !std::isfinite(*value)) {
            f.diags.error(locOf(f.name, v.source()),
                          fmt::format("subdivision.{} must be a number or a fraction such as \"7/32\"", key));
            continue;
        }
        sub.scheme.params[key] = *value;
    }
}

}  // namespace

void readSubdivision(Section& s, const SceneFile& f, SceneSpec& scene) {
    SubdivisionSpec& sub = scene.subdivision;
    SchemeSpec& scheme = sub.scheme;
    if (auto n = s.string("scheme")) scheme.name = *n;
    else if (s.find("preset")) scheme.name = "";  // the preset names the scheme
    readDepth(s, f, sub);
    if (auto p = s.string("preset")) scheme.preset = *p;
    if (auto b = s.boolean("allow_nonconvergent")) scheme.allowNonconvergent = *b;
    readMask(s, f, scheme);
    readSchemeParameters(s, f, sub);
    scheme.locs = sub.locs;
}

void readLimits(Section& s, const SceneFile&, SceneSpec& scene) {
    LimitsSpec& limits = scene.limits;
    if (auto v = s.number("max_triangles", 1, 1e10, "triangles")) limits.maxTriangles = *v;
    if (auto v = s.number("max_sdl_mb", 0.001, 1e6, "MB")) limits.maxSdlMB = *v;
    if (auto v = s.number("max_parse_s", 0.001, 1e6, "s")) limits.maxParseS = *v;
    if (auto v = s.number("max_memory_mb", 1, 1e9, "MB")) limits.maxMemoryMB = *v;
    if (auto v = s.number("max_film_s", 0, 1e9, "s")) limits.maxFilmS = *v;
    if (auto v = s.number("max_layer_vertices", 1, 1e9, "vertices")) limits.maxLayerVertices = *v;
}

void readGeometry(Section& s, const SceneFile&, SceneSpec& scene) {
    if (auto k = s.named<GeometryKind>("kind")) scene.geometry.kind = *k;
    if (auto v = s.number("tolerance_px", 0, 100, "pixels", true)) scene.geometry.tolerancePx = *v;
    if (auto v = s.number("tolerance_m", 0, 1e4, "metres", true)) scene.geometry.toleranceM = *v;
}

namespace {

// render.output: a PNG inside the current folder (-o writes anywhere).
void readOutput(Section& s, RenderSpec& render) {
    const auto v = s.string("output");
    if (!v) return;
    const std::filesystem::path out(*v);
    const bool climbs = std::any_of(out.begin(), out.end(), [](const auto& part) { return part == ".."; });
    const std::string extension = asciiLower(out.extension().string());
    if (out.stem().empty() || (extension != ".png" && extension != ".pdf" && extension != ".svg"))
        s.error("output", fmt::format("render.output = \"{}\" must name a .png, .pdf or .svg file",
                                      printableExcerpt(*v, 200)));
    else if (out.is_absolute() || climbs)
        // A scene from elsewhere must not choose where on the disk it writes; -o can.
        s.error("output", fmt::format("render.output = \"{}\" must stay inside the current folder (no "
                                      "leading /, no ..); give -o to write anywhere else",
                                      printableExcerpt(*v, 200)));
    else
        render.output = *v;
}

}  // namespace

void readRender(Section& s, const SceneFile&, SceneSpec& scene) {
    RenderSpec& render = scene.render;
    if (auto v = s.integer("width", 16, 16384, "pixels")) render.width = *v;
    if (auto v = s.integer("height", 16, 16384, "pixels")) render.height = *v;
    if (auto v = s.boolean("antialias")) render.antialias = *v;
    if (auto q = s.named<Quality>("quality")) render.quality = *q;
    if (auto v = s.number("timeout_s", 0, 1e7, "seconds (0: no limit)")) render.timeoutS = *v;
    if (auto v = s.number("dpi", 1, 4800, "dots an inch")) render.dpi = *v;
    if (auto v = s.string("background")) {
        if (*v == "sky") render.background = Background::Sky;
        else if (*v == "transparent") render.background = Background::Transparent;
        else if (parseHexColor(*v, render.backgroundColour)) render.background = Background::Colour;
        else
            s.error("background", fmt::format("render.background = \"{}\" must be \"sky\", \"transparent\" "
                                              "or a colour \"#rrggbb\"",
                                              printableExcerpt(*v)));
    }
    readOutput(s, render);
}

}  // namespace relief::scene
