#include "serve/preview_server.h"

#include <httplib.h>
#include <pthread.h>
#include <signal.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <memory>
#include <mutex>
#include <optional>
#include <random>
#include <thread>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "core/atomic_file.h"
#include "core/input_file.h"
#include "core/number_format.h"
#include "core/stopwatch.h"
#include "execute/command.h"
#include "serve/web_assets.h"

namespace relief::serve {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

constexpr const char* kLoopback = "127.0.0.1";

// 128 random bits as hex: the URL's secret, which a page of another site or another user of the
// machine cannot guess, so that only the person who started relief can use (and write through) it.
std::string randomToken() {
    std::random_device device;
    std::string token;
    for (int i = 0; i < 4; ++i) token += fmt::format("{:08x}", device());
    return token;
}

// The scene as last built: the preview, or the diagnostics that stopped it, and its number.
struct Built {
    std::optional<PreviewScene> preview;
    std::string diagnostics;  // one per line, as the terminal prints them
    int generation = 0;
};

std::string diagnosticsText(const Diagnostics& diags) {
    std::string text;
    for (const auto& d : diags.all()) text += formatDiagnostic(d) + "\n";
    return text;
}

// What identifies a version of the scene file: its time and size (the file being replaced as an
// editor saves shows as a change, as does one that vanished).
std::string fileStamp(const fs::path& path) {
    std::error_code ec;
    const auto time = fs::last_write_time(path, ec);
    if (ec) return "absent";
    const auto size = fs::file_size(path, ec);
    return fmt::format("{}:{}", time.time_since_epoch().count(), ec ? 0 : size);
}

// A view the page sent: three finite numbers for the eye and the target, a field of view.
std::optional<PageView> pageViewOf(const json& body) {
    const auto vec = [&](const char* key) -> std::optional<Vec3> {
        const auto it = body.find(key);
        if (it == body.end() || !it->is_array() || it->size() != 3) return std::nullopt;
        for (const auto& v : *it)
            if (!v.is_number() || !std::isfinite(v.get<double>())) return std::nullopt;
        return Vec3{(*it)[0].get<double>(), (*it)[1].get<double>(), (*it)[2].get<double>()};
    };
    const auto eye = vec("eye"), target = vec("target");
    const auto fov = body.find("fovDeg");
    if (!eye || !target || fov == body.end() || !fov->is_number()) return std::nullopt;
    return PageView{*eye, *target, fov->get<double>()};
}

std::string tomlLines(const CameraKeys& keys) {
    std::string text;
    for (const auto& [key, value] : keys.toml()) text += key + " = " + value + "\n";
    return text;
}

class PreviewServer {
public:
    PreviewServer(const PreviewServeJob& job, const ServeLog& log) : job_(job), log_(log), token_(randomToken()) {}

    bool bind(Diagnostics& diags) {
        routes();
        port_ = job_.port ? (server_.bind_to_port(kLoopback, job_.port) ? job_.port : -1) : server_.bind_to_any_port(kLoopback);
        if (port_ > 0) return true;
        diags.error({"--port", 0, 0}, fmt::format("relief preview cannot listen on {}:{}: the port is taken or not "
                                                  "allowed; give another with --port, or none for a free one",
                                                  kLoopback, job_.port));
        return false;
    }
    std::string url() const { return fmt::format("http://{}:{}/{}/", kLoopback, port_, token_); }

    // Serves until stop(), the scene built meanwhile (a browser starting up, loading the page and
    // its script, does so while relief builds the model: what the page asks of the scene waits
    // for it), then rebuilt whenever its file changes.
    void run() {
        std::thread builder([this] {
            rebuild();
            watch();
        });
        server_.listen_after_bind();
        {
            std::lock_guard lock(mutex_);
            stopping_ = true;
        }
        wake_.notify_all();
        builder.join();
        if (renderThread_.joinable()) renderThread_.join();
    }
    // Stops serving: requests waiting for a build are answered (with nothing), the server ends.
    void stop() {
        {
            std::lock_guard lock(mutex_);
            stopping_ = true;
        }
        wake_.notify_all();
        server_.stop();
    }
    bool listening() const { return server_.is_running(); }

private:
    const fs::path& scenePath() const { return job_.preview.scenePath; }

