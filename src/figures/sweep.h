#pragma once
// `relief sweep`: one still per combination of parameter values, assembled
// into a labelled contact sheet (one PNG), like the parameter-influence
// figures of the source papers.
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "core/diagnostics.h"
#include "pipeline/job.h"

namespace relief::figures {

/// One --vary: a scene key and its values, as typed ("subdivision.omega", {"0.02", "1/32"}).
struct Variation {
    std::string key;
    std::vector<std::string> values;
};

struct Tile {
    std::filesystem::path image;
    std::string label;  ///< e.g. "omega = 0.02, lambda = 1/16"
};

/// Lays the tiles out in a grid (`columns`; 0 = the first variation's count),
/// each with its label under it, on white; writes `out` atomically. Labels use
/// the DejaVu Sans font (Debian fonts-dejavu-core). Returns "" or the error.
std::string writeContactSheet(const std::vector<Tile>& tiles, int columns, const std::string& title,
                              const std::filesystem::path& out);

/// Every combination of the variations' values, first variation fastest.
std::vector<std::vector<std::pair<std::string, std::string>>> combinations(
    const std::vector<Variation>& variations);

struct SweepRequest {
    std::filesystem::path scenePath;
    scene::SceneOverrides base;          ///< applied to every still, before the variation
    std::vector<Variation> variations;
    std::filesystem::path sheet;         ///< the contact sheet; the stills go to <sheet>-stills/
    std::filesystem::path templatesDir;
    int threads = 0;
    int columns = 0;                     ///< 0: the first variation's count
    int tiles = 1;                       ///< strips of each still
    execute::Options execution;          ///< where the stills render (all at once)
};

/// What the sweep is doing: a still started, its render's progress, or it finished.
struct SweepEvent {
    enum class Kind { Started, Rendering, Finished } kind = Kind::Started;
    size_t index = 0, total = 0;  ///< 1-based still number, and how many
    std::string label;            ///< "omega = 0.02, lambda = 1/16"
    const ProgressEvent* render = nullptr;   ///< Rendering
    const JobOutcome* outcome = nullptr;     ///< Finished
    const Diagnostics* diags = nullptr;      ///< Finished: the still's warnings (or errors)
};

struct SweepResult {
    JobStatus status = JobStatus::Ok;  ///< of the first still that failed, else Ok
    std::vector<Tile> tiles;
    std::string sheetMessage;  ///< "" or writeContactSheet's message ("warning: ..." is not an error)
    bool sheetWritten = false;
};

/// Checks every combination, compiles each into its render plan, renders them
/// all (here or on Slurm; the first failure stops the sweep, its diagnostics
/// with its Finished event), finishes each still, then writes the contact
/// sheet; the stills and the sheet appear together, or nothing does.
SweepResult runSweep(const SweepRequest& request, const std::function<void(const SweepEvent&)>& onEvent);

}  // namespace relief::figures
