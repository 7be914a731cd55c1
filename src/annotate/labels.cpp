#include "annotate/labels.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>

namespace relief::annotate {

namespace {

constexpr double kPadPx = 3;      // between a label and anything else
constexpr int kRings = 4;          // the first beside the marker, three further out with a leader
constexpr double kEdgePx = 2;      // a label stays this far inside the still

// The eight directions a label may sit in, in the cartographers' order of preference
// (Imhof): upper right first, then lower right, upper left, lower left, then the axes.
constexpr std::array<std::array<double, 2>, 8> kDirections{{{1, -1}, {1, 1}, {-1, -1}, {-1, 1}, {1, 0}, {0, -1}, {-1, 0}, {0, 1}}};

// The box of a label `w` x `h` whose nearest corner or side is `gap` from the anchor in direction `d`.
LabelBox candidate(const LabelRequest& r, const std::array<double, 2>& d, double gap) {
    const double cx = r.anchorX + d[0] * (gap + (d[0] != 0 ? r.w / 2 : 0));
    const double cy = r.anchorY + d[1] * (gap + (d[1] != 0 ? r.h / 2 : 0));
    return {cx - r.w / 2, cy - r.h / 2, cx + r.w / 2, cy + r.h / 2};
}

// The point of `b` nearest (x, y).
std::array<double, 2> nearestOn(const LabelBox& b, double x, double y) {
    return {std::clamp(x, b.x0, b.x1), std::clamp(y, b.y0, b.y1)};
}

// Whether the segment a-b passes through box `o` (grown by `pad`): Liang-Barsky clipping.
bool crosses(double ax, double ay, double bx, double by, const LabelBox& o, double pad) {
    double t0 = 0, t1 = 1;
    const double dx = bx - ax, dy = by - ay;
    const double p[4] = {-dx, dx, -dy, dy};
    const double q[4] = {ax - (o.x0 - pad), (o.x1 + pad) - ax, ay - (o.y0 - pad), (o.y1 + pad) - ay};
    for (int i = 0; i < 4; ++i) {
        if (p[i] == 0) {
            if (q[i] < 0) return false;
            continue;
        }
        const double t = q[i] / p[i];
        if (p[i] < 0) t0 = std::max(t0, t);
        else t1 = std::min(t1, t);
        if (t0 > t1) return false;
    }
    return true;
}

}  // namespace

std::vector<std::optional<PlacedLabel>> placeLabels(const std::vector<LabelRequest>& labels, int widthPx,
                                                    int heightPx, const std::vector<LabelBox>& obstacles) {
    std::vector<std::optional<PlacedLabel>> out(labels.size());
    std::vector<LabelBox> taken = obstacles;
    std::vector<size_t> markerAt(labels.size(), SIZE_MAX);  // each label's marker among `taken`
    for (size_t i = 0; i < labels.size(); ++i)
        if (labels[i].marker.x1 > labels[i].marker.x0) markerAt[i] = taken.size(), taken.push_back(labels[i].marker);
    const auto inside = [&](const LabelBox& b) {
        return b.x0 >= kEdgePx && b.y0 >= kEdgePx && b.x1 <= widthPx - kEdgePx && b.y1 <= heightPx - kEdgePx;
    };
    for (size_t i = 0; i < labels.size(); ++i) {
        const LabelRequest& r = labels[i];
        for (int ring = 0; ring < kRings && !out[i]; ++ring) {
            const double gap = r.markerPx + kPadPx + ring * (0.8 * r.h + 2 * kPadPx);
            for (const auto& d : kDirections) {
                const LabelBox box = candidate(r, d, gap);
                if (!inside(box)) continue;
                PlacedLabel placed{box, ring > 0, 0, 0};
                const auto [lx, ly] = nearestOn(box, r.anchorX, r.anchorY);
                placed.leaderX = lx, placed.leaderY = ly;
                bool free = true;
                for (size_t k = 0; k < taken.size() && free; ++k)
                    free = !taken[k].meets(box, kPadPx) &&
                           !(placed.leader && k != markerAt[i] && crosses(r.anchorX, r.anchorY, lx, ly, taken[k], 0));
                if (!free) continue;
                out[i] = placed;
                taken.push_back(box);
                break;
            }
        }
    }
    return out;
}

}  // namespace relief::annotate
