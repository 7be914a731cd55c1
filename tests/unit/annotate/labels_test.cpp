// The label placer: beside the marker when it can, never over another label,
// a marker or the furniture, never off the still; a leader when it moves; the
// same places for the same input.

#include <gtest/gtest.h>

#include <cmath>

#include "annotate/layout.h"

namespace relief::annotate {
namespace {

PixelBox markerOf(double x, double y) {
    return {x - 4, y - 4, x + 4, y + 20};
}

LabelRequest at(double x, double y, double w = 60, double h = 14) {
    return {{x, y}, 4, w, h, markerOf(x, y)};
}

void expectValid(const std::vector<std::optional<PlacedLabel>>& placed, const std::vector<LabelRequest>& requests,
                 const std::vector<PixelBox>& obstacles, int W, int H) {
    for (size_t i = 0; i < placed.size(); ++i) {
        if (!placed[i]) continue;
        const PixelBox& b = placed[i]->box;
        EXPECT_GE(b.x0, 0) << i;
        EXPECT_GE(b.y0, 0) << i;
        EXPECT_LE(b.x1, W) << i;
        EXPECT_LE(b.y1, H) << i;
        EXPECT_NEAR(b.x1 - b.x0, requests[i].w, 1e-9);
        for (const PixelBox& o : obstacles) EXPECT_FALSE(b.meets(o, 0)) << "label " << i << " over an obstacle";
        for (size_t j = 0; j < i; ++j)
            if (placed[j]) {
                EXPECT_FALSE(b.meets(placed[j]->box, 0)) << "labels " << j << " and " << i << " overlap";
            }
    }
}

TEST(PlaceLabels, ALoneLabelSitsUpperRightOfItsMarker) {
    const std::vector<LabelRequest> r{at(100, 100)};
    const auto placed = placeLabels(r, 400, 300, {});
    ASSERT_TRUE(placed[0]);
    EXPECT_FALSE(placed[0]->leader);
    EXPECT_GT(placed[0]->box.x0, 100);  // right of the anchor
    EXPECT_LT(placed[0]->box.y1, 100);  // above it
    EXPECT_LT(placed[0]->box.x0 - 100, 12);  // beside it, not far away
}

TEST(PlaceLabels, ALabelAtTheStillsEdgeTurnsInward) {
    const std::vector<LabelRequest> r{at(390, 10)};  // the top right corner
    const auto placed = placeLabels(r, 400, 300, {});
    ASSERT_TRUE(placed[0]);
    EXPECT_LT(placed[0]->box.x1, 390);  // to the left
    EXPECT_GT(placed[0]->box.y0, 10);   // below
    expectValid(placed, r, {markerOf(390, 10)}, 400, 300);
}

// Fifty points in a 120 x 80 pixel patch of a 480 x 320 still: every label
// placed is free of the others, the markers and the edge, those moved away
// with a leader to their box; those with no room are left out, not drawn over
// another; the same input gives the same places.
TEST(PlaceLabels, ACrowdOfFiftyNeverOverlaps) {
    std::vector<LabelRequest> r;
    std::vector<PixelBox> obstacles;
    for (int i = 0; i < 50; ++i) {
        const double x = 180 + std::fmod(i * 37.0, 120), y = 120 + std::fmod(i * 23.0, 80);
        r.push_back(at(x, y, 40 + (i % 5) * 10, 12));
        obstacles.push_back(r.back().marker);
    }
    const auto placed = placeLabels(r, 480, 320, {});
    expectValid(placed, r, obstacles, 480, 320);
    int count = 0, leaders = 0;
    for (const auto& p : placed) count += p.has_value(), leaders += p && p->leader;
    EXPECT_GE(count, 10);  // the patch and its surroundings hold a good part of them
    EXPECT_LT(count, 50);  // and not all: the rest are left out, not stacked
    EXPECT_GT(leaders, 0);
    for (size_t i = 0; i < placed.size(); ++i)
        if (placed[i] && placed[i]->leader) {  // from its marker to a point on its own box
            const PlacedLabel& p = *placed[i];
            EXPECT_GE(p.leaderEnd.x, p.box.x0 - 1e-9);
            EXPECT_LE(p.leaderEnd.x, p.box.x1 + 1e-9);
            EXPECT_GE(p.leaderEnd.y, p.box.y0 - 1e-9);
            EXPECT_LE(p.leaderEnd.y, p.box.y1 + 1e-9);
            EXPECT_GT(std::hypot(p.leaderEnd.x - r[i].anchor.x, p.leaderEnd.y - r[i].anchor.y), r[i].markerPx);
        }
    const auto again = placeLabels(r, 480, 320, {});
    for (size_t i = 0; i < placed.size(); ++i) {
        ASSERT_EQ(placed[i].has_value(), again[i].has_value());
        if (placed[i]) {
            EXPECT_EQ(placed[i]->box.x0, again[i]->box.x0);
        }
    }
}

TEST(PlaceLabels, ALabelTooBigForTheStillIsLeftOut) {
    const std::vector<LabelRequest> r{at(50, 50, 500, 14)};
    const auto placed = placeLabels(r, 400, 300, {});
    EXPECT_FALSE(placed[0]);
}

// A point under the title: its label would need a leader across the title, and is left out;
// the same point clear of it is labelled.
TEST(PlaceLabels, NoLeaderCrossesTheFurniture) {
    const PixelBox title{50, 90, 150, 110};
    EXPECT_FALSE(placeLabels({at(100, 100)}, 400, 300, {title})[0]);
    EXPECT_TRUE(placeLabels({at(100, 200)}, 400, 300, {title})[0]);
}

// A line's label (the graticule's) sits on its line: centred on its point
// where that is free, else touching it; with no such place, left out, never
// moved off with a leader (where it would read as another line's). Swept over
// the still's points on a grid, with an obstacle beside each.
TEST(PlaceLabels, ALinesLabelStaysOnItsLine) {
    LabelRequest onLine{{200, 150}, 0, 40, 14, {}, true};
    auto placed = placeLabels({onLine}, 400, 300, {});
    ASSERT_TRUE(placed[0]);
    EXPECT_EQ(placed[0]->box, (PixelBox{180, 143, 220, 157}));
    EXPECT_FALSE(placed[0]->leader);
    const auto holds = [](const PixelBox& b, const PixelPoint& p) {
        return b.x0 <= p.x && p.x <= b.x1 && b.y0 <= p.y && p.y <= b.y1;
    };
    int onItsLine = 0, leftOut = 0;
    for (double x = 5; x < 400; x += 15)
        for (double y = 5; y < 300; y += 15) {
            onLine.anchor = {x, y};
            const std::vector<PixelBox> obstacles{{x - 10, y - 12, x + 10, y - 3}};  // over the centred place
            placed = placeLabels({onLine}, 400, 300, obstacles);
            if (!placed[0]) {
                ++leftOut;
                continue;
            }
            ++onItsLine;
            EXPECT_TRUE(holds(placed[0]->box, onLine.anchor)) << x << ", " << y;
            EXPECT_FALSE(placed[0]->leader);
            expectValid(placed, {onLine}, obstacles, 400, 300);
        }
    EXPECT_GT(onItsLine, 450);  // all but the still's edges
    EXPECT_GT(leftOut, 0);      // a corner has no place touching its point
}

}  // namespace
}  // namespace relief::annotate
