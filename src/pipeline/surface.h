#pragma once
// Stages 2 and 3 composed: the control net (geo/) for the loaded scene and
// the refined surface (subdiv/), at the depth the scene gives or relief
// chooses (depth.h), held to the scene's [limits].
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/diagnostics.h"
#include "emit/geometry_kind.h"
#include "fit/fit_net.h"
#include "fit/prefilter.h"
#include "geo/normalize.h"
#include "measure/peak_loss.h"
#include "pipeline/depth.h"
#include "pipeline/load.h"
#include "pipeline/progress.h"
#include "subdiv/budget.h"

namespace relief {

/// Where an error of the output budget belongs: subdivision.depth = "auto",
/// the scheme (a depth the scene gives), else the key that sized the net (or
/// the samples file, when relief chose both the net and the depth).
SourceLoc budgetKey(const scene::SceneSpec& spec);

/// Stages 2 and 3: the control net and the refined surface (metres, in the
/// net's frame), refused with a diagnostic when over the output budget. Used
/// by compileScene and by measurements such as profiles.
struct Surface {
    geo::ControlNet net;
    NetSize size;               ///< net's own; estimateSurface's: the net too large to read
    double heightsReadAtM = 0;  ///< estimateSurface: the spacing `net`'s heights were read at in its place
    geo::GeoGrid refined;  ///< the net refined `depth` times: same frame and extent
    subdiv::OutputEstimate estimate;  ///< of the chosen geometry
    emit::GeometryChoice geometry;
    int depth = 0;            ///< the scene's, the one depth = "auto" chose, or the still's
    std::string depthReason;  ///< "subdivision.depth", the auto summary, or how the still chose it
    std::optional<DepthChoice> autoDepth;  ///< the change per level, for depth = "auto"
    double normalizeSeconds = 0, subdivideSeconds = 0;  ///< subdivide includes choosing the depth
    std::optional<fit::FitReport> fit;              ///< net.gridding = "fit"
    std::optional<fit::PrefilterReport> prefilter;  ///< net.fit = true
    Vec3 dataPeak;                                  ///< the highest sample (or node) the data have
    measure::PeakLoss peakLoss;                     ///< of the refined surface against dataPeak
};
/// What buildSurface will make, without refining: the net, the depth and why,
/// the geometry and its cost, checked against [limits] (a net whose work is
/// over them is refused before its heights are read). What `relief info`
/// and `relief init` show; `refined` is empty.
///
/// The depth, when the scene gives none, is chosen for the still: the
/// shallowest whose refined spacing is within sqrt(arity) of one pixel where
/// the terrain is nearest the camera, lowered until [limits] allow it.
std::optional<Surface> planSurface(const LoadedScene& loaded, Diagnostics& diags, int threads = 0,
                                   const ProgressFn& progress = {});
/// A net of more nodes than this is not read by estimateSurface.
inline constexpr double kEstimateReadNodes = 2e6;
/// planSurface for `relief info`, answered in under a second on any data:
/// a net of more than kEstimateReadNodes is laid out (its size, spacing and
/// why, as planSurface's) and not read. Its heights (the elevation range, the
/// camera's framing, the footprint that chooses the depth) are read on a
/// coarser net over the same extent, as a still's default net is (block
/// means); its size, depth and cost are the net's own. Not the net's: an
/// automatic depth (measured on the stand-in, and said so) and net.gridding
/// = "fit" (not fitted).
std::optional<Surface> estimateSurface(const LoadedScene& loaded, Diagnostics& diags);
/// net.unsupported = "fade": the refined surface's nodes' fades
/// (emit::ScenePlacement::fade); null when the scene does not fade or the
/// data reach every node.
std::shared_ptr<const std::vector<std::uint8_t>> unsupportedFadeOf(const Surface& surface);

/// `progress` (may be empty) hears how far the gridding is.
std::optional<Surface> buildSurface(const LoadedScene& loaded, Diagnostics& diags, int threads = 0,
                                    const ProgressFn& progress = {});

}  // namespace relief
