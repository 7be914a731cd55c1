#pragma once
// Where the labels of a layer's points go on the still: beside their markers,
// never over another label, a marker or the report's furniture, never off the
// still. A pure function of boxes, so that it is tested without drawing.

#include <optional>
#include <vector>

namespace relief::annotate {

/// A box on the still, pixels, y down.
struct LabelBox {
    double x0 = 0, y0 = 0, x1 = 0, y1 = 0;
    bool meets(const LabelBox& o, double pad) const {
        return x0 < o.x1 + pad && o.x0 < x1 + pad && y0 < o.y1 + pad && o.y0 < y1 + pad;
    }
};

/// A label to place: its marker's top (the anchor) and half width, its text's
/// size, and its marker's box on the still (empty: none), which no label covers.
struct LabelRequest {
    double anchorX = 0, anchorY = 0;
    double markerPx = 0;  ///< the marker's half width: the label keeps clear of it
    double w = 0, h = 0;  ///< the text's box
    LabelBox marker;      ///< x0 == x1: no marker
};

/// Where a label went: its box, and the leader line from the marker when it
/// had to move away from it (from the anchor to the box's nearest point).
struct PlacedLabel {
    LabelBox box;
    bool leader = false;
    double leaderX = 0, leaderY = 0;
};

/// Places `labels` in order on a still W x H: each at the first free
/// candidate around its anchor (beside it to the north-east, south-east,
/// north-west, south-west, east, north, west, south; then the same at three
/// growing distances, with a leader line), free meaning inside the still,
/// clear (by a few pixels) of `obstacles` (the furniture), of every label's
/// marker and of the labels placed before it, its leader crossing none of
/// them but its own marker. A label
/// with no free place is left out (nullopt): a label is never drawn over
/// another. The same input gives the same places.
std::vector<std::optional<PlacedLabel>> placeLabels(const std::vector<LabelRequest>& labels, int widthPx,
                                                    int heightPx, const std::vector<LabelBox>& obstacles);

}  // namespace relief::annotate
