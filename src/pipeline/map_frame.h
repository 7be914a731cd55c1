#pragma once
// [overlay] frame: a map's frame around a still from straight above, as
// GMT's -Baf draws one. Its ticks are found in the frame's metres before the
// camera is placed (the terrain's edges are the map's, whatever the camera),
// so that the camera can leave room for their annotations; then they are
// carried onto the still for annotate/.
#include <optional>
#include <string>
#include <vector>

#include "annotate/overlay.h"
#include "emit/camera.h"
#include "geo/geo_grid.h"
#include "scene/scene_spec.h"

namespace relief {

/// The ticks where the meridians and parallels (or the frame's round metres)
/// cross the terrain's four edges: an annotation every annotation interval
/// (the graticule's automatic step: at most five intervals along an edge,
/// fewer where the map's width on the still would crowd them), a frame tick
/// every fourth, fifth or third of it (1° by 15′, 5′ by 1′, 30′ by 10′).
struct MapFrameTicks {
    struct Tick {
        annotate::MapFrame::Side side = annotate::MapFrame::Side::Bottom;
        double atM = 0;     ///< along its edge: x for bottom and top, y for left and right
        double value = 0;   ///< what it marks: a longitude or latitude (degrees), or atM
        std::string label;  ///< empty: a frame tick
    };
    double x0 = 0, y0 = 0, x1 = 0, y1 = 0;  ///< the terrain's edges, metres
    std::vector<Tick> ticks;
    size_t widestLabelChars() const;  ///< in characters (code points)
};

/// The frame's ticks over `net`'s extent; nullopt when the scene asks for
/// none or draws no overlays. Errors at overlay.frame: longitude and
/// latitude where the frame has none (a raster's CRS PROJ cannot invert),
/// annotations and furniture leaving the map less than a fifth of the still.
std::optional<MapFrameTicks> mapFrameTicks(const scene::SceneSpec& spec, const geo::GeoGrid& net, Diagnostics& diags);

/// The room the camera leaves around the map for the ticks' annotations and
/// the furniture (emit::placeCamera's inset); none without a frame.
emit::FrameInsetPx frameInsetOf(const scene::SceneSpec& spec, const std::optional<MapFrameTicks>& ticks);

/// The frame on the still the camera makes.
annotate::MapFrame mapFrameOnImage(const MapFrameTicks& ticks, const emit::ScenePlacement& where,
                                   const emit::CameraView& view, int widthPx, int heightPx);

}  // namespace relief
