#include "annotate/layout.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <span>

namespace relief::annotate {

// The furniture.

PixelBox FurniturePlacer::at(const PixelBox& box, const std::string& where) const {
    const double m = 2 * u_;
    const auto has = [&](const char* side) { return where.find(side) != std::string::npos; };
    const double x = has("left") ? m : has("right") ? W_ - m - box.w() : (W_ - box.w()) / 2;
    const double y = has("top") ? m : has("bottom") ? H_ - m - box.h() : (H_ - box.h()) / 2;
    return {x, y, x + box.w(), y + box.h()};
}

std::optional<FurniturePlacer::Choice> FurniturePlacer::place(const std::string& item, const PixelBox& box,
                                                              const Candidates& candidates) {
    const auto fits = [&](const PixelBox& b) { return inside(b) && !itemMet(b); };
    const std::pair<PixelBox, std::string>* chosen = nullptr;
    for (const auto& c : candidates)
        if (fits(c.first) && !coversTerrain(c.first)) {
            chosen = &c;
            break;
        }
    if (!chosen)
        for (const auto& c : candidates)
            if (fits(c.first)) {
                chosen = &c;
                break;
            }
    if (!chosen) {
        // What is in the way of the first place inside the still: the place the item would have had.
        const auto within = std::find_if(candidates.begin(), candidates.end(), [&](const auto& c) { return inside(c.first); });
        inTheWay_ = within == candidates.end() ? "the still's edge" : "the " + *itemMet(within->first);
        return std::nullopt;
    }
    placed_.push_back(chosen->first);
    names_.push_back(item);
    return Choice{chosen->first.x0 - box.x0, chosen->first.y0 - box.y0, chosen->second, coversTerrain(chosen->first)};
}

bool FurniturePlacer::inside(const PixelBox& b) const {
    return b.x0 >= 0 && b.y0 >= 0 && b.x1 <= W_ && b.y1 <= H_;
}

const std::string* FurniturePlacer::itemMet(const PixelBox& b) const {
    for (size_t i = 0; i < placed_.size(); ++i)
        if (b.meets(placed_[i], u_)) return &names_[i];
    return nullptr;
}

bool FurniturePlacer::coversTerrain(const PixelBox& b) const {
    constexpr int kSamples = 9, kAllowed = 2;
    int on = 0;
    for (int i = 0; i < kSamples; ++i)
        for (int j = 0; j < kSamples; ++j)
            on += terrain_.covers(b.x0 + b.w() * i / (kSamples - 1), b.y0 + b.h() * j / (kSamples - 1));
    return on > kAllowed;
}

// The labels.

namespace {

constexpr double kPadPx = 3;      // between a label and anything else
constexpr int kRings = 4;          // the first beside the marker, three further out with a leader
constexpr double kEdgePx = 2;      // a label stays this far inside the still

// The eight directions a label may sit in, in the cartographers' order of preference
// (Imhof): upper right first, then lower right, upper left, lower left, then the axes.
constexpr std::array<std::array<double, 2>, 8> kDirections{{{1, -1}, {1, 1}, {-1, -1}, {-1, 1}, {1, 0}, {0, -1}, {-1, 0}, {0, 1}}};
// A line's label: centred on its point, else beside it touching it (the same order).
constexpr std::array<std::array<double, 2>, 9> kOnLine{
    {{0, 0}, {1, -1}, {1, 1}, {-1, -1}, {-1, 1}, {1, 0}, {0, -1}, {-1, 0}, {0, 1}}};

// The box of a label `w` x `h` whose nearest corner or side is `gap` from the anchor in direction `d`.
PixelBox candidate(const LabelRequest& r, const std::array<double, 2>& d, double gap) {
    const double cx = r.anchor.x + d[0] * (gap + (d[0] != 0 ? r.w / 2 : 0));
    const double cy = r.anchor.y + d[1] * (gap + (d[1] != 0 ? r.h / 2 : 0));
    return {cx - r.w / 2, cy - r.h / 2, cx + r.w / 2, cy + r.h / 2};
}

// The point of `b` nearest `p`.
PixelPoint nearestOn(const PixelBox& b, const PixelPoint& p) {
    return {std::clamp(p.x, b.x0, b.x1), std::clamp(p.y, b.y0, b.y1)};
}

// Whether the segment a-b passes through box `o` (grown by `pad`): Liang-Barsky clipping.
bool crosses(const PixelPoint& a, const PixelPoint& b, const PixelBox& o, double pad) {
    double t0 = 0, t1 = 1;
    const double dx = b.x - a.x, dy = b.y - a.y;
    const double p[4] = {-dx, dx, -dy, dy};
    const double q[4] = {a.x - (o.x0 - pad), (o.x1 + pad) - a.x, a.y - (o.y0 - pad), (o.y1 + pad) - a.y};
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
                                                    int heightPx, const std::vector<PixelBox>& obstacles) {
    std::vector<std::optional<PlacedLabel>> out(labels.size());
    std::vector<PixelBox> taken = obstacles;
    std::vector<size_t> markerAt(labels.size(), SIZE_MAX);  // each label's marker among `taken`
    for (size_t i = 0; i < labels.size(); ++i)
        if (labels[i].marker.x1 > labels[i].marker.x0) markerAt[i] = taken.size(), taken.push_back(labels[i].marker);
    const auto inside = [&](const PixelBox& b) {
        return b.x0 >= kEdgePx && b.y0 >= kEdgePx && b.x1 <= widthPx - kEdgePx && b.y1 <= heightPx - kEdgePx;
    };
    for (size_t i = 0; i < labels.size(); ++i) {
        const LabelRequest& r = labels[i];
        for (int ring = 0; ring < (r.onLine ? 1 : kRings) && !out[i]; ++ring) {
            const double gap = r.onLine ? 0 : r.markerPx + kPadPx + ring * (0.8 * r.h + 2 * kPadPx);
            const std::span<const std::array<double, 2>> directions =
                r.onLine ? std::span<const std::array<double, 2>>(kOnLine) : kDirections;
            for (const auto& d : directions) {
                const PixelBox box = candidate(r, d, gap);
                if (!inside(box)) continue;
                const PlacedLabel placed{box, ring > 0, nearestOn(box, r.anchor)};
                bool free = true;
                for (size_t k = 0; k < taken.size() && free; ++k)
                    free = !taken[k].meets(box, kPadPx) &&
                           !(placed.leader && k != markerAt[i] && crosses(r.anchor, placed.leaderEnd, taken[k], 0));
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
