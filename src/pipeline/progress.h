#pragma once
// What a job is doing, for the command line to show: every room of the
// pipeline reports through this one type.
#include <functional>
#include <string>

namespace relief {

/// What a job is doing, for the command line to show.
struct ProgressEvent {
    enum class Stage { Reading, Compiling, Rendering, Tiles, Finishing } stage = Stage::Reading;
    std::string text;  ///< e.g. "reading scenes/default.toml", "gridding 458845 samples",
                       ///< POV-Ray's "Rendered 5120 of 480000 pixels (1%)"
    int percent = -1;  ///< of the task `text` names, 0..100; -1 when it has none
};
using ProgressFn = std::function<void(const ProgressEvent&)>;

}  // namespace relief