    void rebuild() {
        {
            std::lock_guard lock(mutex_);
            building_ = true;
        }
        const std::string stamp = fileStamp(scenePath());
        const auto t0 = Clock::now();
        Diagnostics diags;
        auto built = std::make_shared<Built>();
        built->preview = previewScene(job_.preview, diags);
        built->diagnostics = diagnosticsText(diags);
        if (!built->preview) log_(fmt::format("the scene does not compile:\n{}", built->diagnostics));
        else log_(fmt::format("the model: {} triangles{}, {:.1f} MB, made in {:.2f} s",
                              built->preview->page["model"]["triangles"].get<size_t>(),
                              built->preview->page["model"]["toleranceM"].get<double>() > 0
                                  ? fmt::format(" (an adaptive mesh within {:.3g} m of the still's surface)",
                                                built->preview->page["model"]["toleranceM"].get<double>())
                                  : std::string(),
                              built->preview->glb.size() / 1e6, secondsSince(t0)));
        {
            std::lock_guard lock(mutex_);
            built->generation = built_ ? built_->generation + 1 : 1;
            built_ = std::move(built);
            stamp_ = stamp;
            building_ = false;
        }
        wake_.notify_all();
    }

    // Every half second, the scene file's stamp; a new one rebuilds the preview. relief's own write
    // and the stamp it records are seen together (writeMutex_, then mutex_, as a write takes them).
    void watch() {
        std::unique_lock lock(mutex_);
        while (!stopping_) {
            wake_.wait_for(lock, std::chrono::milliseconds(500));
            if (stopping_) break;
            lock.unlock();
            bool changed = false;
            {
                std::lock_guard writing(writeMutex_);
                std::lock_guard state(mutex_);
                changed = fileStamp(scenePath()) != stamp_;
            }
            if (changed) {
                log_(fmt::format("{} changed: rebuilding the preview", scenePath().string()));
                rebuild();
            }
            lock.lock();
        }
    }

    // The scene as last built, waiting for the first build.
    std::shared_ptr<const Built> built() {
        std::unique_lock lock(mutex_);
        wake_.wait(lock, [this] { return built_ || stopping_; });
        return built_ ? built_ : std::make_shared<const Built>();
    }

    static void reply(httplib::Response& res, int status, const json& body) {
        res.status = status;
        res.set_header("Cache-Control", "no-store");
        res.set_content(body.dump(-1, ' ', false, json::error_handler_t::replace), "application/json");
    }

    // The request is this server's own: its Host is this address (a site the browser was led to,
    // rebinding its name to 127.0.0.1, sends its own name) and its path starts with the token.
    bool allowed(const httplib::Request& req) const {
        const std::string host = req.get_header_value("Host");
        const std::string port = fmt::format(":{}", port_);
        if (host != kLoopback + port && host != "localhost" + port) return false;
        return req.matches.size() > 1 && req.matches[1] == token_;
    }

    // Handles a POST of a view: the preview it is of, and the view, or an error replied.
    // The preview a view is of, unless the scene file has changed since it was built (a view's
    // heights are the model's: taken back with an exaggeration that is no longer the scene's, they
    // would be wrong): nullptr, after a reply saying why.
    std::shared_ptr<const Built> current(httplib::Response& res) {
        const auto b = built();
        bool stale = false;
        {
            std::lock_guard lock(mutex_);
            stale = building_ || fileStamp(scenePath()) != stamp_;
        }
        if (stale) return reply(res, 409, {{"error", "the scene file changed: wait for the preview to reload, then use the view"}}), nullptr;
        if (!b->preview) return reply(res, 409, {{"error", "the scene does not compile: fix it first"}}), nullptr;
        return b;
    }

    template <class Then>
    void withView(const httplib::Request& req, httplib::Response& res, Then then) {
        const auto b = current(res);
        if (!b) return;
        const json body = json::parse(req.body, nullptr, false);
        const auto view = body.is_object() ? pageViewOf(body) : std::nullopt;
        if (!view) return reply(res, 400, {{"error", "a view is {eye: [x, y, z], target: [x, y, z], fovDeg}"}});
        Diagnostics diags;
        const auto keys = cameraKeysOf(*b->preview, *view, diags);
        if (!keys) return reply(res, 422, {{"error", diagnosticsText(diags)}});
        then(*b, *view, *keys);
    }

