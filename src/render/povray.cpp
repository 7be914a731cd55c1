#include "render/povray.h"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/syscall.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <cstdio>
#include <deque>
#include <fstream>
#include <optional>
#include <regex>
#include <thread>

#include <fmt/format.h>

#include "core/atomic_file.h"
#include "core/output_set.h"
#include "core/png_file.h"
#include "core/stopwatch.h"

extern char** environ;

namespace relief::render {

namespace {

// A private folder for POV-Ray, removed when done: its HOME and POVINI (so it
// reads no user or system configuration, and the I/O-restriction config we
// give it keeps it from warning), its output, and links to what it reads
// under fixed names: no user path ever reaches POV-Ray's option parser,
// which splits at spaces and takes "+UA" in a folder name for a switch.
class PovrayHome {
public:
    explicit PovrayHome(const RenderRequest& req) : folder_(makeFolder()) {
        namespace fs = std::filesystem;
        const fs::path& dir = folder_.path();
        fs::create_directories(dir / ".povray" / "3.7");
        writeFileAtomically(dir / ".povray" / "3.7" / "povray.conf", "[File I/O Security]\nnone\n");
        writeFileAtomically(dir / "povray.ini", "");
        fs::create_directory(dir / "inputs");
        fs::create_symlink(fs::absolute(req.pov), scene());
        if (!req.templatesDir.empty()) fs::create_directory_symlink(fs::absolute(req.templatesDir), templates());
        for (const auto& f : req.inputFiles) fs::create_symlink(fs::absolute(f), inputs() / f.filename());
    }
    const std::filesystem::path& dir() const { return folder_.path(); }
    std::filesystem::path scene() const { return dir() / "scene.pov"; }
    std::filesystem::path templates() const { return dir() / "templates"; }
    std::filesystem::path inputs() const { return dir() / "inputs"; }
    std::filesystem::path output() const { return dir() / "render.png"; }

private:
    static PrivateFolder makeFolder() {
        removeAbandonedFolders(kParent);  // the folders of runs that were killed
        return PrivateFolder(kParent, "povray");
    }
    static constexpr const char* kParent = "/tmp";
    PrivateFolder folder_;
};

// "Rendered 5120 of 480000 pixels (1%)" -> 1; -1 without a percentage.
int tracedPercent(const std::string& line) {
    const auto open = line.rfind('(');
    if (open == std::string::npos) return -1;
    int pct = -1;
    if (std::sscanf(line.c_str() + open, "(%d%%)", &pct) != 1) return -1;
    return pct;
}

double parseSeconds(const std::string& log, const char* label) {
    // "  Parse Time:       0 hours  0 minutes  1 seconds (1.234 seconds)"
    const std::regex re(std::string(label) + R"(:\s+\d+ hours\s+\d+ minutes\s+\d+ seconds \(([0-9.]+) seconds\))");
    std::smatch m;
    return std::regex_search(log, m, re) ? std::atof(m[1].str().c_str()) : 0.0;
}

// POV-Ray's own error text: everything from its first error line on, e.g.
// "File 'x.pov' line 29: Parse Error: No matching } in 'pigment', ...". POV-Ray
// wraps its messages at 80 columns, continuing with a leading space: unwrap.
std::string errorText(const std::deque<std::string>& lines) {
    static const std::regex first(R"(^File '.*' line \d+:|[Ee]rror)");
    size_t start = lines.size();
    for (size_t i = 0; i < lines.size(); ++i) {
        // Skip the option echo ("Input file: ...", paths that contain "error").
        if (lines[i].rfind("  ", 0) == 0) continue;
        if (std::regex_search(lines[i], first)) {
            start = i;
            break;
        }
    }
    if (start == lines.size()) start = lines.size() > 8 ? lines.size() - 8 : 0;
    std::string out;
    for (size_t i = start; i < lines.size(); ++i) {
        // A line POV-Ray filled to its 80 columns goes on in the next (mid-word when a
        // path is longer than a line); a break at a space leaves the space at the start.
        const bool full = i > start && lines[i - 1].size() >= 80;
        if (full || (i > start && lines[i].rfind(' ', 0) == 0 && lines[i].rfind("  ", 0) != 0))
            out += lines[i];  // continuation of a wrapped line
        else
            out += (out.empty() ? "" : "\n") + lines[i];
    }
    return out;
}

// The bubblewrap command line that runs `command` with only what a render
// needs: the system's programs and libraries read-only, the inputs read-only
// at their own paths (so the .pov's references stay valid), `privateDir`
// writable, fresh /dev, /proc and /tmp, and no network, IPC, PID or user
// namespace shared with the host.
std::vector<std::string> sandboxed(const std::string& bwrap, const std::filesystem::path& privateDir,
                                   const std::vector<std::filesystem::path>& readOnly,
                                   const std::vector<std::string>& env, const std::vector<std::string>& command) {
    namespace fs = std::filesystem;
    // Not --unshare-all: its user namespace cannot be made inside a chroot even by root
    // (EPERM), and bubblewrap makes one anyway when it runs unprivileged.
    std::vector<std::string> a{bwrap,           "--unshare-ipc",   "--unshare-pid",  "--unshare-net",
                               "--unshare-uts", "--unshare-cgroup-try", "--die-with-parent", "--new-session",
                               "--cap-drop",    "ALL",             "--ro-bind",      "/usr",
                               "/usr"};
    std::error_code ec;
    // Debian's merged /usr: /bin, /lib, ... are links into it.
    for (const char* top : {"/bin", "/sbin", "/lib", "/lib32", "/lib64", "/libx32"}) {
        if (fs::is_symlink(top, ec)) a.insert(a.end(), {"--symlink", fs::read_symlink(top, ec).string(), top});
        else if (fs::is_directory(top, ec)) a.insert(a.end(), {"--ro-bind", top, top});
    }
    a.insert(a.end(), {"--ro-bind-try", "/etc/ld.so.cache", "/etc/ld.so.cache", "--ro-bind-try",
                       "/sys/devices/system/cpu", "/sys/devices/system/cpu", "--proc", "/proc", "--dev", "/dev",
                       "--tmpfs", "/tmp"});
    for (const auto& path : readOnly) {
        const auto absolute = fs::absolute(path, ec);
        a.insert(a.end(), {"--ro-bind", absolute.string(), absolute.string()});
    }
    a.insert(a.end(), {"--bind", privateDir.string(), privateDir.string(), "--chdir", privateDir.string(),
                       "--clearenv"});
    for (const auto& kv : env) {
        const auto eq = kv.find('=');
        a.insert(a.end(), {"--setenv", kv.substr(0, eq), kv.substr(eq + 1)});
    }
    a.push_back("--");
    a.insert(a.end(), command.begin(), command.end());
    return a;
}

// Starts argv[0] with `envp`, stdin from /dev/null, stdout and stderr into
// `outFd`, no other file open. The child is killed when the thread that
// started it ends (PR_SET_PDEATHSIG; relief killed, even with SIGKILL):
// POV-Ray never outlives the run, sandboxed or not, as long as the thread
// that starts it waits for it (renderPov does). Returns 0 or the errno of what
// failed (exec's, through a pipe).
int spawnChild(char* const* argv, char* const* envp, int outFd, pid_t& pid) {
    int status[2];
    if (::pipe2(status, O_CLOEXEC) != 0) return errno;
    const pid_t parent = ::getpid();
    // A bare clone, not fork(): fork runs the libraries' atfork handlers in the child (PROJ's
    // frees memory), whose allocator lock another of relief's threads may hold at that moment
    // (tiles render on several threads): under AddressSanitizer the child then spins forever.
    // The child below makes only system calls before exec.
    pid = static_cast<pid_t>(::syscall(SYS_clone, SIGCHLD, nullptr, nullptr, nullptr, nullptr));
    if (pid < 0) {
        const int err = errno;
        ::close(status[0]), ::close(status[1]);
        return err;
    }
    if (pid == 0) {  // only async-signal-safe calls until exec
        ::prctl(PR_SET_PDEATHSIG, SIGKILL);
        if (::getppid() != parent) ::_exit(127);  // the parent died before prctl took hold
        // stdin, stdout, stderr, the status pipe as fd 3 (closed by exec), and no other file
        // of relief's (a GDAL dataset, another case's PNG): POV-Ray could read it through /proc.
        const int in = ::open("/dev/null", O_RDONLY);
        const bool ready = in >= 0 && ::dup2(in, STDIN_FILENO) >= 0 && ::dup2(outFd, STDOUT_FILENO) >= 0 &&
                           ::dup2(outFd, STDERR_FILENO) >= 0 && ::dup2(status[1], 3) >= 0 &&
                           ::fcntl(3, F_SETFD, FD_CLOEXEC) == 0 && ::close_range(4, ~0U, 0) == 0;
        if (ready) ::execve(argv[0], argv, envp);
        const int err = errno;
        (void)!::write(ready ? 3 : status[1], &err, sizeof err);
        ::_exit(127);
    }
    ::close(status[1]);
    int err = 0;
    ssize_t n;
    while ((n = ::read(status[0], &err, sizeof err)) < 0 && errno == EINTR) {
    }
    ::close(status[0]);
    if (n == static_cast<ssize_t>(sizeof err)) {  // exec failed: the child is gone
        while (::waitpid(pid, nullptr, 0) < 0 && errno == EINTR) {
        }
        return err;
    }
    return 0;
}

}  // namespace

std::string findOnPath(const std::string& name) {
    const char* path = std::getenv("PATH");
    if (!path) return "";
    std::string p(path);
    size_t start = 0;
    while (start <= p.size()) {
        size_t end = p.find(':', start);
        if (end == std::string::npos) end = p.size();
        const auto candidate = std::filesystem::path(p.substr(start, end - start)) / name;
        if (::access(candidate.c_str(), X_OK) == 0) return candidate.string();
        start = end + 1;
    }
    return "";
}

namespace {

// POV-Ray's command line: only fixed names in its private folder, and the still's options.
std::vector<std::string> povrayArguments(const RenderRequest& req, const PovrayHome& home, const std::string& povray) {
    std::vector<std::string> args{povray,
                                  "+I" + home.scene().string(),
                                  "+O" + home.output().string(),
                                  fmt::format("+W{}", req.width),
                                  fmt::format("+H{}", req.height),
                                  "-D",
                                  "+FN8",
                                  "-P"};
    // Adaptive anti-aliasing without jitter: pixels do not depend on the thread count,
    // nor on the rows rendered with them (a tile's pixels are the whole still's).
    if (req.antialias)
        args.insert(args.end(), {fmt::format("+A{}", req.antialiasThreshold), "+AM2",
                                 fmt::format("+R{}", req.antialiasDepth), "-J"});
    else args.push_back("-A");
    if (req.alpha) args.push_back("+UA");
    if (req.threads > 0) args.push_back(fmt::format("+WT{}", req.threads));
    if (req.rows) args.insert(args.end(), {fmt::format("+SR{}", req.rows->first), fmt::format("+ER{}", req.rows->last)});
    if (!req.templatesDir.empty()) args.push_back("+L" + home.templates().string());
    args.push_back("+L" + home.inputs().string());
    return args;
}

// The environment POV-Ray gets: its own HOME and POVINI; in the sandbox, only
// PATH, LANG and LC_* of the user's.
std::vector<std::string> povrayEnvironment(const RenderRequest& req, const PovrayHome& home) {
    std::vector<std::string> env;
    for (char** e = environ; *e; ++e) {
        const std::string kv(*e);
        if (kv.rfind("HOME=", 0) == 0 || kv.rfind("POVINI=", 0) == 0) continue;
        if (req.sandbox && kv.rfind("PATH=", 0) != 0 && kv.rfind("LANG=", 0) != 0 && kv.rfind("LC_", 0) != 0)
            continue;
        env.push_back(kv);
    }
    env.push_back("HOME=" + home.dir().string());
    env.push_back("POVINI=" + (home.dir() / "povray.ini").string());
    return env;
}

// What watching POV-Ray saw: its lines (the last 200), its log, how it ended.
struct Watched {
    std::string log;
    std::deque<std::string> lastLines;
    int status = 0;
    bool timedOut = false, cancelled = false;
    double peakMemoryBytes = 0;  ///< the largest resident size of POV-Ray (or the sandbox holding it)
};

// The largest resident size any process of the tree under `pid` has had so
// far (VmHWM), in bytes. Read from /proc, because the usage wait4 gives stops
// at bubblewrap's own process when the sandbox has its own process ids.
double treePeakBytes(pid_t pid) {
    double most = 0;
    std::vector<long> todo{pid};
    for (size_t seen = 0; !todo.empty() && seen < 64; ++seen) {
        const long p = todo.back();
        todo.pop_back();
        std::ifstream status(fmt::format("/proc/{}/status", p));
        for (std::string line; std::getline(status, line);)
            if (line.rfind("VmHWM:", 0) == 0) most = std::max(most, 1024.0 * std::atof(line.c_str() + 6));
        std::ifstream children(fmt::format("/proc/{}/task/{}/children", p, p));
        for (long child; children >> child;) todo.push_back(child);
    }
    return most;
}

// Reads POV-Ray's output until it ends, telling `progress` what it does;
// stops it (SIGKILL: the sandbox goes with it, --die-with-parent) past the
// request's time limit or when the request is cancelled.
Watched watch(pid_t pid, int fd, const RenderRequest& req, std::chrono::steady_clock::time_point t0,
              const ProgressFn& progress) {
    Watched w;
    std::string current;
    char buf[4096];
    static const std::regex parsing(R"(^Parsing \d+K tokens)");
    const auto deadline = t0 + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                   std::chrono::duration<double>(req.timeoutSeconds));
    auto lastSample = t0;
    while (true) {
        int waitMs = 200;  // how often a cancellation is looked for
        if (req.timeoutSeconds > 0) {
            const auto left =
                std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now());
            if (left.count() <= 0) {
                ::kill(pid, SIGKILL);
                w.timedOut = true;
                break;
            }
            waitMs = static_cast<int>(std::min<long long>(waitMs, left.count()));
        }
        if (req.cancelled && req.cancelled()) {
            ::kill(pid, SIGKILL);
            w.cancelled = true;
            break;
        }
        if (const auto now = std::chrono::steady_clock::now(); now - lastSample > std::chrono::milliseconds(50)) {
            w.peakMemoryBytes = std::max(w.peakMemoryBytes, treePeakBytes(pid));
            lastSample = now;
        }
        pollfd pfd{fd, POLLIN, 0};
        const int ready = ::poll(&pfd, 1, waitMs);
        if (ready < 0 && errno == EINTR) continue;
        if (ready == 0) continue;
        const ssize_t n = ::read(fd, buf, sizeof buf);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) break;
        w.log.append(buf, static_cast<size_t>(n));
        // POV-Ray ends progress lines with '\r' and the rest with '\n'.
        for (ssize_t i = 0; i < n; ++i) {
            const char ch = buf[i];
            if (ch != '\r' && ch != '\n') {
                current.push_back(ch);
                continue;
            }
            if (current.empty()) continue;
            if (progress) {
                using Phase = RenderProgress::Phase;
                if (current.rfind("Rendered ", 0) == 0)
                    progress({Phase::Tracing, current, tracedPercent(current)});
                else if (std::regex_search(current, parsing))
                    progress({Phase::Parsing, current, -1});
                else if (current.find("[Parsing...]") != std::string::npos)
                    progress({Phase::Parsing, "parsing the scene", -1});
                else if (current.find("[Rendering...]") != std::string::npos)
                    progress({Phase::Tracing, "tracing", -1});
            }
            w.lastLines.push_back(current);
            if (w.lastLines.size() > 200) w.lastLines.pop_front();
            current.clear();
        }
    }
    if (!current.empty()) w.lastLines.push_back(current);
    while (::waitpid(pid, &w.status, 0) < 0 && errno == EINTR) {
    }
    // Ctrl-C in a terminal reaches POV-Ray too (one process group): it may end before the loop
    // above saw the cancellation, and its end is then the interruption's, not a failure.
    if (req.cancelled && req.cancelled()) w.cancelled = true;
    return w;
}

