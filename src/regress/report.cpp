#include <algorithm>
#include <cctype>
#include <cmath>
#include <set>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "core/atomic_file.h"
#include "core/text_escape.h"
#include "regress/regress.h"

namespace relief::regress {

namespace fs = std::filesystem;

namespace {

// A file in the report folder as a relative URL: every byte but unreserved
// ones and '/' percent-encoded, so that a case named "a#b" or 'x" onload="'
// is a file name, never a fragment or an attribute.
std::string relativeUrl(const fs::path& p, const fs::path& base) {
    if (p.empty()) return "";
    std::string url;
    for (const char ch : fs::relative(p, base).generic_string()) {
        const auto c = static_cast<unsigned char>(ch);
        if (std::isalnum(c) || c == '-' || c == '.' || c == '_' || c == '~' || c == '/') url += ch;
        else url += fmt::format("%{:02X}", c);
    }
    return url;
}

bool failed(CaseStatus s) { return s == CaseStatus::Fail || s == CaseStatus::Error || s == CaseStatus::New; }

std::string number(double v) { return std::isfinite(v) ? fmt::format("{:.6g}", v) : "inf"; }

// A case's geometry checks: each with its distance, its tolerance, where, and a plot of both curves.
std::string geometryHtml(const CaseResult& r, const fs::path& reportDir) {
    if (r.geometry.empty()) return "";
    std::string h = "<table class=\"metrics geometry\"><tr><th>geometry check</th><th>Hausdorff distance</th>"
                    "<th>tolerance</th><th>verdict</th><th>where</th></tr>\n";
    for (const auto& g : r.geometry)
        h += fmt::format("<tr class=\"check\"><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td></tr>\n",
                         markupText(g.name), g.kept ? measure::formatDistance(g.distanceM) : "",
                         measure::formatDistance(g.toleranceM),
                         !g.kept ? "new: no kept curve" : g.pass ? "pass" : "FAIL", markupText(g.where));
    h += "</table>\n<div class=\"images\">\n";
    for (const auto& g : r.geometry)
        if (!g.plot.empty())
            h += fmt::format("<figure><img class=\"geometry-plot\" src=\"{}\" alt=\"{}\"><figcaption>{} "
                             "(grey dashed: kept; blue: new)</figcaption></figure>\n",
                             relativeUrl(g.plot, reportDir), markupText(g.name), markupText(g.name));
    return h + "</div>\n";
}

}  // namespace

namespace {

// `dir` as a name in its parent: absolute, "." and ".." resolved, no trailing slash.
fs::path reportPath(const fs::path& dir) {
    fs::path p = fs::absolute(dir.empty() ? fs::path(".") : dir).lexically_normal();
    if (!p.has_filename()) p = p.parent_path();
    return p;
}

bool within(const fs::path& inner, const fs::path& outer) {
    const fs::path rel = fs::weakly_canonical(inner).lexically_relative(fs::weakly_canonical(outer));
    return !rel.empty() && *rel.begin() != "..";
}

// What a report of relief's holds: its three pages, its images (PNGs) and a Slurm job's folder.
bool holdsOnlyAReport(const fs::path& dir) {
    static const std::set<std::string> kEntries = {"index.html", "summary.json", "junit.xml", "images", "slurm"};
    std::error_code ec;
    if (!fs::exists(dir / "summary.json", ec) || !fs::exists(dir / "index.html", ec)) return false;
    for (const auto& entry : fs::directory_iterator(dir, ec))
        if (!kEntries.count(entry.path().filename().string())) return false;
    for (const auto& entry : fs::directory_iterator(dir / "images", ec)) {
        const auto extension = entry.path().extension();
        if (extension != ".png" && extension != ".svg" && extension != ".json") return false;
    }
    return !ec;
}

}  // namespace

std::string ReportFolder::refusal(const fs::path& given, const Manifest& manifest) {
    const fs::path dir = reportPath(given);
    const std::string shown = given.string();
    if (dir == dir.root_path()) return fmt::format("--report {}: a report cannot replace /", shown);
    // The folder is replaced whole: never one holding the suite's own files.
    for (const auto& c : manifest.cases)
        if (within(c.referenceDir, dir))
            return fmt::format("--report {}: holds the references of case \"{}\", and a new report replaces the "
                               "folder; name a folder outside the suite's references",
                               shown, c.name);
    if (within(manifest.file, dir))
        return fmt::format("--report {}: holds the manifest, and a new report replaces the folder; name a folder "
                           "of its own",
                           shown);
    std::error_code ec;
    const auto status = fs::symlink_status(dir, ec);
    if (!fs::exists(status)) return "";
    if (fs::is_symlink(status))
        return fmt::format("--report {}: is a symbolic link; name the folder itself", shown);
    if (!fs::is_directory(status)) return fmt::format("--report {}: is not a folder; name a folder for the report", shown);
    if (fs::is_empty(dir, ec) || holdsOnlyAReport(dir)) return "";
    return fmt::format("--report {}: holds files that are not a relief test report, and a new report replaces "
                       "the folder; name a new folder (or an old report's)",
                       shown);
}

namespace {
fs::path madeParent(const fs::path& dir) {
    fs::create_directories(dir.parent_path());
    removeAbandonedFolders(dir.parent_path());  // reports of runs killed before they were published
    return dir.parent_path();
}
}  // namespace

ReportFolder::ReportFolder(const fs::path& dir, const Manifest& manifest)
    : dir_(reportPath(dir)), manifest_(manifest), staging_(madeParent(dir_), "report") {
    fs::create_directory(staged());
}

void ReportFolder::publish() {
    // Checked again: the run may have taken hours, and the folder may have changed meanwhile.
    if (const std::string refused = refusal(dir_, manifest_); !refused.empty())
        throw std::runtime_error(fmt::format("the report is not moved into place: {}", refused));
    std::error_code ec;
    const fs::path previous = staging_.path() / "previous";
    const bool replacing = fs::exists(fs::symlink_status(dir_, ec));
    if (replacing) {
        fs::rename(dir_, previous, ec);  // removed with the private folder
        if (ec) throw std::runtime_error(fmt::format("cannot replace the report {}: {}", dir_.string(), ec.message()));
    }
    fs::rename(staged(), dir_, ec);
    if (!ec) return;
    std::error_code back;  // the report before it, put back
    if (replacing) fs::rename(previous, dir_, back);
    throw std::runtime_error(fmt::format("cannot move the report into {}: {}", dir_.string(), ec.message()));
}

namespace {

constexpr const char* kReportStyle = R"(<style>
body { font-family: sans-serif; margin: 1.5em; color: #222; }
h1 { font-size: 1.3em; } .summary { font-size: 1.1em; margin-bottom: 1em; }
.case { border: 1px solid #ccc; border-radius: 6px; padding: 0.8em; margin: 1em 0; }
.case.fail, .case.error, .case.new { border-color: #c62828; background: #fff5f5; }
.status { font-weight: bold; } .fail .status, .error .status, .new .status { color: #c62828; }
.pass .status { color: #2e7d32; } .warning .status { color: #ef6c00; }
.images { display: flex; gap: 1em; flex-wrap: wrap; }
figure { margin: 0; } figcaption { font-size: 0.85em; color: #555; }
.blink { position: relative; display: inline-block; }
.blink img.reference-under { position: absolute; left: 0; top: 0; opacity: 0; }
.blink:hover img.reference-under { opacity: 1; }
table.metrics { border-collapse: collapse; font-size: 0.9em; margin-top: 0.5em; }
table.metrics td, table.metrics th { border: 1px solid #ddd; padding: 2px 8px; text-align: right; }
code { background: #f2f2f2; padding: 2px 4px; }
img.geometry-plot { max-width: 420px; max-height: 320px; border: 1px solid #eee; }
</style></head><body>
)";

// A case's images: the new one (the reference under it on hover), the reference, the difference.
std::string imagesHtml(const CaseResult& r, const fs::path& reportDir) {
    std::string h = "<div class=\"images\">\n";
    const std::string newImg = relativeUrl(r.newImage, reportDir), refImg = relativeUrl(r.referenceImage, reportDir),
                      diffImg = relativeUrl(r.diffImage, reportDir);
    if (!newImg.empty() && fs::exists(r.newImage)) {
        h += "<figure><div class=\"blink\">";
        h += fmt::format("<img class=\"new\" src=\"{}\" alt=\"new\">", newImg);
        if (!refImg.empty())
            h += fmt::format("<img class=\"reference-under\" src=\"{}\" alt=\"reference (hover)\">", refImg);
        h += "</div><figcaption>new (hover: reference)</figcaption></figure>\n";
    }
    if (!refImg.empty())
        h += fmt::format("<figure><img class=\"reference\" src=\"{}\" alt=\"reference\"><figcaption>"
                         "reference {}</figcaption></figure>\n",
                         refImg, markupText(r.referenceName));
    if (!diffImg.empty())
        h += fmt::format("<figure><img class=\"difference\" src=\"{}\" alt=\"difference\"><figcaption>"
                         "difference (black: identical; scaled to the largest)</figcaption></figure>\n",
                         diffImg);
    return h + "</div>\n";
}

// A case's section: its status, message, images, the difference's measures and the geometry checks.
std::string caseHtml(const CaseResult& r, const fs::path& reportDir) {
    const TestCase& c = *r.testCase;
    std::string cls = statusName(r.status);
    std::transform(cls.begin(), cls.end(), cls.begin(), [](unsigned char ch) { return std::tolower(ch); });
    std::string h = fmt::format("<div class=\"case {}\" data-case=\"{}\">\n<h2><span class=\"status\">{}</span> {}</h2>\n",
                                cls, markupText(c.name), statusName(r.status), markupText(c.name));
    h += fmt::format("<p>{} — scene <code>{}</code>, {} x {}, {:.1f} s</p>\n", markupText(r.message),
                     markupText(c.scene.string()), c.width, c.height, r.seconds);
    h += imagesHtml(r, reportDir);
    if (r.difference.width > 0) {
        const auto& d = r.difference;
        const auto& t = c.thresholds;
        h += "<table class=\"metrics\"><tr><th>max error</th><th>at</th><th>mean</th><th>RMS</th><th>PSNR</th>"
             "<th>pixels over fail</th><th>fail</th><th>failpercent</th><th>hardfail</th></tr>\n";
        h += fmt::format("<tr><td>{}</td><td>({}, {})</td><td>{}</td><td>{}</td><td>{}</td><td>{} ({:.3f} %)</td>"
                         "<td>{}</td><td>{}</td><td>{}</td></tr></table>\n",
                         number(d.maxError), d.maxX, d.maxY, number(d.meanError), number(d.rmsError),
                         number(d.psnr), d.failingPixels, d.failingPercent, number(t.fail),
                         number(t.failPercent), number(t.hardFail));
    }
    return h + geometryHtml(r, reportDir) + "</div>\n";
}

// index.html: the summary, how to bless the failing cases, then each case, failed ones first.
std::string indexHtml(const Manifest& m, const std::vector<CaseResult>& results, const fs::path& reportDir,
                      size_t nFailed, const std::string& bless, double wallSeconds) {
    std::vector<const CaseResult*> order;
    for (const auto& r : results) order.push_back(&r);
    std::stable_sort(order.begin(), order.end(), [](const CaseResult* a, const CaseResult* b) {
        return failed(a->status) && !failed(b->status);
    });
    std::string h = "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">\n";
    h += fmt::format("<title>relief test: {} passed, {} failed</title>\n", results.size() - nFailed, nFailed);
    h += kReportStyle;
    h += fmt::format("<h1>relief test — {}</h1>\n", markupText(m.file.string()));
    h += fmt::format("<p class=\"summary\" id=\"summary\">{} passed, {} failed, {} cases in {:.1f} s</p>\n",
                     results.size() - nFailed, nFailed, results.size(), wallSeconds);
    if (nFailed)
        h += fmt::format("<p>To accept the new images of the failing cases as references: "
                         "<code id=\"bless\">{}</code></p>\n",
                         markupText(bless));
    for (const CaseResult* r : order) h += caseHtml(*r, reportDir);
    return h + "</body></html>\n";
}

// summary.json: the counts, and each case's status, measures and geometry checks, in manifest order.
std::string summaryJson(const Manifest& m, const std::vector<CaseResult>& results, const RunOptions& o,
                        size_t nFailed, const std::string& bless, double wallSeconds) {
    nlohmann::ordered_json j;
    j["manifest"] = m.file.string();
    j["passed"] = results.size() - nFailed;
    j["failed"] = nFailed;
    j["seconds"] = wallSeconds;
    j["jobs"] = o.jobs;
    nlohmann::ordered_json cases = nlohmann::ordered_json::array();
    for (const auto& r : results) {
        nlohmann::ordered_json cj{{"name", r.testCase->name}, {"status", statusName(r.status)},
                                  {"message", r.message}, {"seconds", r.seconds},
                                  {"new", r.newImage.empty() ? "" : fs::relative(r.newImage, o.reportDir).generic_string()}, {"reference", r.referenceName},
                                  {"nodes", r.nodes}};
        if (r.difference.width > 0)
            cj["metrics"] = {{"max_error", r.difference.maxError},
                             {"failing_pixels", r.difference.failingPixels},
                             {"failing_percent", r.difference.failingPercent},
                             {"mean_error", r.difference.meanError}};
        for (const auto& g : r.geometry)
            cj["geometry"].push_back({{"check", g.name},
                                      {"kept", g.kept},
                                      {"distance_m", g.distanceM},
                                      {"tolerance_m", g.toleranceM},
                                      {"pass", g.pass},
                                      {"where", g.where}});
        cases.push_back(cj);
    }
    j["cases"] = cases;
    if (nFailed) j["bless"] = bless;
    return j.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n";
}

// junit.xml, which CI systems read: a test case a relief case, a failure each failed one.
std::string junitXml(const Manifest& m, const std::vector<CaseResult>& results, size_t nFailed, double wallSeconds) {
    std::string x = fmt::format("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<testsuite name=\"relief\" "
                                "tests=\"{}\" failures=\"{}\" time=\"{:.3f}\">\n",
                                results.size(), nFailed, wallSeconds);
    for (const auto& r : results) {
        x += fmt::format("  <testcase classname=\"relief.{}\" name=\"{}\" time=\"{:.3f}\"",
                         markupText(m.file.stem().string()), markupText(r.testCase->name), r.seconds);
        if (failed(r.status))
            x += fmt::format(">\n    <failure message=\"{}\">{}</failure>\n  </testcase>\n",
                             markupText(statusName(r.status)), markupText(r.message));
        else
            x += "/>\n";
    }
    return x + "</testsuite>\n";
}

}  // namespace

void writeReport(const Manifest& m, const std::vector<CaseResult>& results, const RunOptions& o,
                 double wallSeconds) {
    size_t nFailed = 0;
    for (const auto& r : results) nFailed += failed(r.status);
    const std::string bless = fmt::format("relief test {} --update", shellQuoted(o.manifestArgument));
    writeFileAtomically(o.reportDir / "index.html", indexHtml(m, results, o.reportDir, nFailed, bless, wallSeconds));
    writeFileAtomically(o.reportDir / "summary.json", summaryJson(m, results, o, nFailed, bless, wallSeconds));
    writeFileAtomically(o.reportDir / "junit.xml", junitXml(m, results, nFailed, wallSeconds));
}

}  // namespace relief::regress
