#pragma once
// Where the overlays go on the still, as boxes of pixels: the furniture (the
// title, the north arrow, the legends, the scale bar, the credits) in the
// corners and along the edges, kept off the terrain where a place is free;
// the labels of a layer's points beside their markers, never over another
// label, a marker or the furniture, never off the still. Nothing here draws,
// so that the places are tested without drawing.

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "annotate/facts.h"
#include "core/types.h"

namespace relief::annotate {

/// The furniture's places on a still W x H: each in the first of its places
/// that is inside the still, clear of the furniture placed before it and off
/// the terrain (a corner of it may touch the terrain: 2 of 81 points); else
/// the first inside and clear (its halo keeps it legible on the terrain);
/// else nowhere: an item is never drawn over another, nor cut by the edge.
class FurniturePlacer {
public:
    /// `unit`: the pixels the furniture's sizes and margins scale with.
    FurniturePlacer(int widthPx, int heightPx, double unit, const TerrainOnImage& terrain)
        : W_(widthPx), H_(heightPx), u_(unit), terrain_(terrain) {}

    struct Choice {
        double dx = 0, dy = 0;  ///< move from the default box
        std::string where;      ///< "top-left", ...
        bool onTerrain = false;
    };

    /// Boxes the size of the one placed, each with the name of its place.
    using Candidates = std::vector<std::pair<PixelBox, std::string>>;

    /// `box` moved to a place of scene::kFurniturePlaces: a corner of the
    /// still (2 units in from its edges) or the middle of an edge.
    PixelBox at(const PixelBox& box, const std::string& where) const;

    /// `box` (`item`'s, at its default place) at the first free of
    /// `candidates` (boxes its size); nullopt when none is, and inTheWay()
    /// then says what kept it out.
    std::optional<Choice> place(const std::string& item, const PixelBox& box, const Candidates& candidates);

    /// Why the last item with no place has none: "the <item>" placed before,
    /// or "the still's edge".
    const std::string& inTheWay() const { return inTheWay_; }

    /// The boxes placed so far.
    const std::vector<PixelBox>& placed() const { return placed_; }
    /// `box` kept for `item`, which is where it is (a map frame's annotations): the furniture keeps off it.
    void reserve(const std::string& item, const PixelBox& box) {
        placed_.push_back(box);
        names_.push_back(item);
    }

private:
    bool coversTerrain(const PixelBox& b) const;
    bool inside(const PixelBox& b) const;
    const std::string* itemMet(const PixelBox& b) const;

    int W_, H_;
    double u_;
    const TerrainOnImage& terrain_;
    std::vector<PixelBox> placed_;
    std::vector<std::string> names_;  ///< each placed box's item
    std::string inTheWay_;
};

/// A label to place: its marker's top (the anchor) and half width, its text's
/// size, and its marker's box on the still (empty: none), which no label covers.
struct LabelRequest {
    PixelPoint anchor;
    double markerPx = 0;  ///< the marker's half width: the label keeps clear of it
    double w = 0, h = 0;  ///< the text's box
    PixelBox marker;      ///< x0 == x1: no marker
    /// A line's label (the graticule's): on its line, its box holding the
    /// anchor (centred on it, else touching it), or left out; never moved
    /// off with a leader, where it would read as another line's.
    bool onLine = false;
};

/// Where a label went: its box, and the leader line from the marker when it
/// had to move away from it (from the anchor to the box's nearest point,
/// `leaderEnd`).
struct PlacedLabel {
    PixelBox box;
    bool leader = false;
    PixelPoint leaderEnd;
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
                                                    int heightPx, const std::vector<PixelBox>& obstacles);

}  // namespace relief::annotate