// Why POV-Ray gave no image: bubblewrap's failure, or POV-Ray's own words.
std::string failureText(const Watched& w, const RenderRequest& req, const PovrayHome& home) {
    // bubblewrap's own failure (e.g. no user namespaces here) comes before POV-Ray's output.
    if (req.sandbox && !w.lastLines.empty() && w.lastLines.front().rfind("bwrap: ", 0) == 0)
        return fmt::format("the sandbox for POV-Ray cannot start here ({}); render without it (--no-sandbox) only "
                           "a scene you trust",
                           w.lastLines.front());
    std::string error = errorText(w.lastLines);
    // POV-Ray names its input by the private folder's link: "File 'scene.pov' line 12" says enough.
    const std::string privatePrefix = home.dir().string() + "/";
    for (size_t at; (at = error.find(privatePrefix)) != std::string::npos;) error.erase(at, privatePrefix.size());
    if (!error.empty()) return error;
    return WIFEXITED(w.status) ? fmt::format("povray exited with status {}", WEXITSTATUS(w.status))
                               : "povray was killed by a signal";
}

// POV-Ray's image where the request wants it: re-encoded canonically (the
// whole image, or a tile's own rows only, so that stitching reads each pixel
// once however many tiles there are), or, whole, as POV-Ray wrote it (to be
// re-encoded once, when the still is finished).
std::string deliver(const std::filesystem::path& raw, const RenderRequest& req) {
    if (!req.rows && !req.rawOutput) return writeCanonicalPng(raw, req.png);
    try {
        if (!req.rows) {
            writeThroughTemporary(req.png, [&](const std::filesystem::path& staged) { return copyFileContents(raw, staged); });
            return "";
        }
        PngImage8 image;
        if (std::string error = readPng8(raw, image); !error.empty()) return error;
        const size_t rowBytes = static_cast<size_t>(image.width) * image.channels;
        const int rows = req.rows->last - req.rows->first + 1;
        if (req.rows->first < 1 || req.rows->last > image.height || rows < 1)
            return "POV-Ray's image has not the rows asked for";
        writePngAtomically(req.png, {image.width, rows, image.channels, false,
                                     image.pixels.data() + (req.rows->first - 1) * rowBytes});
    } catch (const OutputError& e) {
        return e.what();
    }
    return "";
}