    void routes() {
        const std::string token = "/([0-9a-f]{32})/";
        server_.Get(token + "(|preview\\.js)", [this](const httplib::Request& req, httplib::Response& res) {
            if (!allowed(req)) return void(res.status = 404);
            for (const WebAsset& a : webAssets())
                if (a.name == req.matches[2].str()) {
                    res.set_header("Cache-Control", "no-store");
                    res.set_header("X-Content-Type-Options", "nosniff");
                    res.set_content(std::string(a.bytes), std::string(a.contentType));
                    return;
                }
            res.status = 404;
        });
        server_.Get(token + "page\\.json", [this](const httplib::Request& req, httplib::Response& res) {
            if (!allowed(req)) return void(res.status = 404);
            const auto b = built();
            reply(res, 200, {{"generation", b->generation},
                             {"diagnostics", b->diagnostics},
                             {"preview", b->preview ? b->preview->page : json(nullptr)}});
        });
        server_.Get(token + "model\\.glb", [this](const httplib::Request& req, httplib::Response& res) {
            if (!allowed(req)) return void(res.status = 404);
            const auto b = built();
            if (!b->preview) return void(res.status = 409);
            res.set_header("Cache-Control", "no-store");
            res.set_content(b->preview->glb, "model/gltf-binary");
        });
        server_.Get(token + "state", [this](const httplib::Request& req, httplib::Response& res) {
            if (!allowed(req)) return void(res.status = 404);
            const int generation = built()->generation;
            std::lock_guard lock(mutex_);
            reply(res, 200, {{"generation", generation}, {"building", building_}});
        });
        server_.Post(token + "keys", [this](const httplib::Request& req, httplib::Response& res) {
            if (!allowed(req)) return void(res.status = 404);
            withView(req, res, [&](const Built&, const PageView&, const CameraKeys& keys) {
                reply(res, 200, {{"toml", tomlLines(keys)}});
            });
        });
        server_.Post(token + "use", [this](const httplib::Request& req, httplib::Response& res) {
            if (!allowed(req)) return void(res.status = 404);
            withView(req, res, [&](const Built& b, const PageView& view, const CameraKeys& keys) { use(b, view, keys, res); });
        });
        server_.Post(token + "path", [this](const httplib::Request& req, httplib::Response& res) {
            if (!allowed(req)) return void(res.status = 404);
            usePath(req, res);
        });
        server_.Post(token + "render", [this](const httplib::Request& req, httplib::Response& res) {
            if (!allowed(req)) return void(res.status = 404);
            withView(req, res, [&](const Built&, const PageView&, const CameraKeys& keys) { render(keys, res); });
        });
        server_.Get(token + "still", [this](const httplib::Request& req, httplib::Response& res) {
            if (!allowed(req)) return void(res.status = 404);
            std::lock_guard lock(mutex_);
            reply(res, 200, still_);
        });
        server_.Get(token + "still\\.png", [this](const httplib::Request& req, httplib::Response& res) {
            if (!allowed(req)) return void(res.status = 404);
            std::string bytes;
            {
                std::lock_guard lock(mutex_);
                bytes = stillBytes_;
            }
            if (bytes.empty()) return void(res.status = 404);
            res.set_header("Cache-Control", "no-store");
            res.set_content(std::move(bytes), "image/png");
        });
    }

    void use(const Built& b, const PageView& view, const CameraKeys& keys, httplib::Response& res) {
        if (job_.printOnly) {
            log_(fmt::format("[camera]\n{}", tomlLines(keys)));
            return reply(res, 200, {{"written", nullptr}, {"toml", tomlLines(keys)}});
        }
        Diagnostics diags;
        std::lock_guard writing(writeMutex_);
        const auto written = writeSceneKeys(*b.preview, scenePath(), "camera", keys.toml(), kOrbitCameraKeys, diags);
        if (!written) return reply(res, 422, {{"error", diagnosticsText(diags)}});
        ownWrite(*written, view);
        log_(fmt::format("wrote the view into {} (the file before: {}.bak)", written->string(), written->string()));
        reply(res, 200, {{"written", written->string()}, {"toml", tomlLines(keys)}});
    }

    // The scene file as relief itself just wrote it is not a change to rebuild the model for: its
    // camera (or animation) moved, which a page loaded afresh starts from.
    void ownWrite(const fs::path& written, const std::optional<PageView>& view = std::nullopt) {
        if (written != scenePath()) return;
        std::lock_guard lock(mutex_);
        stamp_ = fileStamp(written);
        if (!view || !built_->preview) return;
        auto moved = std::make_shared<Built>(*built_);
        moved->preview->page["camera"]["eye"] = {view->eye.x, view->eye.y, view->eye.z};
        moved->preview->page["camera"]["target"] = {view->target.x, view->target.y, view->target.z};
        moved->preview->page["camera"]["fovDeg"] = view->fovDeg;
        built_ = std::move(moved);
    }

    // The keyframes as the scene's flyover ([animation]), written or (--print) printed.
    void usePath(const httplib::Request& req, httplib::Response& res) {
        const auto b = current(res);
        if (!b) return;
        const json body = json::parse(req.body, nullptr, false);
        std::vector<PageView> keyframes;
        if (body.is_object() && body.contains("keyframes") && body["keyframes"].is_array()) {
            for (const json& k : body["keyframes"]) {
                const auto view = k.is_object() ? pageViewOf(k) : std::nullopt;
                if (!view) return reply(res, 400, {{"error", "a keyframe is {eye: [x, y, z], target: [x, y, z], fovDeg}"}});
                keyframes.push_back(*view);
            }
        }
        Diagnostics diags;
        const auto keys = flyoverKeysOf(*b->preview, keyframes, diags);
        if (!keys) return reply(res, 422, {{"error", diagnosticsText(diags)}});
        std::string text;
        for (const auto& [key, value] : *keys) text += key + " = " + value + "\n";
        if (job_.printOnly) {
            log_(fmt::format("[animation]\n{}", text));
            return reply(res, 200, {{"written", nullptr}, {"toml", text}});
        }
        std::lock_guard writing(writeMutex_);
        const auto written = writeSceneKeys(*b->preview, scenePath(), "animation", *keys, kReplacedAnimationKeys, diags,
                                            flyoverDefaultsOf(keyframes.size()));
        if (!written) return reply(res, 422, {{"error", diagnosticsText(diags)}});
        ownWrite(*written);
        log_(fmt::format("wrote {} keyframes as [animation] into {} (the file before: {}.bak)", keyframes.size(),
                         written->string(), written->string()));
        reply(res, 200, {{"written", written->string()}, {"toml", text}});
    }

