#pragma once
// `relief test`: the regression suite users run. A manifest (TOML) lists
// cases (scene, accepted reference images, thresholds, test resolution); each
// case is rendered, compared with OpenImageIO against every reference (it
// passes when any one matches), and reported as text, HTML, JSON and JUnit XML.
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "compare/compare_images.h"
#include "regress/geometry_check.h"
#include "execute/execute.h"
#include "core/diagnostics.h"
#include "core/output_set.h"

namespace relief::regress {

struct TestCase {
    std::string name;
    std::filesystem::path scene;                    ///< resolved against the manifest's folder
    std::filesystem::path referenceDir;             ///< every *.png in it is an accepted reference
    SourceLoc referencesLoc;                        ///< where the manifest names it
    compare::Thresholds thresholds;
    int width = 160, height = 120;                  ///< the test resolution
    GeometryChecks geometry;                        ///< profiles, levels, peak loss: none when !any()
};

struct Manifest {
    std::filesystem::path file;
    std::vector<TestCase> cases;
};

/// Reads a manifest; reports every problem (unknown keys, missing scenes,
/// duplicate names) with file:line:col.
std::optional<Manifest> readManifest(const std::filesystem::path& path, Diagnostics& diags);

/// For --update, which replaces the PNGs of a case's references folder: false,
/// with an error at each, when a case's folder is outside the manifest's
/// folder (links resolved). References elsewhere can be read, never blessed.
bool checkUpdatable(const Manifest& manifest, Diagnostics& diags);

enum class CaseStatus { Pass, Warning, Fail, New, Error };
const char* statusName(CaseStatus s);

struct CaseResult {
    const TestCase* testCase = nullptr;
    CaseStatus status = CaseStatus::Error;
    std::string message;                    ///< one line: why
    std::filesystem::path newImage;         ///< in the report folder
    std::filesystem::path referenceImage;   ///< the closest reference (copied into the report)
    std::filesystem::path diffImage;
    std::string referenceName;              ///< its file name in the reference folder
    compare::ImageDifference difference;    ///< against the closest reference
    std::vector<GeometryResult> geometry;   ///< the case's geometry checks, in order
    std::filesystem::path newGeometry;      ///< the surface's curves now (what --update keeps)
    std::vector<std::string> nodes;         ///< the node each of its tiles ran on (plan::tileNodes)
    double seconds = 0;
};

struct RunOptions {
    std::filesystem::path reportDir;        ///< self-contained output folder
    std::filesystem::path templatesDir;
    int jobs = 1;                           ///< renders in parallel
    bool update = false;                    ///< bless new images of failing or new cases
    std::string manifestArgument;           ///< as typed, for the bless command line
    execute::Options execution;             ///< where the cases render (local: `jobs` at once)
};

using CaseDoneFn = std::function<void(const CaseResult&, size_t done, size_t total)>;

/// Compiles every case into its plan, renders them (one task a case, here or
/// on Slurm), and compares each as soon as its render is in; calls `done` as
/// each finishes (from whichever thread finished it, one at a time). Results
/// are in manifest order.
std::vector<CaseResult> runCases(const Manifest& manifest, const RunOptions& options,
                                 const CaseDoneFn& done);

/// Where a run's report is made: a private folder beside `dir`, moved into
/// place whole by publish(), so that an interrupted or failed run leaves the
/// report before it as it was (and a new report holds only this run's
/// images). `dir` may be absent, empty, or a report relief wrote; anything
/// else (a folder of the user's) is refused, since publishing replaces it.
class ReportFolder {
public:
    /// The refusal, when `dir` is not one relief may replace: "" if it may.
    /// Refused too: a folder holding the manifest or any case's references.
    static std::string refusal(const std::filesystem::path& dir, const Manifest& manifest);
    /// Throws std::runtime_error when the folder beside `dir` cannot be made.
    ReportFolder(const std::filesystem::path& dir, const Manifest& manifest);
    /// Where runCases and writeReport write (RunOptions::reportDir).
    std::filesystem::path staged() const { return staging_.path() / "report"; }
    /// The report's folder, absolute.
    const std::filesystem::path& path() const { return dir_; }
    /// Replaces `dir` with the staged report (refusal() asked again first);
    /// throws std::runtime_error, leaving the report before it in place.
    void publish();

private:
    std::filesystem::path dir_;
    const Manifest& manifest_;
    PrivateFolder staging_;
};

/// Writes index.html (failed cases first; new, reference and difference images
/// side by side; hover the new image to see the reference), summary.json and
/// junit.xml into the report folder.
void writeReport(const Manifest& manifest, const std::vector<CaseResult>& results,
                 const RunOptions& options, double wallSeconds);

}  // namespace relief::regress
