#pragma once
// relief preview's server: the page and the scene's preview (pipeline/
// preview.h) on loopback only, under a random token no other user of the
// machine can guess; the scene rebuilt when its file changes; the views the
// page sends turned into [camera] keys, written into the scene, or rendered.
#include <filesystem>
#include <functional>
#include <string>

#include "core/diagnostics.h"
#include "pipeline/preview.h"

namespace relief::serve {

struct PreviewServeJob {
    PreviewJob preview;
    int port = 0;            ///< 0: a free port the system chooses
    bool printOnly = false;  ///< --print: "Use this view" prints the keys here instead of writing them
    std::filesystem::path stillOutput;  ///< where "Render" writes its still (default out/<scene>-preview.png)
};

/// What the server tells its user as it goes (the address; each view used).
using ServeLog = std::function<void(const std::string& line)>;

/// Builds the preview, then serves it until SIGINT or SIGTERM (Ctrl-C).
/// `listening` gets the page's address once the port is open. False, after
/// an error in `diags`, when the port cannot be opened (a scene that does
/// not compile is served: the page shows its diagnostics).
bool servePreview(const PreviewServeJob& job, Diagnostics& diags, const ServeLog& listening, const ServeLog& log);

}  // namespace relief::serve
