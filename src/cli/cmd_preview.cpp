#include "cli/cli_common.h"

// relief preview: the scene in the browser, the view chosen by looking
// (serve/preview_server.h).
#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <memory>
#include <thread>

#include <fmt/format.h>

#include "core/text_escape.h"
#include "execute/command.h"
#include "serve/preview_server.h"

namespace relief::cli {

namespace {

struct PreviewOptions {
    CommonOptions common;
    int port = 0;
    long long maxTriangles = relief::kDefaultPreviewTriangles;
    bool print = false;
    bool noOpen = false;
};

// The user's browser, where there is a desktop to show it on (xdg-open's choice); none is no
// error. The address is not on the browser's command line, which any user of the machine can read
// (/proc/PID/cmdline), but in a page of the user's own (0600, in a 0700 folder) that sends the
// browser on to it; the folder is removed when the preview stops.
std::filesystem::path openBrowser(const std::string& url) {
    if (!std::getenv("DISPLAY") && !std::getenv("WAYLAND_DISPLAY")) return {};
    std::string folder = (std::filesystem::temp_directory_path() / "relief-preview-XXXXXX").string();
    if (!::mkdtemp(folder.data())) return {};
    const std::filesystem::path page = std::filesystem::path(folder) / "open.html";
    const int fd = ::open(page.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW, 0600);
    if (fd < 0) return folder;
    // The address is relief's own (digits, hex, ':', '/', '.'): nothing in it is markup.
    const std::string html = fmt::format("<!doctype html><meta http-equiv=\"refresh\" content=\"0; url={}\">\n", url);
    const bool written = ::write(fd, html.data(), html.size()) == static_cast<ssize_t>(html.size());
    ::close(fd);
    if (written) std::thread([page] { execute::runCommand({"xdg-open", page.string()}, {{}, 30}); }).detach();
    return folder;
}

int runPreview(const PreviewOptions& o) {
    relief::Diagnostics diags;
    serve::PreviewServeJob job;
    job.preview.scenePath = o.common.scene;
    if (!parseOverrides(o.common.sets, job.preview.overrides)) return code(Exit::BadInput);
    job.preview.maxTriangles = o.maxTriangles;
    job.preview.threads = o.common.threads;
    job.port = o.port;
    job.printOnly = o.print;
    job.stillOutput = o.common.output;
    const auto say = [](const std::string& text) {
        for (size_t at = 0; at < text.size();) {
            const size_t end = std::min(text.find('\n', at), text.size());
            std::cerr << "relief preview: " << terminalText(text.substr(at, end - at), 4000) << std::endl;
            at = end + 1;
        }
    };
    std::filesystem::path opened;  // the page that sent the browser to the address
    const auto listening = [&](const std::string& url) {
        // The address on stdout alone (a script reads it there); the rest on stderr.
        std::cout << url << std::endl;
        if (!o.common.quiet) say("open the address above in a browser (Ctrl-C stops the preview; it serves 127.0.0.1 only)");
        if (!o.noOpen) opened = openBrowser(url);
    };
    const bool served = serve::servePreview(job, diags, listening, o.common.quiet ? serve::ServeLog([](const std::string&) {}) : serve::ServeLog(say));
    if (!opened.empty()) {
        std::error_code ec;
        std::filesystem::remove_all(opened, ec);
    }
    printDiagnostics(diags, false);
    return code(served ? Exit::Ok : Exit::BadInput);
}

}  // namespace

void addPreviewCommands(CLI::App& app, std::vector<Command>& out) {
    auto o = std::make_shared<PreviewOptions>();
    CLI::App* cmd = app.add_subcommand(
        "preview", "show the scene in the browser (three.js): orbit, pan, zoom and fly to the view you want, then Use "
                   "this view writes its [camera] keys into the scene, so that relief render makes that still");
    cmd->add_option("scene", o->common.scene,
                    "scene file (TOML), or a DEM alone (Use this view then writes relief init's scene for it, "
                    "<DEM name>.toml here)")
        ->required();
    cmd->add_option("--port", o->port, "the port on 127.0.0.1 (default: a free one)")->check(CLI::Range(1, 65535));
    cmd->add_flag("--print", o->print, "Use this view prints the [camera] keys here instead of writing the scene");
    cmd->add_flag("--no-open", o->noOpen, "do not open the page in a browser (the address is printed either way)");
    cmd->add_option("--max-triangles", o->maxTriangles,
                    fmt::format("the preview's model at most this many triangles (default {}): the still renders "
                                "every node whatever this is",
                                relief::kDefaultPreviewTriangles))
        ->check(CLI::Range(100LL, 100'000'000LL));
    cmd->add_option("-o,--output", o->common.output,
                    "where Render writes the still of the view (default: out/<scene name>-preview.png)");
    cmd->add_option("--threads", o->common.threads, "refiner threads (0: all cores)")->check(CLI::Range(0, 256));
    cmd->add_flag("-q,--quiet", o->common.quiet, "print the address and errors only");
    cmd->add_option("--set", o->common.sets,
                    "override a scene key: section.key=value, the value as TOML writes it; repeatable");
    out.push_back({cmd, [o] { return runPreview(*o); }});
}

}  // namespace relief::cli
