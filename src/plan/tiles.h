#pragma once
// A still as tiles: rows of it rendered by POV-Ray from a render plan
// (plan/plan.h), each its own process, anywhere the plan's folder is seen;
// then the tiles stitched into the still. The stitch is exact: POV-Ray's
// non-jittered adaptive antialiasing (+AM2 -J) reads nothing outside a
// pixel's own samples, so a tile's rows are the whole still's rows.
#include <functional>
#include <optional>
#include <string>

#include "core/png_file.h"
#include "plan/plan.h"
#include "render/povray.h"

namespace relief::plan {

struct TileOptions {
    int threads = 0;                    ///< POV-Ray's threads; 0: all cores
    /// POV-Ray in its sandbox: the command's choice (--no-sandbox), never the plan's.
    bool sandbox = true;
    std::function<bool()> cancelled;    ///< stops POV-Ray when it says so
    render::ProgressFn progress;        ///< POV-Ray's own lines (may be empty)
};

/// Renders tile `index` of `plan` into the plan's tiles/ (its PNG, then its
/// record with the PNG's SHA-256: a tile with a record is whole). The result
/// says why not; a tiles/ that is not the plan's own folder (a link planted
/// there) is an output that cannot be written.
render::RenderResult renderTile(const RenderPlan& plan, int index, const TileOptions& options);

/// The still from the plan's tiles, each checked against the plan (its
/// record's hash and versions, its image's SHA-256, its size from the PNG's
/// header before its pixels are decoded, its channels); nullopt with an error
/// at the plan naming the first tile that is not right.
std::optional<PngImage8> stitchTiles(const RenderPlan& plan, Diagnostics& diags);

}  // namespace relief::plan
