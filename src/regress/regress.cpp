#include "regress/regress.h"

#include <algorithm>
#include <atomic>
#include <cctype>
#include <chrono>
#include <cmath>
#include <mutex>
#include <set>
#include <thread>

#include "execute/execute.h"

#include <fmt/format.h>
#include <toml++/toml.h>

#include "core/atomic_file.h"
#include "core/input_file.h"
#include "core/stopwatch.h"
#include "core/text_escape.h"
#include "core/text_distance.h"
#include "pipeline/job.h"

namespace relief::regress {

namespace fs = std::filesystem;

const char* statusName(CaseStatus s) {
    switch (s) {
        case CaseStatus::Pass: return "PASS";
        case CaseStatus::Warning: return "WARNING";
        case CaseStatus::Fail: return "FAIL";
        case CaseStatus::New: return "NEW";
        case CaseStatus::Error: return "ERROR";
    }
    return "?";
}

SourceLoc locOf(const std::string& file, const toml::source_region& r) {
    return {file, static_cast<int>(r.begin.line), static_cast<int>(r.begin.column)};
}

namespace {

const std::vector<std::string> kCaseKeys{"name",  "scene", "references", "width", "height",
                                         "fail",  "failpercent", "hardfail", "warn",
                                         "warnpercent", "hardwarn", "allowfailures",
                                         "profile", "levels", "tolerance_m", "peak_loss_tolerance_m"};

// Reads the threshold and size keys of a [defaults] table or a [[case]].
void readSettings(const toml::table& t, const std::string& file, TestCase& c, Diagnostics& diags) {
    auto number = [&](const char* key, double& out) {
        if (const toml::node* n = t.get(key)) {
            if (auto v = n->value<double>(); v && *v >= 0) out = *v;
            else diags.error(locOf(file, n->source()), fmt::format("{} must be a number >= 0", key));
        }
    };
    number("fail", c.thresholds.fail);
    number("failpercent", c.thresholds.failPercent);
    number("hardfail", c.thresholds.hardFail);
    number("warn", c.thresholds.warn);
    number("warnpercent", c.thresholds.warnPercent);
    number("hardwarn", c.thresholds.hardWarn);
    double allow = static_cast<double>(c.thresholds.allowFailures);
    number("allowfailures", allow);
    c.thresholds.allowFailures = static_cast<long long>(allow);
    for (auto [key, out] : {std::pair{"width", &c.width}, std::pair{"height", &c.height}})
        if (const toml::node* n = t.get(key)) {
            if (auto v = n->value_exact<int64_t>(); v && *v >= 16 && *v <= 4096) *out = static_cast<int>(*v);
            else diags.error(locOf(file, n->source()), fmt::format("{} must be an integer in [16, 4096] pixels", key));
        }
}

void unknownKeys(const toml::table& t, const std::string& file, const std::vector<std::string>& known,
                 Diagnostics& diags) {
    for (auto&& [k, v] : t) {
        const std::string key(k.str());
        if (std::find(known.begin(), known.end(), key) != known.end()) continue;
        const std::string best = closestMatch(key, known);
        diags.error(locOf(file, k.source()),
                    fmt::format("unknown key \"{}\"{}", key,
                                best.empty() ? "" : " (did you mean \"" + best + "\"?)"));
    }
}

// A case's name becomes file names in the report folder (<name>.new.png):
// no separators, no "..", nothing a shell or a URL would read otherwise.
bool isCaseName(const std::string& name) {
    if (name.empty() || name.size() > 100 || name[0] == '.') return false;
    for (const char ch : name) {
        const auto c = static_cast<unsigned char>(ch);
        if (!std::isalnum(c) && c != '-' && c != '_' && c != '.') return false;
    }
    return true;
}

}  // namespace

std::optional<Manifest> readManifest(const fs::path& path, Diagnostics& diags) {
    const std::string file = path.string();
    std::string problem;
    const auto text = readInputFile(path, kMaxManifestBytes, problem);
    if (!text) {
        diags.error({file, 0, 0}, "cannot read the manifest: " + problem);
        return std::nullopt;
    }
    toml::table root;
    try {
        root = toml::parse(*text, file);
    } catch (const toml::parse_error& e) {
        diags.error(locOf(file, e.source()), fmt::format("invalid TOML: {}", e.description()));
        return std::nullopt;
    }
    Manifest m;
    m.file = path;
    TestCase defaults;
    // Test thresholds: one 8-bit step per channel, 0.02 % of pixels, three steps at most.
    defaults.thresholds.fail = defaults.thresholds.warn = 0.004;
    defaults.thresholds.failPercent = 0.02;
    defaults.thresholds.hardFail = 0.012;
    unknownKeys(root, file, {"defaults", "case"}, diags);
    if (const toml::table* d = root.get_as<toml::table>("defaults")) {
        unknownKeys(*d, file, {"width", "height", "fail", "failpercent", "hardfail", "warn",
                               "warnpercent", "hardwarn", "allowfailures"}, diags);
        readSettings(*d, file, defaults, diags);
    }
    const toml::array* cases = root.get_as<toml::array>("case");
    if (!cases || cases->empty()) {
        diags.error({file, 0, 0}, "no [[case]] entries; add [[case]] name = ..., scene = ..., "
                                  "references = \"folder/\"");
        return std::nullopt;
    }
    std::set<std::string> names;
    const fs::path base = path.parent_path();
    for (const toml::node& node : *cases) {
        const toml::table* t = node.as_table();
        if (!t) continue;
        unknownKeys(*t, file, kCaseKeys, diags);
        TestCase c = defaults;
        const auto name = t->get("name") ? t->get("name")->value_exact<std::string>() : std::nullopt;
        const auto scene = t->get("scene") ? t->get("scene")->value_exact<std::string>() : std::nullopt;
        const auto refs = t->get("references") ? t->get("references")->value_exact<std::string>() : std::nullopt;
        if (!name || !scene || !refs) {
            diags.error(locOf(file, t->source()), "each [[case]] needs name, scene (a scene file) "
                                                  "and references (a folder of accepted PNGs)");
            continue;
        }
        if (!isCaseName(*name))
            diags.error(locOf(file, t->get("name")->source()),
                        fmt::format("case name \"{}\" must be 1 to 100 letters, digits, '-', '_' or '.', not "
                                    "starting with '.': it names the case's files in the report",
                                    printableExcerpt(*name, 100)));
        else if (!names.insert(*name).second)
            diags.error(locOf(file, t->get("name")->source()), fmt::format("case name \"{}\" is used twice", *name));
        c.name = *name;
        c.scene = (base / *scene).lexically_normal();
        c.referenceDir = (base / *refs).lexically_normal();
        c.referencesLoc = locOf(file, t->get("references")->source());
        // The non-throwing test: a path the system refuses (too long, say) is a
        // missing scene, not an exception out of the reader.
        std::error_code ec;
        if (!fs::is_regular_file(c.scene, ec))
            diags.error(locOf(file, t->get("scene")->source()),
                        fmt::format("scene \"{}\" not found (relative to the manifest){}",
                                    printableExcerpt(*scene, 200), ec ? ": " + ec.message() : ""));
        readSettings(*t, file, c, diags);
        c.geometry = readGeometryChecks(*t, file, diags);
        m.cases.push_back(std::move(c));
    }
    if (diags.hasErrors()) return std::nullopt;
    return m;
}

namespace {

std::vector<fs::path> referencesOf(const TestCase& c) {
    std::vector<fs::path> refs;
    std::error_code ec;
    if (fs::is_directory(c.referenceDir, ec))
        for (auto it = fs::directory_iterator(c.referenceDir, ec); !ec && it != fs::directory_iterator();
             it.increment(ec))
            if (it->path().extension() == ".png") refs.push_back(it->path());
    std::sort(refs.begin(), refs.end());
    return refs;
}

SceneJob caseJob(const TestCase& c, const RunOptions& o) {
    SceneJob job;
    job.scenePath = c.scene;
    job.overrides = {{"render.width", std::to_string(c.width)}, {"render.height", std::to_string(c.height)}};
    job.output = o.reportDir / "images" / (c.name + ".new.png");
    job.templatesDir = o.templatesDir;
    job.threads = 1;  // the refiner: cases compile side by side
    job.stillOnly = true;  // the .pov and sidecar of a test render are not part of the report
    return job;
}

std::string errorsOf(const Diagnostics& diags) {
    std::string message;
    for (const auto& d : diags.all())
        if (d.severity == Severity::Error) message += (message.empty() ? "" : "; ") + formatDiagnostic(d);
    return message;
}

// The new image against the case's references: the closest one decides.
void compareCase(const TestCase& c, const RunOptions& o, CaseResult& r) {
    const fs::path images = o.reportDir / "images";
    std::error_code ec;
    const auto refs = referencesOf(c);
    if (refs.empty()) {
        r.status = CaseStatus::New;
        r.message = fmt::format("no reference image in {}", c.referenceDir.string());
        return;
    }
    bool first = true;
    for (const auto& ref : refs) {
        auto d = compare::compareImages(r.newImage, ref, c.thresholds);
        const bool better = first || (d.pass() && !r.difference.pass()) ||
                            (d.pass() == r.difference.pass() && d.failingPixels < r.difference.failingPixels);
        if (better) {
            r.difference = d;
            r.referenceName = ref.filename().string();
            r.referenceImage = ref;
        }
        first = false;
        if (d.verdict == compare::Verdict::Pass) break;
    }
    const auto& d = r.difference;
    r.status = d.verdict == compare::Verdict::Pass      ? CaseStatus::Pass
               : d.verdict == compare::Verdict::Warning ? CaseStatus::Warning
                                                        : CaseStatus::Fail;
    r.message = d.verdict == compare::Verdict::NotComparable || d.verdict == compare::Verdict::FileError
                    ? d.error
                    : fmt::format("{}: max error {:.4f} at ({}, {}), {} pixels ({:.3f} %) over {}",
                                  r.referenceName, d.maxError, d.maxX, d.maxY, d.failingPixels,
                                  d.failingPercent, c.thresholds.fail);
    // Copies for the self-contained report, and the difference image; a
    // reference that is not an image (someone's text file named ref.png) is
    // not copied into a report that travels.
    if (d.verdict == compare::Verdict::FileError) {
        r.referenceImage.clear();
        return;
    }
    const fs::path refCopy = images / (c.name + ".ref.png");
    fs::copy_file(r.referenceImage, refCopy, fs::copy_options::overwrite_existing, ec);
    r.referenceImage = refCopy;
    if (d.verdict != compare::Verdict::NotComparable && d.verdict != compare::Verdict::FileError) {
        r.diffImage = images / (c.name + ".diff.png");
        if (!compare::writeDifferenceImage(r.newImage, refCopy, r.diffImage).empty()) r.diffImage.clear();
    }
}

// The case's geometry checks, which can fail a case its pixels pass (or leave it new).
void checkCaseGeometry(const TestCase& c, const RunOptions& o, CaseResult& r) {
    if (!c.geometry.any() || r.status == CaseStatus::Error) return;
    r.newGeometry = o.reportDir / "images" / (c.name + ".geometry.json");
    const auto overrides = caseJob(c, o).overrides;
    if (const std::string error = checkGeometry(c.scene, overrides, c.geometry, c.referenceDir, r.newGeometry,
                                                o.reportDir / "images", c.name, r.geometry);
        !error.empty()) {
        r.status = CaseStatus::Error;
        r.message = "geometry: " + error;
        return;
    }
    std::string failing;
    bool unkept = false;
    for (const auto& g : r.geometry) {
        unkept = unkept || !g.kept;
        if (g.kept && !g.pass)  // moved beyond its tolerance, or not measurable (`where` says why)
            failing += (failing.empty() ? "" : "; ") +
                       (std::isfinite(g.distanceM) && g.distanceM > g.toleranceM
                            ? fmt::format("{} moved {} > {}", g.name, measure::formatDistance(g.distanceM),
                                          measure::formatDistance(g.toleranceM))
                            : fmt::format("{}: {}", g.name, g.where));
    }
    if (!failing.empty()) {
        r.status = CaseStatus::Fail;
        r.message += "; geometry: " + failing;
    } else if (unkept && r.status != CaseStatus::Fail) {
        r.status = CaseStatus::New;
        r.message += fmt::format("; geometry: no kept curves in {}", (c.referenceDir / kGeometryFile).string());
    } else {
        r.message += fmt::format("; geometry: {} checks within their tolerances", r.geometry.size());
    }
}

}  // namespace

bool checkUpdatable(const Manifest& m, Diagnostics& diags) {
    // --update replaces the PNGs it finds in a case's references: only a
    // folder of the manifest's own tree may be blessed (not ~/Pictures, not a
    // link out of it); references elsewhere are read, never written.
    const fs::path base = m.file.parent_path();
    for (const auto& c : m.cases)
        if (!pathInside(c.referenceDir, base))
            diags.error(c.referencesLoc,
                        fmt::format("--update: the references of case \"{}\", {}, are not in the manifest's folder "
                                    "({}); relief test --update replaces the PNGs of a folder only there: run it on "
                                    "the manifest beside them",
                                    c.name, printableExcerpt(c.referenceDir.string(), 200),
                                    printableExcerpt(base.empty() ? "." : base.string(), 200)));
    return !diags.hasErrors();
}

namespace {

// A case's plan once the case is decided: the report travels, so no .pov or
// tile of a plan is left in it; and the plan's descriptors (its lock, its set)
// go with it, so that a long suite holds only those of cases not yet rendered.
void dropPlan(PlannedJob& p) {
    std::error_code ec;
    if (p.plan) fs::remove_all(p.plan->dir, ec);
    p.plan.reset();
    p.lock.reset();
    p.ownOutputs.reset();
}

// Every case compiled into its plan, `jobs` at once (compiling runs here); a
// case that cannot be compiled is an error now.
std::vector<PlannedJob> planCases(const Manifest& m, const RunOptions& o, std::vector<CaseResult>& results,
                                  const std::function<void(size_t)>& finished) {
    std::vector<PlannedJob> planned(m.cases.size());
    std::atomic<size_t> next{0};
    auto worker = [&] {
        for (size_t i = next++; i < m.cases.size(); i = next++) {
            Diagnostics diags;
            planned[i] = planJob(caseJob(m.cases[i], o), diags, nullptr);
            if (planned[i].outcome.status == JobStatus::Ok) continue;
            results[i].status = CaseStatus::Error;
            results[i].message = errorsOf(diags);
            finished(i);
        }
    };
    const int jobs = std::max(1, std::min<int>(o.jobs, static_cast<int>(m.cases.size())));
    std::vector<std::thread> threads;
    for (int j = 1; j < jobs; ++j) threads.emplace_back(worker);
    worker();
    for (auto& t : threads) t.join();
    return planned;
}

}  // namespace

std::vector<CaseResult> runCases(const Manifest& m, const RunOptions& o, const CaseDoneFn& done) {
    fs::create_directories(o.reportDir / "images");
    std::vector<CaseResult> results(m.cases.size());
    std::vector<std::chrono::steady_clock::time_point> started(m.cases.size(), std::chrono::steady_clock::now());
    for (size_t i = 0; i < m.cases.size(); ++i) {
        results[i].testCase = &m.cases[i];
        results[i].newImage = o.reportDir / "images" / (m.cases[i].name + ".new.png");
    }
    std::mutex mutex;
    size_t reported = 0;
    auto finished = [&](size_t i) {
        results[i].seconds = secondsSince(started[i]);
        std::lock_guard lock(mutex);
        if (done) done(results[i], ++reported, m.cases.size());
    };
    std::vector<PlannedJob> planned = planCases(m, o, results, finished);
    // The cases' renders, a task each, here or on Slurm; each case finished
    // and compared as soon as its render is in.
    std::vector<const plan::RenderPlan*> plans;
    std::vector<size_t> caseOf;
    for (size_t i = 0; i < planned.size(); ++i)
        if (planned[i].plan) plans.push_back(&*planned[i].plan), caseOf.push_back(i);
    execute::Options e = o.execution;
    e.jobs = e.executor == execute::Executor::Local ? o.jobs : e.jobs;
    e.stopOnFailure = false;
    if (e.jobDir.empty()) e.jobDir = o.reportDir / "slurm";
    PlansProgress told;
    told.onPlanDone = [&](size_t plan, const std::string& error) {
        const size_t i = caseOf[plan];
        CaseResult& r = results[i];
        Diagnostics diags;
        r.nodes = plan::tileNodes(*planned[i].plan);
        if (!error.empty()) {
            r.status = CaseStatus::Error;
            r.message = "POV-Ray failed: " + error;
        } else if (!finishPlan(*planned[i].plan, planned[i].outputs(), true, true, false, planned[i].outcome, diags)) {
            r.status = CaseStatus::Error;
            r.message = errorsOf(diags);
        } else {
            compareCase(m.cases[i], o, r);
            checkCaseGeometry(m.cases[i], o, r);
        }
        dropPlan(planned[i]);
        finished(i);
    };
    Diagnostics unused;  // a failure before any case ran (Slurm missing, say) is each case's message
    const PlansRendered run = renderPlans(plans, e, told, unused);
    for (size_t i : caseOf)
        if (planned[i].plan) {  // its render never ended
            dropPlan(planned[i]);
            results[i].status = CaseStatus::Error;
            results[i].message = run.error.empty() ? "not rendered" : run.error;
            finished(i);
        }
    if (o.update)
        for (auto& r : results) {
            if (r.status != CaseStatus::Fail && r.status != CaseStatus::New) continue;
            // Bless: the new image becomes the case's reference (git shows the change): ref.png
            // written whole first, the other references removed only then.
            const fs::path ref = r.testCase->referenceDir / "ref.png";
            try {
                writeThroughTemporary(ref, [&](const fs::path& staged) { return copyFileContents(r.newImage, staged); });
            } catch (const OutputError& e) {
                r.message += "; not blessed: " + std::string(e.what());
                continue;
            }
            std::error_code ec;
            for (const auto& old : referencesOf(*r.testCase))
                if (old.filename() != "ref.png") fs::remove(old, ec);
            r.message += fmt::format("; blessed as {}", ref.string());
            if (!r.newGeometry.empty() && fs::exists(r.newGeometry, ec)) {
                const fs::path kept = r.testCase->referenceDir / kGeometryFile;
                try {
                    writeThroughTemporary(kept, [&](const fs::path& staged) {
                        return copyFileContents(r.newGeometry, staged);
                    });
                    r.message += fmt::format(", its curves as {}", kept.string());
                } catch (const OutputError& e) {
                    r.message += "; its curves not kept: " + std::string(e.what());
                }
            }
        }
    return results;
}

}  // namespace relief::regress
