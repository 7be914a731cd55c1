#pragma once
// What the subcommands share: exit codes, printing diagnostics, progress,
// the scene options every scene command takes, small argument parsers.
// Each subcommand lives in one cmd_*.cpp and registers itself through a
// Command; main.cpp only builds the app and dispatches.
#include <chrono>
#include <filesystem>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "core/atomic_file.h"
#include "core/diagnostics.h"
#include "execute/execute.h"
#include "pipeline/progress.h"
#include "scene/read_scene.h"

namespace relief::cli {

namespace fs = std::filesystem;

/// Every command's exit codes (also in README.md and `relief --help`).
/// `relief diff` keeps idiff's codes and `relief test` its own; the rest share
/// the first four.
enum class Exit : int {
    Ok = 0,          ///< success; diff: PASS; test: every case passed
    Internal = 1,    ///< a bug in relief: please report it
    BadInput = 2,    ///< bad arguments, scene, samples or template; over budget; cannot write
    ToolFailed = 3,  ///< POV-Ray is missing or failed (its own error text is printed)

    DiffWarning = 1,        ///< diff: over the warning thresholds (WARNING)
    DiffFailure = 2,        ///< diff: over the failure thresholds (FAILURE)
    DiffNotComparable = 3,  ///< diff: sizes or channel counts differ
    DiffFileError = 4,      ///< diff: an image cannot be read or written, or bad arguments

    TestCaseFailed = 1,     ///< test: a case failed, errored or is new (without --update)

