#pragma once
// The render plan: what compiling leaves for the render, so that the render
// can run anywhere its folder is seen (other processes, other machines).
// Input: the compiled scene's files and the facts the later steps need.
// Output: a folder holding
//   plan.json        this struct: the still's size and POV-Ray's options, the
//                    overlays and their facts, the sidecar so far, the relief
//                    and POV-Ray versions, the file names of the outputs, the
//                    SHA-256 of every file below, and a hash of all of it;
//   <name>.pov       and the files it reads (a height field's, a drape's PNGs);
//   templates/       the template folder's files (a template's #include files);
//   net.csv|.asc     the control net, when the run dumps it;
//   tiles/           tile-0003.png (tile 3: rows first..last of the still) and
//                    tile-0003.json (its record, with the image's SHA-256), as
//                    each tile is rendered.
// A plan is untrusted input, whoever wrote it (it sits on a shared disk):
// every step that reads one verifies it whole (readPlan), and nothing in it
// can turn the sandbox off, name a file outside its folder or a folder to
// bind, or write anywhere but beside it (docs/security.md).
// The steps that use it: plan/tiles.h (a tile, and the tiles stitched),
// execute/ (many tiles at once, here or on Slurm), pipeline.h (finish).
#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "annotate/overlay.h"
#include "core/diagnostics.h"
#include "scene/scene_spec.h"