// POV-Ray's front end gives up when its worker thread is slow to start
// (vfeInitializeTimedOut, seen on a loaded machine). That is no fault of the
// scene's, so such a run is tried again, up to kStartAttempts in all.
constexpr int kStartAttempts = 3;

bool workerStartTimedOut(const Watched& w) {
    const bool exitedNonZero = WIFEXITED(w.status) && WEXITSTATUS(w.status) != 0;
    return !w.cancelled && !w.timedOut && exitedNonZero &&
           w.log.find("Timed out waiting for worker thread startup") != std::string::npos;
}

// One run of POV-Ray (argv, envp: made by the caller), watched to its end
// into `w`. "" or why it could not start.
std::string runPovray(std::vector<char*>& argv, std::vector<char*>& envp, const RenderRequest& req,
                      std::chrono::steady_clock::time_point t0, const ProgressFn& progress, Watched& w) {
    int pipeFd[2];
    if (::pipe2(pipeFd, O_CLOEXEC) != 0) return "cannot create a pipe";
    pid_t pid = 0;
    const int spawnErr = spawnChild(argv.data(), envp.data(), pipeFd[1], pid);
    ::close(pipeFd[1]);
    if (spawnErr != 0) {
        ::close(pipeFd[0]);
        return fmt::format("cannot run {}: {}", argv[0], std::strerror(spawnErr));
    }
    w = watch(pid, pipeFd[0], req, t0, progress);
    ::close(pipeFd[0]);
    return "";
}

}  // namespace

