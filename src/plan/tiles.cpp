#include "plan/tiles.h"

#include <cmath>
#include <cstring>

#include <fmt/format.h>

#include "core/atomic_file.h"
#include "core/hash.h"
#include "relief/version.h"

namespace relief::plan {

namespace fs = std::filesystem;

render::RenderResult renderTile(const RenderPlan& plan, int index, const TileOptions& options) {
    const TileRows rows = tileRows(plan.height, plan.tiles, index);
    render::RenderRequest req;
    req.pov = plan.dir / plan.pov.name;
    req.png = tileImage(plan, index);
    req.width = plan.width;
    req.height = plan.height;
    req.antialias = plan.antialias;
    req.antialiasThreshold = plan.antialiasThreshold;
    req.antialiasDepth = plan.antialiasDepth;
    req.alpha = plan.alpha;
    if (!plan.templates.empty()) req.templatesDir = plan.dir / "templates";
    for (const auto& f : plan.reads) req.inputFiles.push_back(plan.dir / f.name);
    req.threads = options.threads;
    req.sandbox = options.sandbox;
    req.timeoutSeconds = plan.timeoutS;
    if (plan.tiles > 1) req.rows = render::RowRange{rows.first, rows.last};
    else req.rawOutput = true;  // finishing re-encodes the still once
    req.cancelled = options.cancelled;
    render::RenderResult result;
    try {
        makeOwnFolder(plan.dir / "tiles");
    } catch (const OutputError& e) {
        result.cannotWriteOutput = true;
        result.error = e.what();
        return result;
    }
    result = render::renderPov(req, options.progress);
    if (!result.ok) return result;
    TileRecord record;
    record.index = index;
    record.rows = rows;
    record.planHash = plan.hash;
    record.reliefVersion = kVersion;
    record.povrayVersion = povrayVersion();
    record.parseSeconds = result.parseSeconds;
    record.traceSeconds = result.traceSeconds;
    record.wallSeconds = result.wallSeconds;
    record.peakMemoryMB = std::round(result.peakMemoryBytes / 1e5) / 10;  // to 0.1 MB
    record.povrayCommand = result.command;
    std::string problem;
    record.imageSha256 = fileSha256(req.png, problem);
    try {
        writeFileAtomically(tileRecordPath(plan, index), tileRecordJson(record).dump(1) + "\n");
    } catch (const std::runtime_error& e) {
        result.ok = false;
        result.cannotWriteOutput = true;
        result.error = e.what();
    }
    return result;
}

std::optional<PngImage8> stitchTiles(const RenderPlan& plan, Diagnostics& diags) {
    const SourceLoc at{(plan.dir / "plan.json").string(), 0, 0};
    PngImage8 still;
    for (int k = 0; k < plan.tiles; ++k) {
        std::string problem;
        if (!readTileRecord(plan, k, problem)) {
            diags.error(at, fmt::format("tile {} of {}: {}", k + 1, plan.tiles, problem));
            return std::nullopt;
        }
        const TileRows rows = tileRows(plan.height, plan.tiles, k);
        const PngSize size{plan.width, rows.last - rows.first + 1};
        PngImage8 tile;
        if (std::string e = readPng8(tileImage(plan, k), tile, &size); !e.empty()) {
            diags.error(at, fmt::format("tile {} of {}: {}", k + 1, plan.tiles, e));
            return std::nullopt;
        }
        if (k > 0 && tile.channels != still.channels) {
            diags.error(at, fmt::format("tile {} of {} is {} x {} with {} channels, where tile 1 has {}", k + 1,
                                        plan.tiles, tile.width, tile.height, tile.channels, still.channels));
            return std::nullopt;
        }
        if (plan.tiles == 1) return tile;  // the still in one piece
        const size_t rowBytes = static_cast<size_t>(tile.width) * tile.channels;
        if (k == 0) {
            still.width = plan.width;
            still.height = plan.height;
            still.channels = tile.channels;
            still.pixels.resize(rowBytes * static_cast<size_t>(plan.height));
        }
        std::memcpy(still.pixels.data() + (rows.first - 1) * rowBytes, tile.pixels.data(), tile.pixels.size());
    }
    return still;
}

}  // namespace relief::plan