namespace relief::plan {

/// Rows `first`..`last` of the still, as POV-Ray counts them (1 is the top,
/// both included: +SR and +ER).
struct TileRows {
    int first = 1, last = 1;
};
/// Tile `index` of `tiles` strips of a still `height` rows high: as equal as
/// whole rows make them, top first.
TileRows tileRows(int height, int tiles, int index);

/// A file the plan holds (in its folder) and the output it becomes.
struct PlanFile {
    std::string name;             ///< in the plan's folder: the output's file name (the .pov reads its PNGs by it)
    /// Where finishing moves it (absolute): the job's own path in the run that
    /// planned it; in a plan read back, `name` beside the plan's folder.
    std::filesystem::path final;
    std::string role;             ///< "the .pov", "the height field's PNG", "--dump-net"
    std::string sha256;           ///< "sha256:...": the file as the plan was made (writePlan fills it)
};

struct RenderPlan {
    std::filesystem::path dir;   ///< the plan's folder (not stored: where it was read from)
    std::string reliefVersion, povrayVersion;
    std::string hash;            ///< "sha256:..." over this plan and its files
    // The scene POV-Ray renders and what it reads.
    PlanFile pov;
    std::vector<PlanFile> reads;   ///< PNGs the .pov reads by name
    std::vector<PlanFile> extras;  ///< other outputs made while compiling (the net dump)
    /// The templates folder's files, copied into templates/ (bound read-only
    /// for POV-Ray's #include): the plan's own, never a folder it names.
    std::vector<PlanFile> templates;
    // The still.
    int width = 0, height = 0, tiles = 1;
    bool antialias = true, alpha = false;
    /// POV-Ray's +A threshold and +R depth, when antialias is on ([render] quality).
    double antialiasThreshold = 0.3;
    int antialiasDepth = 3;
    double timeoutS = 0;
    double dpi = 0;  ///< render.dpi: a PNG's pHYs, a PDF's or SVG's page size; 0: unset
    /// The final still (.png, .pdf, .svg) and sidecar (absolute): the job's in
    /// the run that planned it; read back, their names beside the plan.
    std::filesystem::path still, sidecar;
    // What finishing draws and writes.
    bool overlays = false;
    scene::OverlaySpec overlaySpec;     ///< without key locations
    annotate::OverlayFacts overlayFacts;
    nlohmann::ordered_json sidecar0;    ///< the sidecar so far (every field but the render's)
};

/// Copies the regular files of `templatesDir` (not its folders or links)
/// into the plan's templates/ and lists them; throws OutputError when the
/// folder holds more than a template's files may be (64 files, 16 MB).
void copyTemplates(RenderPlan& plan, const std::filesystem::path& templatesDir);

/// Writes `plan` into `plan.dir` (plan.json: every file's SHA-256, hashed
/// here unless the caller gave it, and a hash over all its fields); false
/// with an error.
bool writePlan(RenderPlan& plan, Diagnostics& diags);

/// Reads the plan in `dir` and verifies it whole before anything acts on it:
/// made by this relief, plan.json as relief wrote it (its hash), every file
/// it lists a plain file in the folder (no link) with the SHA-256 it was
/// planned with, names that are plain file names, sizes a scene can give.
/// Errors name the file that differs and what is wrong. The outputs are
/// named beside the folder.
std::optional<RenderPlan> readPlan(const std::filesystem::path& dir, Diagnostics& diags);

/// Whether this machine can render the plan's tiles: its POV-Ray is the one
/// the plan was made for (a tile from another would be refused at the
/// finish). False with the error naming the host.
bool checkRenderable(const RenderPlan& plan, Diagnostics& diags);

/// The hash a plan.json holds: over its fields but "hash", as relief writes
/// them. For the fuzz target, which makes arbitrary plans pass the check.
std::string planFieldsHash(const nlohmann::ordered_json& fields);

/// What rendering a tile leaves beside its PNG.
struct TileRecord {
    int index = 0;
    TileRows rows;
    std::string planHash, reliefVersion, povrayVersion, host;
    /// The node it ran on: Slurm's name for it ($SLURMD_NODENAME: nodes of one
    /// host share its host name), else the host's.
    std::string node;
    std::string imageSha256;  ///< the tile's PNG as rendered: the finish stitches only that image
    double parseSeconds = 0, traceSeconds = 0, wallSeconds = 0;
    double peakMemoryMB = 0;  ///< POV-Ray's largest resident size while it rendered the tile
    std::vector<std::string> povrayCommand;
};
std::filesystem::path tileImage(const RenderPlan& plan, int index);
std::filesystem::path tileRecordPath(const RenderPlan& plan, int index);
nlohmann::ordered_json tileRecordJson(const TileRecord& record);
/// The node this process runs on: $SLURMD_NODENAME in a Slurm task, else the host's name.
std::string nodeName();
/// The nodes a plan's tiles ran on, a tile each, in tile order (a tile
/// without a good record: none).
std::vector<std::string> tileNodes(const RenderPlan& plan);
/// The record of tile `index`, or nullopt (with `problem` set) when it is
/// missing, damaged, or from another plan or another relief or POV-Ray, or
/// its image is not the one it records (changed, missing, a link).
std::optional<TileRecord> readTileRecord(const RenderPlan& plan, int index, std::string& problem);

/// The tiles without a good record: what a render (or a resumed one) must do.
std::vector<int> missingTiles(const RenderPlan& plan);

/// Held by the run that uses a plan (renders its tiles here, or finishes
/// it), on the file `lock` in its folder: a second run never takes a plan in
/// use (a Slurm task only writes its tile, and takes none).
class PlanLock {
public:
    /// The lock of `dir`, or nullopt when another run holds it (or it cannot be made).
    static std::optional<PlanLock> take(const std::filesystem::path& dir);
    /// The same, saying why not at `dir`'s lock: another relief uses the
    /// folder now, or the folder cannot be written (read-only, full).
    static std::optional<PlanLock> take(const std::filesystem::path& dir, Diagnostics& diags);
    PlanLock(PlanLock&& o) noexcept : fd_(o.fd_) { o.fd_ = -1; }
    PlanLock& operator=(PlanLock&& o) noexcept {
        std::swap(fd_, o.fd_);
        return *this;
    }
    PlanLock(const PlanLock&) = delete;
    ~PlanLock();

private:
    explicit PlanLock(int fd) : fd_(fd) {}
    int fd_ = -1;
};

/// POV-Ray's version as `povray --version` says it ("3.7.0.10.unofficial"), or "".
std::string povrayVersion();

}  // namespace relief::plan