    // The still of a view, as `relief render` makes it (this executable, the usual plan and
    // sandbox), its camera set by --set; one at a time.
    void render(const CameraKeys& keys, httplib::Response& res) {
        std::lock_guard lock(mutex_);
        if (still_.value("running", false)) return reply(res, 409, {{"error", "a still is being rendered: wait for it"}});
        if (renderThread_.joinable()) renderThread_.join();
        // The preview's own --set keys, then the view's: the still is of the scene as previewed.
        std::vector<std::string> argv{"relief", "render", scenePath().string(), "-q", "-o", stillPath().string()};
        for (const auto& [key, value] : job_.preview.overrides) argv.insert(argv.end(), {"--set", key + "=" + value});
        for (const auto& [key, value] : keys.toml()) argv.insert(argv.end(), {"--set", "camera." + key + "=" + value});
        std::error_code ec;
        argv[0] = fs::read_symlink("/proc/self/exe", ec).string();
        if (ec) return reply(res, 500, {{"error", "relief cannot find its own executable to render with"}});
        still_ = {{"running", true}};
        renderThread_ = std::thread([this, argv] {
            const auto t0 = Clock::now();
            const auto out = execute::runCommand(argv);
            json status = {{"running", false}, {"seconds", secondsSince(t0)}};
            std::string bytes, problem;
            if (out.status != 0) status["error"] = out.output.empty() ? "relief render failed" : out.output;
            else if (auto png = readInputFile(stillPath(), std::uintmax_t{1} << 31, problem)) bytes = std::move(*png);
            else status["error"] = problem;
            std::lock_guard lock(mutex_);
            still_ = std::move(status);
            stillBytes_ = std::move(bytes);
        });
        reply(res, 202, {{"running", true}});
    }
    fs::path stillPath() const {
        return job_.stillOutput.empty() ? fs::path("out") / (scenePath().stem().string() + "-preview.png") : job_.stillOutput;
    }

    PreviewServeJob job_;
    ServeLog log_;
    std::string token_;
    httplib::Server server_;
    int port_ = -1;
    std::mutex mutex_;
    std::mutex writeMutex_;  // one write of the scene file at a time (read, edit, write)
    std::condition_variable wake_;
    bool stopping_ = false, building_ = false;
    std::shared_ptr<const Built> built_;
    std::string stamp_;
    std::thread renderThread_;
    json still_ = {{"running", false}};
    std::string stillBytes_;
};

}  // namespace

bool servePreview(const PreviewServeJob& job, Diagnostics& diags, const ServeLog& listening, const ServeLog& log) {
    PreviewServer server(job, log);
    if (!server.bind(diags)) return false;
    // Ctrl-C and SIGTERM are waited for by a thread of their own (blocked in every other, which
    // inherit this mask), which stops the server; the server's end wakes that thread the same way.
    // A handler that does nothing, in place of an inherited "ignore" (a shell script's background
    // job starts with SIGINT ignored, which would discard it before sigwait could take it).
    struct sigaction wake {};
    wake.sa_handler = [](int) {};
    sigaction(SIGINT, &wake, nullptr);
    sigaction(SIGTERM, &wake, nullptr);
    sigset_t stopSignals, before;
    sigemptyset(&stopSignals);
    sigaddset(&stopSignals, SIGINT);
    sigaddset(&stopSignals, SIGTERM);
    pthread_sigmask(SIG_BLOCK, &stopSignals, &before);
    std::atomic<bool> served{false};
    std::thread signals([&] {
        int signal = 0;
        sigwait(&stopSignals, &signal);
        if (served) return;
        // A signal before the server listens would be lost on it (stop() acts on a running server).
        while (!server.listening() && !served) std::this_thread::sleep_for(std::chrono::milliseconds(10));
        server.stop();
    });
    listening(server.url());
    server.run();
    served = true;
    pthread_kill(signals.native_handle(), SIGTERM);
    signals.join();
    pthread_sigmask(SIG_SETMASK, &before, nullptr);
    return true;
}

}  // namespace relief::serve
