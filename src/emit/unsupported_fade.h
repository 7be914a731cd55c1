#pragma once
// net.unsupported = "fade": a fitted surface's colour washed out where no
// sample says what is there, so that a reader sees which terrain is the
// data's and which the fit's guess, as a map greys what was not surveyed.
#include <cstdint>
#include <vector>

#include "geo/geo_grid.h"

namespace relief::emit {

/// Each node of `refined` (row-major) its fade, 0..kFadeLevels (emit/mesh.h),
/// from its distance to the nearest sample: `reachM`, the distances of the
/// net's nodes (row-major over `net`), bilinearly between them. No fade up to
/// `fromM` (the fit's unsupported distance: the net's share it reports is
/// the share that fades), the most from twice that, smoothly between.
std::vector<std::uint8_t> unsupportedFade(const geo::GeoGrid& net, const std::vector<float>& reachM, double fromM,
                                          const geo::GeoGrid& refined);

}  // namespace relief::emit