    Interrupted = 130,      ///< stopped by Ctrl-C (SIGINT) or SIGTERM: nothing written, a render's plan kept
};
inline int code(Exit e) { return static_cast<int>(e); }

/// One exit code every command but diff and test shares, and what it means:
/// `relief --help` and README.md's table are both this list (tests/cli/exit_codes.sh).
struct ExitCodeRow {
    Exit exit;
    const char* meaning;
};
extern const std::vector<ExitCodeRow> kExitCodeRows;
/// The help's footer: the rows, then diff's and test's own codes.
std::string exitCodesHelp();

/// A registered subcommand: run() is called when it was parsed; a parse error
/// exits with parseErrorCode (relief diff keeps idiff's 4).
struct Command {
    CLI::App* app = nullptr;
    std::function<int()> run;
    int parseErrorCode = code(Exit::BadInput);
};

// Registration, one function per group of commands (a cmd_*.cpp each but the plan's steps).
void addDataCommands(CLI::App& app, std::vector<Command>& out);      // info, init
void addSceneCommands(CLI::App& app, std::vector<Command>& out);     // compile, render, plan
void addAnimateCommands(CLI::App& app, std::vector<Command>& out);   // animate
void addPlanStepCommands(CLI::App& app, std::vector<Command>& out);  // render-tile, finish
void addSchemeCommands(CLI::App& app, std::vector<Command>& out);    // check, curve
void addGeometryCommands(CLI::App& app, std::vector<Command>& out);  // hausdorff, profile, compare-geometry
void addExportCommands(CLI::App& app, std::vector<Command>& out);    // export
void addPreviewCommands(CLI::App& app, std::vector<Command>& out);   // preview
void addImageCommands(CLI::App& app, std::vector<Command>& out);     // diff, test, sweep (relief-images)

/// The image commands run in a helper executable, relief-images, because
/// OpenImageIO's 260 shared libraries cost every process that links it 0.15 s
/// of start-up; `relief` lists them and hands their command lines over.
struct ImageCommandInfo {
    const char* name;
    const char* description;
};
extern const ImageCommandInfo kImageCommands[3];
bool isImageCommand(const char* name);
/// Lists the image commands in `relief --help` (their options are the helper's).
void addImageCommandEntries(CLI::App& app);
/// Replaces this process with relief-images, same arguments; returns only on
/// failure, with the exit code after printing why.
int runImageHelper(int argc, char** argv);

/// Parses, dispatches and maps exceptions to exit codes: main() of both executables.
int runCommands(CLI::App& app, const std::vector<Command>& commands, int argc, char** argv);

/// Errors and warnings in file order, then the count line.
void printDiagnostics(const Diagnostics& diags, bool wrote);

/// Where the templates are: --templates, $RELIEF_TEMPLATES, the installed
/// share/relief/templates beside the binary, or the source tree.
fs::path findTemplates(const std::string& option);

/// One status line, rewritten in place on a terminal, where a task with a
/// percentage also shows the seconds spent and an estimate of those left; in
/// a log, stage lines and one line per 10 % of a task. Nothing when quiet.
class Progress {
public:
    explicit Progress(bool quiet);
    /// A line of text; `percent` (0..100, or -1) thins a log to one line per 10 %.
    void show(const std::string& line, int percent = -1);
    /// A pipeline event: stages as they are, POV-Ray's lines prefixed "povray: ".
    void show(const relief::ProgressEvent& event);
    void done();

private:
    bool quiet_, tty_, open_ = false;
    std::string last_;
    int lastDecile_ = -1;
    std::string task_;  ///< the task the percentages belong to, and when it started
    std::chrono::steady_clock::time_point taskStart_;
    int firstPercent_ = -1;  ///< its first percentage, and when it came: the rate is measured from there
    std::chrono::steady_clock::time_point firstPercentAt_;
};

/// "relief: <what> kept: relief <command> --resume <dir> renders what is
/// missing" and a line feed, or "" when nothing was kept (`dir` empty).
std::string keptForResume(std::string_view what, std::string_view command, const fs::path& dir);

/// What a job tells, shown on `progress`: each stage on a line of its own, the
/// render's progress rewriting its line.
ProgressFn showing(Progress& progress);

/// The options of the commands that take one scene file.
struct CommonOptions {
    std::string scene;
    std::vector<std::string> sets;  ///< section.key=value overrides
    std::string output;
    std::string templates;
    int threads = 0;
    bool quiet = false;
    bool noSandbox = false;
};

/// Where and how many tiles (or cases, or stills) are rendered at once:
/// --jobs, --executor local|slurm, --slurm-args, and --tiles where a still
/// is cut into strips.
struct ExecutionOptions {
    int tiles = 1;
    int jobs = 0;
    std::string executor = "local";
    std::string slurmArgs;
};
void addExecutionOptions(CLI::App* app, ExecutionOptions& o, bool tiles, const char* jobsHelp);
void addTilesOption(CLI::App* app, ExecutionOptions& o);  ///< --tiles alone (relief plan)

/// Raises the soft limit of open files towards the hard one (at most 65536):
/// relief test holds two descriptors for each planned case until it is
/// rendered, and a default soft limit of 1024 would cap a suite at about 500.
void raiseOpenFileLimit();
/// As execute::Options, cancelled by Ctrl-C (interruptHandler).
/// The execution options, POV-Ray sandboxed unless `noSandbox` (--no-sandbox,
/// the only way to turn it off: a warning says so).
execute::Options executionOf(const ExecutionOptions& o, bool noSandbox);

/// Ctrl-C and SIGTERM stop a long command cleanly: the first asks the work
/// to stop (every POV-Ray process it started, the Slurm job), which then
/// returns; a second ends the process at once.
void installInterruptHandler();
bool interrupted();

/// KEY=VALUE strings -> scene overrides (`section.key=value`); false with a message.
bool parseOverrides(const std::vector<std::string>& list, scene::SceneOverrides& out);

/// KEY=VALUE list (values may be fractions) -> map; false with a message on bad input.
bool parseParams(const std::vector<std::string>& list, std::map<std::string, double>& out);

std::vector<std::string> split(const std::string& s, char sep);

/// A number for --json output; infinity (a PSNR of identical images, a
/// distance to nothing) as the string "inf", which JSON has no number for.
nlohmann::ordered_json jsonNumber(double v);

/// "LON,LAT" in WGS84 degrees; false when malformed or out of range.
std::optional<GeoPoint> parseLonLat(const std::string& text);

}  // namespace relief::cli
