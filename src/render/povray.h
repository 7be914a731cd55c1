#pragma once
// Stage 5 of 6. Input: a .pov file. Output: a PNG rendered by POV-Ray 3.7,
// run in a controlled environment (its own HOME and POVINI, so no user
// configuration leaks in) and, by default, in a bubblewrap sandbox, with
// progress reported from its stderr.
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace relief::render {

/// Rows of a still, as POV-Ray counts them: 1 is the top, both included.
struct RowRange {
    int first = 1, last = 1;
};

struct RenderRequest {
    std::filesystem::path pov;
    std::filesystem::path png;  ///< where the canonical PNG goes (written atomically)
    int width = 800;
    int height = 600;
    bool antialias = true;
    double antialiasThreshold = 0.3;  ///< +A: a pixel is supersampled where it differs from a neighbour by more
    int antialiasDepth = 3;           ///< +R: up to (depth + 1)^2 rays a pixel
    bool alpha = false;  ///< an RGBA PNG: what the rays miss is transparent (+UA)
    /// The folder of the template, which a template's own #include files
    /// come from; may be empty.
    std::filesystem::path templatesDir;
    int threads = 0;  ///< 0: POV-Ray's default (all cores)
    /// POV-Ray's scene language can open, read and write files (#fopen,
    /// #read, #write) and POV-Ray 3.7's own I/O restrictions are not enforced
    /// in Debian's build, so a .pov from elsewhere could read or overwrite the
    /// user's files. In the sandbox (bubblewrap) it sees the system read-only,
    /// the .pov, the templates folder and `inputFiles` read-only (those files
    /// only, not the folders they are in), and one private temporary folder it
    /// may write (its output); no network, no other process, no home folder.
    bool sandbox = true;
    double timeoutSeconds = 0;  ///< POV-Ray is stopped after this long; 0: no limit
    /// Files the .pov reads by their file name (a height field's and a drape's
    /// PNGs): POV-Ray finds them on its library path.
    std::vector<std::filesystem::path> inputFiles;
    /// Rows first..last only (1 = the top; POV-Ray's +SR and +ER): a tile of
    /// the still; `png` then holds those rows alone. Unset: every row.
    std::optional<RowRange> rows;
    /// Without `rows`: the PNG as POV-Ray wrote it (with its date), for a
    /// caller that re-encodes it anyway.
    bool rawOutput = false;
    /// Asked every 200 ms; true stops POV-Ray (result.cancelled).
    std::function<bool()> cancelled;
};

struct RenderResult {
    bool ok = false;
    std::string error;          ///< POV-Ray's own error text (or why it could not run)
    bool cannotWriteOutput = false;  ///< POV-Ray rendered, but the PNG could not be written (error says why)
    bool cancelled = false;          ///< stopped because the request was cancelled
    double parseSeconds = 0;    ///< from POV-Ray's statistics
    double traceSeconds = 0;
    double wallSeconds = 0;
    double peakMemoryBytes = 0;  ///< POV-Ray's largest resident size (the system's accounting)
    std::vector<std::string> command;  ///< the povray command line, for the record
};

/// What POV-Ray reports as it goes.
struct RenderProgress {
    enum class Phase { Parsing, Tracing } phase = Phase::Parsing;
    std::string text;  ///< e.g. "parsing the scene", "Parsing 120K tokens", "Rendered 5120 of 480000 pixels (1%)"
    int percent = -1;  ///< of the pixels traced, 0..100; -1 when POV-Ray gives none
};
using ProgressFn = std::function<void(const RenderProgress&)>;

/// Runs povray. The PNG is written without its render date, so the same scene
/// gives the same bytes; it appears at `png` only when the render succeeded.
RenderResult renderPov(const RenderRequest& request, const ProgressFn& progress);

/// An executable on PATH ("povray", "bwrap"), or "" when it is not installed.
std::string findOnPath(const std::string& name);

}  // namespace relief::render
