#include "geo/curvature_drop.h"

#include <algorithm>
#include <cmath>

#include "geo/normalize.h"

namespace relief::geo {

CurvatureDrop::CurvatureDrop(const Frame& frame, double x0, double y0, double x1, double y1) {
    if (frame.kind != scene::FrameKind::Local) return;
    none_ = false;
    x0_ = x0, y0_ = y0;
    stepX_ = std::max(x1 - x0, 1e-9) / (kSamples - 1);
    stepY_ = std::max(y1 - y0, 1e-9) / (kSamples - 1);
    fall_.resize(static_cast<size_t>(kSamples) * kSamples);
    for (int j = 0; j < kSamples; ++j)
        for (int i = 0; i < kSamples; ++i) {
            // The point of the ellipsoid (height 0) below the plane's point (x, y).
            std::optional<Vec3> below;
            if (auto g = reverse(frame, {x0 + i * stepX_, y0 + j * stepY_, 0}))
                below = forward(frame, {g->lonDeg, g->latDeg, 0});
            fall_[static_cast<size_t>(j) * kSamples + i] = below ? below->z : 0;
        }
}

double CurvatureDrop::at(double x, double y) const {
    if (none_) return 0;
    const double u = std::clamp((x - x0_) / stepX_, 0.0, double(kSamples - 1));
    const double v = std::clamp((y - y0_) / stepY_, 0.0, double(kSamples - 1));
    const int i = std::min(static_cast<int>(u), kSamples - 2), j = std::min(static_cast<int>(v), kSamples - 2);
    const double fu = u - i, fv = v - j;
    const double* row0 = &fall_[static_cast<size_t>(j) * kSamples + i];
    const double* row1 = row0 + kSamples;
    return (1 - fv) * ((1 - fu) * row0[0] + fu * row0[1]) + fv * ((1 - fu) * row1[0] + fu * row1[1]);
}

}  // namespace relief::geo
