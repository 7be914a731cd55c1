#include "cli/cli_common.h"

#include <signal.h>
#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <sstream>
#include <tuple>

#include <fmt/format.h>

#include "core/output_set.h"
#include "core/text_escape.h"

namespace relief::cli {

const std::vector<ExitCodeRow> kExitCodeRows = {
    {Exit::Ok, "success"},
    {Exit::Internal, "internal error (a bug in relief)"},
    {Exit::BadInput, "bad input: arguments, scene file, samples, template, over the output budget, or an output "
                     "that cannot be written; every problem is printed as `file:line:col: error: ...`"},
    {Exit::ToolFailed, "POV-Ray is missing or failed (a tile, a Slurm task: named, with its log); its own error "
                       "text is printed"},
    {Exit::Interrupted, "interrupted (Ctrl-C, SIGTERM): every POV-Ray and Slurm task stopped, nothing written, a "
                        "render's plan kept for `--resume`"},
};

namespace {

// `text` in lines of at most `width` characters, the later ones indented by `indent`.
std::string wrapped(const std::string& text, size_t width, size_t indent) {
    std::string out, line;
    std::istringstream words(text);
    for (std::string w; words >> w;) {
        if (!line.empty() && line.size() + 1 + w.size() > width) {
            out += line + "\n" + std::string(indent, ' ');
            line.clear();
        }
        line += (line.empty() ? "" : " ") + w;
    }
    return out + line;
}

}  // namespace

std::string exitCodesHelp() {
    std::string out = "Exit codes:\n";
    for (const ExitCodeRow& row : kExitCodeRows)
        out += fmt::format("  {:<4} {}\n", code(row.exit), wrapped(row.meaning, 86, 7));
    return out + "relief diff keeps idiff's: 0 pass, 1 warning, 2 failure, 3 images not comparable, 4 file error or\n"
                 "bad arguments. relief test: 0 all cases pass, 1 a case failed.";
}

void printDiagnostics(const Diagnostics& diags, bool wrote) {
    // In file order, so a user fixes them top to bottom.
    auto sorted = diags.all();
    std::stable_sort(sorted.begin(), sorted.end(), [](const auto& a, const auto& b) {
        return std::tie(a.loc.file, a.loc.line) < std::tie(b.loc.file, b.loc.line);
    });
    // Without a place in a file (an override, a full disk), the line says who speaks.
    // Inputs reach messages (paths, values, a file's bytes): shown as text, never run as terminal commands.
    for (const auto& d : sorted)
        std::cerr << (d.loc.file.empty() ? "relief: " : "") << terminalText(formatDiagnostic(d)) << '\n';
    if (diags.errorCount() > 0)
        std::cerr << fmt::format("relief: {} error{}, {} warning{}; {}\n", diags.errorCount(),
                                 diags.errorCount() == 1 ? "" : "s", diags.warningCount(),
                                 diags.warningCount() == 1 ? "" : "s",
                                 wrote ? "output may be incomplete" : "nothing written");
}

// Where the templates are: --templates, $RELIEF_TEMPLATES, the installed
// share/relief/templates beside the binary, or the source tree.
fs::path findTemplates(const std::string& option) {
    if (!option.empty()) return option;
    if (const char* env = std::getenv("RELIEF_TEMPLATES")) return env;
    std::error_code ec;
    const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
    if (!ec) {
        // <prefix>/bin/relief, or <prefix>/libexec/relief/relief-images
        for (fs::path prefix = exe.parent_path().parent_path(); !prefix.empty() && prefix != prefix.root_path();
             prefix = prefix.parent_path()) {
            const fs::path installed = prefix / "share/relief/templates";
            if (fs::exists(installed / "scene.pov.in", ec)) return installed;
            if (prefix.filename() != "libexec") break;
        }
    }
    return RELIEF_SOURCE_TEMPLATES_DIR;
}



const ImageCommandInfo kImageCommands[3] = {
    {"diff", "compare two images (OpenImageIO), with idiff's thresholds and exit codes: "
             "0 PASS, 1 WARNING, 2 FAILURE, 3 not comparable (different sizes or channel "
             "counts), 4 file error or bad arguments"},
    {"test", "render every case of a manifest, compare with its reference images, write an "
             "HTML report (and summary.json, junit.xml); exit 1 when a case fails"},
    {"sweep", "render one still per combination of --vary values and assemble a labelled "
              "contact sheet (one PNG)"},
};

bool isImageCommand(const char* name) {
    for (const auto& c : kImageCommands)
        if (std::strcmp(name, c.name) == 0) return true;
    return false;
}

int runCommands(CLI::App& app, const std::vector<Command>& commands, int argc, char** argv) {
    try {
        app.parse(argc, argv);
    } catch (const CLI::Success& e) {
        return app.exit(e);
    } catch (const CLI::ParseError& e) {
        app.exit(e);
        for (const auto& c : commands)
            if (c.app->parsed()) return c.parseErrorCode;
        return code(Exit::BadInput);
    }
    try {
        for (const auto& c : commands)
            if (c.app->parsed()) return c.run();
        return code(Exit::BadInput);
    } catch (const relief::OutputError& e) {
        std::cerr << terminalText(e.file().string()) << ": error: " << terminalText(e.problem())
                  << "\nrelief: nothing written\n";
        return code(Exit::BadInput);
    } catch (const std::runtime_error& e) {  // other I/O
        std::cerr << "relief: error: " << terminalText(e.what()) << "\nrelief: nothing written\n";
        return code(Exit::BadInput);
    } catch (const std::exception& e) {
        std::cerr << "relief: internal error: " << terminalText(e.what()) << '\n';
        return code(Exit::Internal);
    }
}

void raiseOpenFileLimit() {
    // Capped: a child that closes every descriptor it might have (not POV-Ray, which relief
    // starts with close_range) would loop over a hard limit of 2^30.
    constexpr rlim_t kEnough = 65536;
    struct rlimit files {};
    if (::getrlimit(RLIMIT_NOFILE, &files) != 0 || files.rlim_cur >= std::min(files.rlim_max, kEnough)) return;
    files.rlim_cur = std::min(files.rlim_max, kEnough);
    ::setrlimit(RLIMIT_NOFILE, &files);  // best effort: a refusal leaves the limit as it was
}

void addTilesOption(CLI::App* app, ExecutionOptions& o) {
    app->add_option("--tiles", o.tiles, "strips of the still, each rendered by its own POV-Ray (default 1); "
                                        "the same bytes for any number")
        ->check(CLI::Range(1, 100000));
}

void addExecutionOptions(CLI::App* app, ExecutionOptions& o, bool tiles, const char* jobsHelp) {
    if (tiles) addTilesOption(app, o);
    app->add_option("--jobs,-j", o.jobs, jobsHelp)->check(CLI::Range(0, 100000));
    app->add_option("--executor", o.executor, "where the renders run: local (this machine, default) or slurm (a "
                                              "job array on the cluster SLURM_CONF names; docs/distributed.md)")
        ->check(CLI::IsMember({"local", "slurm"}));
    app->add_option("--slurm-args", o.slurmArgs, "passed to sbatch, e.g. \"--partition=batch --time=30\"");
}

namespace {
std::atomic<int> gSignals{0};
void onInterrupt(int) {
    if (gSignals.fetch_add(1) > 0) ::_exit(code(Exit::Interrupted));  // a second Ctrl-C: at once
}
}  // namespace

void installInterruptHandler() {
    struct sigaction sa {};
    sa.sa_handler = onInterrupt;
    sigemptyset(&sa.sa_mask);
    sigaction(SIGINT, &sa, nullptr);
    sigaction(SIGTERM, &sa, nullptr);
}

bool interrupted() { return gSignals.load() > 0; }

execute::Options executionOf(const ExecutionOptions& o, bool noSandbox) {
    execute::Options e;
    e.executor = o.executor == "slurm" ? execute::Executor::Slurm : execute::Executor::Local;
    e.jobs = o.jobs;
    e.slurmArgs = o.slurmArgs;
    e.sandbox = !noSandbox;
    if (noSandbox)  // the only way to turn it off, and never quietly
        std::cerr << "relief: warning: POV-Ray runs outside its sandbox (--no-sandbox): a .pov can then read and "
                     "write any file you can; use it only for scenes and plans you trust\n";
    e.cancelled = [] { return interrupted(); };
    return e;
}

// KEY=VALUE strings -> scene overrides (`section.key=value`).
bool parseOverrides(const std::vector<std::string>& list, scene::SceneOverrides& out) {
    for (const auto& kv : list) {
        const auto eq = kv.find('=');
        if (eq == std::string::npos || eq == 0) {
            std::cerr << "relief: error: " << terminalText(kv, 200) << ": write section.key=value, e.g. subdivision.omega=1/32\n";
            return false;
        }
        out.emplace_back(kv.substr(0, eq), kv.substr(eq + 1));
    }
    return true;
}

Progress::Progress(bool quiet) : quiet_(quiet), tty_(::isatty(STDERR_FILENO)) {}

void Progress::show(const std::string& text, int percent) {
    if (quiet_) return;
    const std::string line = terminalText(text, 400);  // POV-Ray's lines and paths: text, never terminal commands
    if (tty_) {
        std::cerr << "\r\033[K" << line << std::flush;
        open_ = true;
    } else if (line != last_) {
        // Not a terminal (a log): stage lines, and render progress per 10 %.
        if (percent < 0 || percent / 10 != lastDecile_) std::cerr << line << '\n';
        lastDecile_ = percent < 0 ? -1 : percent / 10;
    }
    last_ = line;
}

void Progress::show(const relief::ProgressEvent& e) {
    const bool rendering = e.stage == relief::ProgressEvent::Stage::Rendering;
    // POV-Ray's own lines carry their percentage (and change with it): the stage is the task.
    const std::string task = rendering ? std::string("povray") : e.text;
    const auto now = std::chrono::steady_clock::now();
    if (task != task_) {
        task_ = task;
        taskStart_ = now;
        firstPercent_ = -1;
    }
    if (e.percent >= 0 && firstPercent_ < 0) {
        firstPercent_ = e.percent;
        firstPercentAt_ = now;
    }
    std::string line = rendering ? "povray: " + e.text
                                 : e.percent < 0 ? e.text : fmt::format("{} ({}%)", e.text, e.percent);
    // On a terminal: seconds spent on the task, and those left at the rate since its first percentage.
    if (tty_ && e.percent > firstPercent_ && e.percent < 100) {
        const auto seconds = [](auto d) { return std::chrono::duration<double>(d).count(); };
        const double rate = (e.percent - firstPercent_) / seconds(now - firstPercentAt_);
        const double left = (100 - e.percent) / rate;
        line += fmt::format(", {:.0f} s, {}", seconds(now - taskStart_),
                            left < 1 ? std::string("under a second left") : fmt::format("about {:.0f} s left", left));
    }
    show(line, e.percent);
}

std::string keptForResume(std::string_view what, std::string_view command, const fs::path& dir) {
    if (dir.empty()) return "";
    return fmt::format("relief: {} kept: relief {} --resume {} renders what is missing\n", what, command,
                       terminalText(shellQuoted(dir.string()), 500));
}

ProgressFn showing(Progress& progress) {
    return [&](const relief::ProgressEvent& e) {
        // Each stage on a line of its own; the render's progress rewrites its line.
        if ((e.stage == relief::ProgressEvent::Stage::Compiling || e.stage == relief::ProgressEvent::Stage::Finishing) &&
            e.percent < 0)
            progress.done();
        progress.show(e);
    };
}

void Progress::done() {
    if (open_) std::cerr << "\r\033[K" << std::flush;
    open_ = false;
}

// KEY=VALUE list (values may be fractions) -> map; false with a message on bad input.
bool parseParams(const std::vector<std::string>& list, std::map<std::string, double>& out) {
    for (const auto& kv : list) {
        const auto eq = kv.find('=');
        const auto value = eq == std::string::npos
                               ? std::nullopt
                               : scene::parseFraction(kv.substr(eq + 1));
        if (!value) {
            std::cerr << "relief: error: " << terminalText(kv, 200)
                      << ": write KEY=VALUE, the value a number or a fraction such as 7/32\n";
            return false;
        }
        out[kv.substr(0, eq)] = *value;
    }
    return true;
}

std::vector<std::string> split(const std::string& s, char sep) {
    std::vector<std::string> out;
    size_t start = 0;
    while (true) {
        const size_t e = s.find(sep, start);
        out.push_back(s.substr(start, e == std::string::npos ? std::string::npos : e - start));
        if (e == std::string::npos) break;
        start = e + 1;
    }
    return out;
}

nlohmann::ordered_json jsonNumber(double v) {
    return std::isfinite(v) ? nlohmann::ordered_json(v) : nlohmann::ordered_json("inf");
}

std::optional<GeoPoint> parseLonLat(const std::string& text) {
    const auto parts = split(text, ',');
    if (parts.size() != 2) return std::nullopt;
    char* end = nullptr;
    GeoPoint p;
    p.lonDeg = std::strtod(parts[0].c_str(), &end);
    if (end == parts[0].c_str() || *end) return std::nullopt;
    p.latDeg = std::strtod(parts[1].c_str(), &end);
    if (end == parts[1].c_str() || *end) return std::nullopt;
    if (!(std::fabs(p.latDeg) <= 90 && std::fabs(p.lonDeg) <= 180)) return std::nullopt;
    return p;
}

}  // namespace relief::cli