RenderResult renderPov(const RenderRequest& req, const ProgressFn& progress) {
    RenderResult result;
    const auto t0 = Clock::now();
    const std::string povray = findOnPath("povray");
    if (povray.empty()) {
        result.error = "povray is not installed (on Debian: apt-get install povray)";
        return result;
    }
    const std::string bwrap = req.sandbox ? findOnPath("bwrap") : std::string();
    if (req.sandbox && bwrap.empty()) {
        result.error = "POV-Ray runs in a bubblewrap sandbox, and bwrap is not installed: apt-get install "
                       "bubblewrap, or render without the sandbox (--no-sandbox) only a scene you trust";
        return result;
    }
    std::optional<PovrayHome> made;
    try {
        made.emplace(req);
    } catch (const std::exception& e) {  // /tmp full or not writable: not POV-Ray's failure
        result.error = fmt::format("cannot prepare POV-Ray's private folder in /tmp: {}", e.what());
        result.cannotWriteOutput = true;
        return result;
    }
    const PovrayHome& home = *made;
    std::vector<std::string> args = povrayArguments(req, home, povray);
    result.command = args;
    std::vector<std::string> env = povrayEnvironment(req, home);
    if (req.sandbox) {
        // The files themselves, at their own paths (the links lead there), never their folders.
        std::vector<std::filesystem::path> readOnly{req.pov};
        if (!req.templatesDir.empty()) readOnly.push_back(req.templatesDir);
        readOnly.insert(readOnly.end(), req.inputFiles.begin(), req.inputFiles.end());
        if (!povray.starts_with("/usr/")) readOnly.push_back(povray);
        args = sandboxed(bwrap, home.dir(), readOnly, env, args);
    }
    std::vector<char*> envp, argv;
    for (auto& e : env) envp.push_back(e.data());
    envp.push_back(nullptr);
    for (auto& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);

    Watched w;
    for (int attempt = 1;; ++attempt) {
        if (std::string cannotRun = runPovray(argv, envp, req, t0, progress, w); !cannotRun.empty()) {
            result.error = cannotRun;
            return result;
        }
        if (attempt == kStartAttempts || !workerStartTimedOut(w)) break;
        if (progress) progress({RenderProgress::Phase::Parsing, "POV-Ray's worker thread was slow to start: again", -1});
        std::this_thread::sleep_for(std::chrono::milliseconds(500));
    }
    if (w.cancelled) {
        result.cancelled = true;
        result.error = "stopped";
        return result;
    }
    if (w.timedOut) {
        result.error = fmt::format("POV-Ray did not finish within render.timeout_s = {} s and was stopped; "
                                   "raise the limit, or lower the resolution or subdivision.depth",
                                   req.timeoutSeconds);
        return result;
    }
    result.parseSeconds = parseSeconds(w.log, "Parse Time");
    result.traceSeconds = parseSeconds(w.log, "Trace Time");
    result.peakMemoryBytes = w.peakMemoryBytes;
    std::error_code ec;
    if (!(WIFEXITED(w.status) && WEXITSTATUS(w.status) == 0) || !std::filesystem::exists(home.output(), ec)) {
        result.error = failureText(w, req, home);
        return result;
    }
    if (const std::string pngError = deliver(home.output(), req); !pngError.empty()) {
        result.error = pngError;
        result.cannotWriteOutput = true;
        return result;
    }
    result.ok = true;
    result.wallSeconds = secondsSince(t0);
    return result;
}

}  // namespace relief::render
