#include "plan/plan.h"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <mutex>

#include <fmt/format.h>

#include "core/atomic_file.h"
#include "core/hash.h"
#include "core/input_file.h"
#include "core/text_escape.h"
#include "relief/version.h"

namespace relief::plan {

namespace fs = std::filesystem;
using nlohmann::ordered_json;

namespace {

constexpr int kPlanFormat = 5;
constexpr std::uintmax_t kMaxPlanBytes = 64'000'000;

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
        a.push_back({{"text", l.text}, {"x", l.x}, {"y", l.y}, {"marker_px", l.markerPx}, {"ground_y", l.groundY},
                     {"size_px", l.sizePx}, {"layer", l.layer}});
    return a;
}
std::vector<annotate::LabelFact> labelsOf(const ordered_json& a) {
    std::vector<annotate::LabelFact> out;
    for (const auto& l : a)
        out.push_back({l.at("text").get<std::string>(), l.at("x").get<double>(), l.at("y").get<double>(),
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

ordered_json overlayJson(const RenderPlan& p) {
    const scene::OverlaySpec& s = p.overlaySpec;
    const annotate::OverlayFacts& f = p.overlayFacts;
    ordered_json spec = {{"enabled", static_cast<int>(s.enabled)}, {"title", s.title}, {"subtitle", s.subtitle},
                         {"legend", s.legend}, {"scale_bar", s.scaleBar}, {"north_arrow", s.northArrow}};
    if (s.credits) spec["credits"] = *s.credits;
    ordered_json facts = {
        {"credits", f.credits},
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
    const auto& f = j.at("facts");
    annotate::OverlayFacts& o = p.overlayFacts;
    o.credits = f.at("credits").get<std::string>();
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
}

ordered_json fileJson(const PlanFile& f) { return {{"name", f.name}, {"final", f.final.string()}, {"role", f.role}}; }
PlanFile fileOf(const ordered_json& j) {
    return {j.at("name").get<std::string>(), j.at("final").get<std::string>(), j.at("role").get<std::string>()};
}

// Everything but the hash, in one order: what the hash is taken over, with the files.
ordered_json planJson(const RenderPlan& p) {
    ordered_json reads = ordered_json::array(), extras = ordered_json::array();
    for (const auto& f : p.reads) reads.push_back(fileJson(f));
    for (const auto& f : p.extras) extras.push_back(fileJson(f));
    return {{"relief_plan", kPlanFormat},
            {"relief_version", p.reliefVersion},
            {"povray_version", p.povrayVersion},
            {"pov", fileJson(p.pov)},
            {"reads", reads},
            {"extras", extras},
            {"render",
             {{"width", p.width},
              {"height", p.height},
              {"tiles", p.tiles},
              {"antialias", p.antialias},
              {"antialias_threshold", p.antialiasThreshold},
              {"antialias_depth", p.antialiasDepth},
              {"alpha", p.alpha},
              {"sandbox", p.sandbox},
              {"timeout_s", p.timeoutS},
              {"dpi", p.dpi},
              {"templates", p.templatesDir.string()}}},
            {"still", p.still.string()},
            {"sidecar", p.sidecar.string()},
            {"overlay", overlayJson(p)},
            {"sidecar_so_far", p.sidecar0}};
}

std::string hashOf(const RenderPlan& p, const ordered_json& fields, Diagnostics* diags) {
    Sha256 h;
    h.add(fields.dump());
    std::vector<const PlanFile*> files{&p.pov};
    for (const auto& f : p.reads) files.push_back(&f);
    for (const auto& f : p.extras) files.push_back(&f);
    for (const PlanFile* f : files) {
        h.add(f->name);
        if (!h.addFile(p.dir / f->name)) {
            if (diags) diags->error({(p.dir / f->name).string(), 0, 0}, "the plan's file is missing or unreadable");
            return {};
        }
    }
    return h.hex();
}

bool plainName(const std::string& n) {
    return !n.empty() && n != "." && n != ".." && n.find('/') == std::string::npos;
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

bool writePlan(RenderPlan& plan, Diagnostics& diags) {
    plan.reliefVersion = kVersion;
    const ordered_json fields = planJson(plan);
    plan.hash = hashOf(plan, fields, &diags);
    if (plan.hash.empty()) return false;
    ordered_json j = fields;
    j["hash"] = plan.hash;
    try {
        writeFileAtomically(plan.dir / "plan.json", j.dump(1, ' ', false, nlohmann::json::error_handler_t::replace) + "\n");
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
        ok = ok && within(l.sizePx, 1, 1000) && within(l.markerPx, 0, 1000) && within(l.x, -1e7, 1e7) &&
             within(l.y, -1e7, 1e7) && within(l.groundY, -1e7, 1e7);
    for (const auto& e : p.overlayFacts.layerLegend)
        ok = ok && within(e.widthPx, 0, 1000) && within(e.fillOpacity, 0, 1);
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
    p.dir = dir;
    try {
        const ordered_json j = ordered_json::parse(*text);
        if (j.at("relief_plan").get<int>() != kPlanFormat) {
            diags.error(at, "a render plan of another format: make it again with this relief");
            return std::nullopt;
        }
        p.reliefVersion = j.at("relief_version").get<std::string>();
        p.povrayVersion = j.at("povray_version").get<std::string>();
        p.hash = j.at("hash").get<std::string>();
        p.pov = fileOf(j.at("pov"));
        for (const auto& f : j.at("reads")) p.reads.push_back(fileOf(f));
        for (const auto& f : j.at("extras")) p.extras.push_back(fileOf(f));
        const auto& r = j.at("render");
        p.width = r.at("width").get<int>();
        p.height = r.at("height").get<int>();
        p.tiles = r.at("tiles").get<int>();
        p.antialias = r.at("antialias").get<bool>();
        p.antialiasThreshold = r.at("antialias_threshold").get<double>();
        p.antialiasDepth = r.at("antialias_depth").get<int>();
        p.alpha = r.at("alpha").get<bool>();
        p.sandbox = r.at("sandbox").get<bool>();
        p.timeoutS = r.at("timeout_s").get<double>();
        p.dpi = r.at("dpi").get<double>();
        p.templatesDir = r.at("templates").get<std::string>();
        p.still = j.at("still").get<std::string>();
        p.sidecar = j.at("sidecar").get<std::string>();
        readOverlay(j.at("overlay"), p);
        p.sidecar0 = j.at("sidecar_so_far");
    } catch (const nlohmann::json::exception&) {
        diags.error(at, "the render plan is damaged (not the JSON relief writes): make it again");
        return std::nullopt;
    }
    // Names in the plan's folder only, whatever the file says.
    bool names = plainName(p.pov.name);
    for (const auto& f : p.reads) names = names && plainName(f.name);
    for (const auto& f : p.extras) names = names && plainName(f.name);
    if (!names || p.width < 1 || p.height < 1 || p.tiles < 1 || p.tiles > p.height || !overlaySizesSane(p)) {
        diags.error(at, "the render plan is damaged (its files or sizes are not a plan's): make it again");
        return std::nullopt;
    }
    return p;
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
            {"seconds", {{"povray_parse", r.parseSeconds}, {"povray_trace", r.traceSeconds}, {"povray_wall", r.wallSeconds}}},
            {"povray_peak_memory_mb", r.peakMemoryMB},
            {"povray_command", r.povrayCommand}};
}

std::optional<TileRecord> readTileRecord(const RenderPlan& plan, int index, std::string& problem) {
    const auto text = readInputFile(tileRecordPath(plan, index), 1'000'000, problem);
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
        r.parseSeconds = j.at("seconds").at("povray_parse").get<double>();
        r.traceSeconds = j.at("seconds").at("povray_trace").get<double>();
        r.wallSeconds = j.at("seconds").at("povray_wall").get<double>();
        r.peakMemoryMB = j.at("povray_peak_memory_mb").get<double>();
        r.povrayCommand = j.at("povray_command").get<std::vector<std::string>>();
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
    else if (inputFileProblem(tileImage(plan, index)) != "")
        problem = "its image is missing";
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
    const int fd = ::open((dir / "lock").c_str(), O_RDWR | O_CREAT | O_NOFOLLOW | O_CLOEXEC, 0600);
    if (fd < 0) return std::nullopt;
    struct flock l {};
    l.l_type = F_WRLCK;
    l.l_whence = SEEK_SET;
    if (::fcntl(fd, F_OFD_SETLK, &l) != 0) {
        ::close(fd);
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
