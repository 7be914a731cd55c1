#include "plan/plan.h"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <mutex>
#include <set>

#include <fmt/format.h>

#include "core/atomic_file.h"
#include "core/hash.h"
#include "core/utf8_record.h"
#include "core/input_file.h"
#include "core/text_escape.h"
#include "relief/version.h"

namespace relief::plan {

namespace fs = std::filesystem;
using nlohmann::ordered_json;

namespace {

constexpr int kPlanFormat = 9;  // 9: the overlay spec and facts hold a map frame
constexpr std::uintmax_t kMaxPlanBytes = 64'000'000;
// A template folder holds a template and its #include files: a few kB.
constexpr size_t kMaxTemplateFiles = 64;
constexpr std::uintmax_t kMaxTemplateFolderBytes = 16'000'000;
// What ordered_json's dump writes for a byte that is not UTF-8 (U+FFFD): a
// record is UTF-8 whatever names it holds.
constexpr auto kReplace = nlohmann::json::error_handler_t::replace;

ordered_json coloursJson(const std::vector<LinearRgb>& colours) {
    ordered_json a = ordered_json::array();
    for (const auto& c : colours) a.push_back({c.r, c.g, c.b});
    return a;
}
std::vector<LinearRgb> coloursOf(const ordered_json& a) {
    std::vector<LinearRgb> out;
    for (const auto& c : a) out.push_back({c.at(0).get<double>(), c.at(1).get<double>(), c.at(2).get<double>()});
    return out;
}

ordered_json labelsJson(const std::vector<annotate::LabelFact>& labels) {
    ordered_json a = ordered_json::array();
    for (const auto& l : labels)
        a.push_back({{"text", l.text}, {"x", l.anchor.x}, {"y", l.anchor.y}, {"marker_px", l.markerPx},
                     {"ground_y", l.groundY}, {"size_px", l.sizePx}, {"layer", l.layer}});
    return a;
}
std::vector<annotate::LabelFact> labelsOf(const ordered_json& a) {
    std::vector<annotate::LabelFact> out;
    for (const auto& l : a)
        out.push_back({l.at("text").get<std::string>(), {l.at("x").get<double>(), l.at("y").get<double>()},
                       l.at("marker_px").get<double>(), l.at("ground_y").get<double>(), l.at("size_px").get<double>(),
                       l.at("layer").get<int>()});
    return out;
}

ordered_json legendJson(const std::vector<annotate::LegendEntry>& entries) {
    ordered_json a = ordered_json::array();
    for (const auto& e : entries) {
        ordered_json j = {{"text", e.text},
                          {"kind", static_cast<int>(e.kind)},
                          {"colour", coloursJson({e.colour})[0]},
                          {"fill_opacity", e.fillOpacity},
                          {"width_px", e.widthPx},
                          {"dashed", e.dashed}};
        if (e.fill) j["fill"] = coloursJson({*e.fill})[0];
        a.push_back(j);
    }
    return a;
}
std::vector<annotate::LegendEntry> legendOf(const ordered_json& a) {
    std::vector<annotate::LegendEntry> out;
    for (const auto& j : a) {
        annotate::LegendEntry e;
        e.text = j.at("text").get<std::string>();
        const int kind = j.at("kind").get<int>();
        if (kind < 0 || kind > 2) throw nlohmann::json::other_error::create(501, "a legend entry's kind", nullptr);
        e.kind = static_cast<annotate::LegendEntry::Kind>(kind);
        e.colour = coloursOf(ordered_json::array({j.at("colour")}))[0];
        if (j.contains("fill")) e.fill = coloursOf(ordered_json::array({j.at("fill")}))[0];
        e.fillOpacity = j.at("fill_opacity").get<double>();
        e.widthPx = j.at("width_px").get<double>();
        e.dashed = j.at("dashed").get<bool>();
        out.push_back(e);
    }
    return out;
}

ordered_json mapFrameJson(const annotate::MapFrame& m) {
    ordered_json ticks = ordered_json::array();
    for (const auto& t : m.ticks) ticks.push_back({{"side", static_cast<int>(t.side)}, {"px", t.px}, {"label", t.label}});
    return {{"map", {m.map.x0, m.map.y0, m.map.x1, m.map.y1}}, {"ticks", ticks}};
}
annotate::MapFrame mapFrameOf(const ordered_json& j) {
    annotate::MapFrame m;
    const auto bad = [](const char* what) { return nlohmann::json::other_error::create(501, what, nullptr); };
    const auto box = j.at("map").get<std::array<double, 4>>();
    if (!std::all_of(box.begin(), box.end(), [](double v) { return std::isfinite(v); })) throw bad("a map frame's box");
    m.map = {box[0], box[1], box[2], box[3]};
    // Each side has a few dozen ticks at most (five annotations, five ticks each): a plan's thousands are forged.
    if (j.at("ticks").size() > 1000) throw bad("a map frame of more than 1000 ticks");
    for (const auto& t : j.at("ticks")) {
        const int side = t.at("side").get<int>();
        const double px = t.at("px").get<double>();
        if (side < 0 || side > 3 || !std::isfinite(px)) throw bad("a map frame's tick");
        m.ticks.push_back({static_cast<annotate::MapFrame::Side>(side), px, t.at("label").get<std::string>()});
    }
    return m;
}

ordered_json overlayJson(const RenderPlan& p) {
    const scene::OverlaySpec& s = p.overlaySpec;
    const annotate::OverlayFacts& f = p.overlayFacts;
    ordered_json spec = {{"enabled", static_cast<int>(s.enabled)}, {"title", s.title}, {"subtitle", s.subtitle},
                         {"legend", s.legend}, {"scale_bar", s.scaleBar}, {"north_arrow", s.northArrow}};
    if (s.credits) spec["credits"] = *s.credits;
    spec["places"] = s.places;
    spec["text_scale"] = s.textScale;
    spec["legend_title"] = s.legendTitle;
    spec["legend_feet"] = s.legendFeet;
    spec["scale_bar_imperial"] = s.scaleBarImperial;
    if (s.scaleBarUnit)
        spec["scale_bar_length"] = {{"length", s.scaleBarLength}, {"unit", s.scaleBarUnit->name},
                                    {"metres", s.scaleBarUnit->metres}};
    spec["frame"] = s.frame;
    spec["frame_metres"] = s.frameMetres;
    ordered_json facts = {
        {"credits", f.credits},
        {"map_furniture", f.mapFurniture},
        {"palette", coloursJson(f.palette)},
        {"z_min_m", f.zMinM},
        {"z_max_m", f.zMaxM},
        {"legend_title", f.legendTitle},
        {"legend_note", f.legendNote},
        {"exaggeration", f.exaggeration},
        {"metres_per_pixel", f.metresPerPixel},
        {"perspective", f.perspective},
        {"north_deg", f.northDeg},
        {"terrain", {{"band_px", f.terrain.bandPx}, {"top", f.terrain.top}, {"bottom", f.terrain.bottom}}},
        {"labels", labelsJson(f.labels)},
        {"layer_legend", legendJson(f.layerLegend)}};
    if (f.mapFrame) facts["map_frame"] = mapFrameJson(*f.mapFrame);
    return {{"drawn", p.overlays}, {"spec", spec}, {"facts", facts}};
}

void readOverlay(const ordered_json& j, RenderPlan& p) {
    p.overlays = j.at("drawn").get<bool>();
    const auto& s = j.at("spec");
    p.overlaySpec.enabled = static_cast<scene::OverlaySpec::Enabled>(s.at("enabled").get<int>());
    p.overlaySpec.title = s.at("title").get<std::string>();
    p.overlaySpec.subtitle = s.at("subtitle").get<std::string>();
    p.overlaySpec.legend = s.at("legend").get<bool>();
    p.overlaySpec.scaleBar = s.at("scale_bar").get<bool>();
    p.overlaySpec.northArrow = s.at("north_arrow").get<bool>();
    if (s.contains("credits")) p.overlaySpec.credits = s.at("credits").get<std::string>();
    for (const auto& [item, where] : s.at("places").items()) {
        const auto known = [](const std::vector<std::string>& names, const std::string& name) {
            return std::find(names.begin(), names.end(), name) != names.end();
        };
        if (!known(scene::kFurnitureItems, item) || !known(scene::kFurniturePlaces, where.get<std::string>()))
            throw nlohmann::json::other_error::create(501, "an overlay place relief does not know", nullptr);
        if (where.get<std::string>() != "auto") p.overlaySpec.places[item] = where.get<std::string>();
    }
    p.overlaySpec.textScale = s.at("text_scale").get<double>();
    if (!(p.overlaySpec.textScale >= 0.5 && p.overlaySpec.textScale <= 3))
        throw nlohmann::json::other_error::create(501, "an overlay text scale outside 0.5 to 3", nullptr);
    p.overlaySpec.legendTitle = s.at("legend_title").get<std::string>();
    p.overlaySpec.legendFeet = s.at("legend_feet").get<bool>();
    p.overlaySpec.scaleBarImperial = s.at("scale_bar_imperial").get<bool>();
    p.overlaySpec.frame = s.at("frame").get<bool>();
    p.overlaySpec.frameMetres = s.at("frame_metres").get<bool>();
    if (s.contains("scale_bar_length")) {
        const auto& b = s.at("scale_bar_length");
        p.overlaySpec.scaleBarUnit = scene::LengthUnit{b.at("unit").get<std::string>(), b.at("metres").get<double>()};
        p.overlaySpec.scaleBarLength = b.at("length").get<double>();
        if (!(p.overlaySpec.scaleBarLength > 0 && p.overlaySpec.scaleBarLength <= 1e7 &&
              p.overlaySpec.scaleBarUnit->metres > 0 && p.overlaySpec.scaleBarUnit->metres <= 1e4))
            throw nlohmann::json::other_error::create(501, "a scale bar's length out of range", nullptr);
    }
    const auto& f = j.at("facts");
    annotate::OverlayFacts& o = p.overlayFacts;
    o.credits = f.at("credits").get<std::string>();
    o.mapFurniture = f.at("map_furniture").get<bool>();
    o.palette = coloursOf(f.at("palette"));
    o.zMinM = f.at("z_min_m").get<double>();
    o.zMaxM = f.at("z_max_m").get<double>();
    o.legendTitle = f.at("legend_title").get<std::string>();
    o.legendNote = f.at("legend_note").get<std::string>();
    o.exaggeration = f.at("exaggeration").get<double>();
    o.metresPerPixel = f.at("metres_per_pixel").get<double>();
    o.perspective = f.at("perspective").get<bool>();
    o.northDeg = f.at("north_deg").get<double>();
    o.terrain.bandPx = f.at("terrain").at("band_px").get<double>();
    o.terrain.top = f.at("terrain").at("top").get<std::vector<double>>();
    o.terrain.bottom = f.at("terrain").at("bottom").get<std::vector<double>>();
    o.labels = labelsOf(f.at("labels"));
    o.layerLegend = legendOf(f.at("layer_legend"));
    if (f.contains("map_frame")) o.mapFrame = mapFrameOf(f.at("map_frame"));
}

ordered_json fileJson(const PlanFile& f) {
    ordered_json j;
    putName(j, "name", f.name);
    j["role"] = f.role;
    j["sha256"] = f.sha256;
    return j;
}
PlanFile fileOf(const ordered_json& j) {
    return {nameAt(j, "name"), {}, j.at("role").get<std::string>(), j.at("sha256").get<std::string>()};
}
ordered_json filesJson(const std::vector<PlanFile>& files) {
    ordered_json a = ordered_json::array();
    for (const auto& f : files) a.push_back(fileJson(f));
    return a;
}
std::vector<PlanFile> filesOf(const ordered_json& a) {
    std::vector<PlanFile> out;
    for (const auto& f : a) out.push_back(fileOf(f));
    return out;
}

// Everything but the hash, in one order: what the hash is taken over. Each
// file is in it by its SHA-256; the outputs by their file names only (a plan
// read back writes them beside its folder); nothing says whether POV-Ray runs
// sandboxed (the command that runs it does) or names a folder outside.
ordered_json planJson(const RenderPlan& p) {
    ordered_json outputs;
    putName(outputs, "still", p.still.filename().string());
    putName(outputs, "sidecar", p.sidecar.filename().string());
    return {{"relief_plan", kPlanFormat},
            {"relief_version", p.reliefVersion},
            {"povray_version", p.povrayVersion},
            {"pov", fileJson(p.pov)},
            {"reads", filesJson(p.reads)},
            {"extras", filesJson(p.extras)},
            {"templates", filesJson(p.templates)},
            {"render",
             {{"width", p.width},
              {"height", p.height},
              {"tiles", p.tiles},
              {"antialias", p.antialias},
              {"antialias_threshold", p.antialiasThreshold},
              {"antialias_depth", p.antialiasDepth},
              {"alpha", p.alpha},
              {"timeout_s", p.timeoutS},
              {"dpi", p.dpi}}},
            {"outputs", outputs},
            {"overlay", overlayJson(p)},
            {"sidecar_so_far", p.sidecar0}};
}

// Calls fn(file, its path) for each of the plan's files (const or not).
template <class Plan, class Fn>
void forEachFile(Plan& p, Fn fn) {
    fn(p.pov, p.dir / p.pov.name);
    for (auto& f : p.reads) fn(f, p.dir / f.name);
    for (auto& f : p.extras) fn(f, p.dir / f.name);
    for (auto& f : p.templates) fn(f, p.dir / "templates" / f.name);
}

bool plainName(const std::string& n) {
    return !n.empty() && n != "." && n != ".." && n.find('/') == std::string::npos && n.find('\0') == std::string::npos;
}

std::string hostName() {
    char buf[256] = {};
    return ::gethostname(buf, sizeof buf - 1) == 0 ? buf : "?";
}

}  // namespace

TileRows tileRows(int height, int tiles, int index) {
    tiles = std::clamp(tiles, 1, std::max(1, height));
    const long first = static_cast<long>(index) * height / tiles, next = static_cast<long>(index + 1) * height / tiles;
    return {static_cast<int>(first) + 1, static_cast<int>(next)};
}

std::string planFieldsHash(const ordered_json& fields) {
    Sha256 h;
    h.add(fields.dump(-1, ' ', false, kReplace));
    return h.hex();
}

void copyTemplates(RenderPlan& plan, const fs::path& templatesDir) {
    plan.templates.clear();
    if (templatesDir.empty()) return;
    makeOwnFolder(plan.dir / "templates");
    std::error_code ec;
    std::vector<fs::path> files;
    for (const auto& e : fs::directory_iterator(templatesDir, ec))
        if (e.is_regular_file(ec) && !e.is_symlink(ec)) files.push_back(e.path());
    if (ec) throw OutputError(templatesDir, "cannot be listed as the templates folder: " + ec.message());
    std::sort(files.begin(), files.end());
    std::uintmax_t bytes = 0;
    for (const auto& f : files) bytes += fs::file_size(f, ec);
    if (files.size() > kMaxTemplateFiles || bytes > kMaxTemplateFolderBytes)
        throw OutputError(templatesDir, fmt::format("holds {} files, {}: more than a template and its #include "
                                                    "files ({} files, {}); give --templates a folder of them alone",
                                                    files.size(), byteSize(bytes), kMaxTemplateFiles,
                                                    byteSize(kMaxTemplateFolderBytes)));
    for (const auto& f : files) {
        if (const std::string error = copyFileContents(f, plan.dir / "templates" / f.filename()); !error.empty())
            throw OutputError(plan.dir / "templates" / f.filename(), "cannot be written: " + error);
        plan.templates.push_back({f.filename().string(), {}, "a template file", ""});
    }
}

bool writePlan(RenderPlan& plan, Diagnostics& diags) {
    plan.reliefVersion = kVersion;
    bool read = true;
    forEachFile(plan, [&](PlanFile& f, const fs::path& at) {
        std::string problem;
        if (f.sha256.empty() && read) f.sha256 = fileSha256(at, problem);  // a film's shared files come hashed
        if (!problem.empty()) diags.error({at.string(), 0, 0}, "the plan's file cannot be read: " + problem);
        read = read && problem.empty();
    });
    if (!read) return false;
    const ordered_json fields = planJson(plan);
    plan.hash = planFieldsHash(fields);
    ordered_json j = fields;
    j["hash"] = plan.hash;
    try {
        writeFileAtomically(plan.dir / "plan.json", j.dump(1, ' ', false, kReplace) + "\n");
    } catch (const OutputError& e) {
        diags.error(e.at(), e.problem());
        return false;
    }
    return true;
}

namespace {

// The sizes the overlay draws at, as a scene can give them (a plan is untrusted: a huge dpi or font
// would overflow the PNG's resolution or ask Pango for a page of one glyph).
bool overlaySizesSane(const RenderPlan& p) {
    const auto within = [](double v, double lo, double hi) { return v >= lo && v <= hi; };  // false for NaN
    bool ok = p.dpi == 0 || within(p.dpi, 1, 4800);
    for (const auto& l : p.overlayFacts.labels)
        ok = ok && within(l.sizePx, 1, 1000) && within(l.markerPx, 0, 1000) && within(l.anchor.x, -1e7, 1e7) &&
             within(l.anchor.y, -1e7, 1e7) && within(l.groundY, -1e7, 1e7);
    for (const auto& e : p.overlayFacts.layerLegend)
        ok = ok && within(e.widthPx, 0, 1000) && within(e.fillOpacity, 0, 1);
    return ok;
}

}  // namespace

namespace {

// plan.json's fields into `p` (throws nlohmann's exceptions on a wrong shape).
void readFields(const ordered_json& j, RenderPlan& p) {
    p.reliefVersion = j.at("relief_version").get<std::string>();
    p.povrayVersion = j.at("povray_version").get<std::string>();
    p.hash = j.at("hash").get<std::string>();
    p.pov = fileOf(j.at("pov"));
    p.reads = filesOf(j.at("reads"));
    p.extras = filesOf(j.at("extras"));
    p.templates = filesOf(j.at("templates"));
    const auto& r = j.at("render");
    p.width = r.at("width").get<int>();
    p.height = r.at("height").get<int>();
    p.tiles = r.at("tiles").get<int>();
    p.antialias = r.at("antialias").get<bool>();
    p.antialiasThreshold = r.at("antialias_threshold").get<double>();
    p.antialiasDepth = r.at("antialias_depth").get<int>();
    p.alpha = r.at("alpha").get<bool>();
    p.timeoutS = r.at("timeout_s").get<double>();
    p.dpi = r.at("dpi").get<double>();
    // The outputs beside the plan's folder, whatever it was planned beside.
    const fs::path beside = p.dir.parent_path();
    p.still = beside / nameAt(j.at("outputs"), "still");
    p.sidecar = beside / nameAt(j.at("outputs"), "sidecar");
    p.pov.final = beside / p.pov.name;
    for (auto* files : {&p.reads, &p.extras})
        for (auto& f : *files) f.final = beside / f.name;
    readOverlay(j.at("overlay"), p);
    p.sidecar0 = j.at("sidecar_so_far");
}

// Names that are plain file names, each once, none of the plan's own (plan.json, tiles/, ...).
bool namesSane(const RenderPlan& p) {
    static const std::set<std::string> own{"plan.json", "lock", "tiles", "templates", "slurm"};
    std::set<std::string> seen;
    bool ok = true;
    for (const auto* files : {&p.reads, &p.extras}) {
        for (const auto& f : *files) ok = ok && plainName(f.name) && !own.count(f.name) && seen.insert(f.name).second;
    }
    ok = ok && plainName(p.pov.name) && !own.count(p.pov.name) && seen.insert(p.pov.name).second;
    std::set<std::string> templates;
    for (const auto& f : p.templates) ok = ok && plainName(f.name) && templates.insert(f.name).second;
    const std::string still = asciiLower(p.still.extension().string());
    const fs::path beside = p.dir.parent_path();
    return ok && plainName(p.still.filename().string()) && plainName(p.sidecar.filename().string()) &&
           p.still.parent_path() == beside && p.sidecar.parent_path() == beside && p.still != p.sidecar &&
           (still == ".png" || still == ".pdf" || still == ".svg") && asciiLower(p.sidecar.extension().string()) == ".json";
}

// The still's size and POV-Ray's options within what a scene can give ([render]'s ranges).
bool sizesSane(const RenderPlan& p) {
    const auto within = [](double v, double lo, double hi) { return v >= lo && v <= hi; };  // false for NaN
    return within(p.width, 16, 16384) && within(p.height, 16, 16384) && within(p.tiles, 1, p.height) &&
           within(p.antialiasThreshold, 0, 3) && within(p.antialiasDepth, 1, 9) && within(p.timeoutS, 0, 1e7) &&
           within(static_cast<int>(p.overlaySpec.enabled), 0, 2) && overlaySizesSane(p);
}

// Every file the plan lists: a plain file in its folder with the SHA-256 it was planned with.
bool filesAsPlanned(const RenderPlan& p, Diagnostics& diags) {
    bool ok = true;
    forEachFile(p, [&](const PlanFile& f, const fs::path& at) {
        if (!ok) return;
        std::string problem;
        const std::string sha = fileSha256(at, problem);
        if (!problem.empty())
            diags.error({at.string(), 0, 0}, problem == "no such file"
                                                 ? "the plan's file is missing: make the plan again"
                                                 : "the plan's file cannot be used: " + problem);
        else if (sha != f.sha256)
            diags.error({at.string(), 0, 0}, "differs from the file the plan was made with (its SHA-256 is not the one "
                                             "plan.json holds): make the plan again");
        ok = problem.empty() && sha == f.sha256;
    });
    return ok;
}

}  // namespace

std::optional<RenderPlan> readPlan(const fs::path& dir, Diagnostics& diags) {
    const fs::path file = dir / "plan.json";
    const SourceLoc at{file.string(), 0, 0};
    std::string problem;
    const auto text = readInputFile(file, kMaxPlanBytes, problem);
    if (!text) {
        diags.error(at, problem == "no such file"
                            ? "no render plan here: the plan's folder must be on a filesystem this machine sees"
                            : "cannot read the render plan: " + problem);
        return std::nullopt;
    }
    RenderPlan p;
    p.dir = fs::absolute(dir).lexically_normal();
    if (!p.dir.has_filename()) p.dir = p.dir.parent_path();  // "x.plan/": the folder x.plan
    try {
        ordered_json j = ordered_json::parse(*text);
        if (j.at("relief_plan").get<int>() != kPlanFormat) {
            diags.error(at, "a render plan of another format: make it again with this relief");
            return std::nullopt;
        }
        if (const auto made = j.at("relief_version").get<std::string>(); made != kVersion) {
            diags.error(at, fmt::format("a render plan made by relief {}, and this is relief {}: make it again with "
                                        "this relief, or use the one that made it",
                                        terminalText(made, 40), kVersion));
            return std::nullopt;
        }
        readFields(j, p);
        j.erase("hash");
        if (planFieldsHash(j) != p.hash) {
            diags.error(at, "the render plan was changed after relief wrote it (its fields do not give the hash it "
                            "holds): make it again");
            return std::nullopt;
        }
    } catch (const nlohmann::json::exception&) {
        diags.error(at, "the render plan is damaged (not the JSON relief writes): make it again");
        return std::nullopt;
    }
    if (!namesSane(p) || !sizesSane(p)) {
        diags.error(at, "the render plan is damaged (its files or sizes are not a plan's): make it again");
        return std::nullopt;
    }
    if (!filesAsPlanned(p, diags)) return std::nullopt;
    return p;
}

bool checkRenderable(const RenderPlan& plan, Diagnostics& diags) {
    const std::string here = povrayVersion();
    if (here == plan.povrayVersion) return true;
    diags.error({(plan.dir / "plan.json").string(), 0, 0},
                fmt::format("the plan was made for POV-Ray {}, and {} has {}: install that POV-Ray here, or render "
                            "the plan where it is",
                            terminalText(plan.povrayVersion, 40), terminalText(hostName(), 60),
                            here.empty() ? std::string("none") : "POV-Ray " + here));
    return false;
}

std::string nodeName() {
    const char* slurm = std::getenv("SLURMD_NODENAME");
    return slurm && *slurm ? slurm : hostName();
}

std::vector<std::string> tileNodes(const RenderPlan& plan) {
    std::vector<std::string> nodes;
    for (int k = 0; k < plan.tiles; ++k) {
        std::string problem;
        if (const auto r = readTileRecord(plan, k, problem)) nodes.push_back(r->node);
    }
    return nodes;
}

fs::path tileImage(const RenderPlan& plan, int index) {
    return plan.dir / "tiles" / fmt::format("tile-{:04}.png", index);
}
fs::path tileRecordPath(const RenderPlan& plan, int index) {
    return plan.dir / "tiles" / fmt::format("tile-{:04}.json", index);
}

ordered_json tileRecordJson(const TileRecord& r) {
    return {{"tile", r.index},
            {"rows", {r.rows.first, r.rows.last}},
            {"plan_hash", r.planHash},
            {"relief_version", r.reliefVersion},
            {"povray_version", r.povrayVersion},
            {"host", r.host.empty() ? hostName() : r.host},
            {"node", r.node.empty() ? nodeName() : r.node},
            {"seconds", {{"povray_parse", r.parseSeconds}, {"povray_trace", r.traceSeconds}, {"povray_wall", r.wallSeconds}}},
            {"povray_peak_memory_mb", r.peakMemoryMB},
            {"povray_command", r.povrayCommand},
            {"image_sha256", r.imageSha256}};
}

std::optional<TileRecord> readTileRecord(const RenderPlan& plan, int index, std::string& problem) {
    problem = plainFileProblem(tileRecordPath(plan, index));
    const auto text = problem.empty() ? readInputFile(tileRecordPath(plan, index), 1'000'000, problem) : std::nullopt;
    if (!text) return std::nullopt;
    TileRecord r;
    try {
        const ordered_json j = ordered_json::parse(*text);
        r.index = j.at("tile").get<int>();
        r.rows = {j.at("rows").at(0).get<int>(), j.at("rows").at(1).get<int>()};
        r.planHash = j.at("plan_hash").get<std::string>();
        r.reliefVersion = j.at("relief_version").get<std::string>();
        r.povrayVersion = j.at("povray_version").get<std::string>();
        r.host = j.at("host").get<std::string>();
        r.node = j.value("node", r.host);  // a record from before nodes were named: its host
        r.parseSeconds = j.at("seconds").at("povray_parse").get<double>();
        r.traceSeconds = j.at("seconds").at("povray_trace").get<double>();
        r.wallSeconds = j.at("seconds").at("povray_wall").get<double>();
        r.peakMemoryMB = j.at("povray_peak_memory_mb").get<double>();
        r.povrayCommand = j.at("povray_command").get<std::vector<std::string>>();
        r.imageSha256 = j.at("image_sha256").get<std::string>();
    } catch (const nlohmann::json::exception&) {
        problem = "its record is damaged";
        return std::nullopt;
    }
    const TileRows rows = tileRows(plan.height, plan.tiles, index);
    if (r.index != index || r.rows.first != rows.first || r.rows.last != rows.last)
        problem = "its record is of another tile";
    else if (r.planHash != plan.hash)
        problem = fmt::format("it was rendered from another plan ({}, not {})", r.planHash.substr(0, 19),
                              plan.hash.substr(0, 19));
    else if (r.reliefVersion != plan.reliefVersion)
        problem = fmt::format("it was rendered by relief {}, the plan by {}", terminalText(r.reliefVersion, 40),
                              plan.reliefVersion);
    else if (r.povrayVersion != plan.povrayVersion)
        problem = fmt::format("it was rendered by POV-Ray {} on {}, the plan made for {}", terminalText(r.povrayVersion, 40),
                              terminalText(r.host, 60), plan.povrayVersion);
    if (!problem.empty()) return std::nullopt;
    std::string imageProblem;
    const std::string image = fileSha256(tileImage(plan, index), imageProblem);
    if (imageProblem == "no such file")
        problem = "its image is missing";
    else if (!imageProblem.empty())
        problem = "its image cannot be used: " + imageProblem;
    else if (image != r.imageSha256)
        problem = "its image is not the one rendered (its SHA-256 is not the record's): render the tile again";
    if (!problem.empty()) return std::nullopt;
    return r;
}

std::vector<int> missingTiles(const RenderPlan& plan) {
    std::vector<int> out;
    for (int k = 0; k < plan.tiles; ++k) {
        std::string problem;
        if (!readTileRecord(plan, k, problem)) out.push_back(k);
    }
    return out;
}

std::optional<PlanLock> PlanLock::take(const fs::path& dir) {
    Diagnostics unused;
    return take(dir, unused);
}

std::optional<PlanLock> PlanLock::take(const fs::path& dir, Diagnostics& diags) {
    const int fd = ::open((dir / "lock").c_str(), O_RDWR | O_CREAT | O_NOFOLLOW | O_CLOEXEC, 0600);
    if (fd < 0) {
        diags.error({(dir / "lock").string(), 0, 0},
                    fmt::format("cannot be written: {}; relief writes its tiles and its lock in the folder",
                                std::strerror(errno)));
        return std::nullopt;
    }
    struct flock l {};
    l.l_type = F_WRLCK;
    l.l_whence = SEEK_SET;
    if (::fcntl(fd, F_OFD_SETLK, &l) != 0) {
        ::close(fd);
        diags.error({dir.string(), 0, 0}, "another relief is using this folder now: wait for it to end");
        return std::nullopt;
    }
    return PlanLock(fd);
}

PlanLock::~PlanLock() {
    if (fd_ >= 0) ::close(fd_);
}

std::string povrayVersion() {
    static std::once_flag once;
    static std::string version;
    std::call_once(once, [] {
        // "POV-Ray 3.7.0.10.unofficial" on the first line (Debian's build prints it to stderr).
        std::FILE* p = ::popen("povray --version 2>&1", "re");
        if (!p) return;
        char line[256] = {};
        while (std::fgets(line, sizeof line, p)) {
            const std::string_view l(line);
            if (const auto at = l.find("POV-Ray "); at != std::string_view::npos && version.empty()) {
                std::string_view v = l.substr(at + 8);
                v = v.substr(0, v.find_first_of(" \n\r"));
                version = v;
            }
        }
        ::pclose(p);
    });
    return version;
}

}  // namespace relief::plan
