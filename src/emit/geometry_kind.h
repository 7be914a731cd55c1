#pragma once
// Which geometry carries the terrain into the .pov ([geometry] kind): the
// exact mesh2, or the height_field POV-Ray parses in a fraction of the time.
#include <optional>
#include <string>

#include "core/diagnostics.h"
#include "scene/scene_spec.h"

namespace relief::emit {

/// What the choice knows before refining: the refined grid's size, whether
/// any node is masked, the elevation range, the extent and the still's width.
struct GeometryFacts {
    double triangles = 0;      ///< of the full mesh2
    bool masked = false;       ///< nodata left out (holes)
    double zRangeM = 0;        ///< elevation range of the net
    double extentM = 0;        ///< the larger side of the net
    double exaggeration = 1;
    int widthPx = 800;
    /// The refined surface is rough (a scheme whose Hölder exponent is below
    /// 1, at depth 1 or more): POV-Ray's height_field normals (a sum of its
    /// four quadrants' unit normals, taken with heights in 16-bit levels)
    /// then part from the mesh2's (central differences) enough to show
    /// (2.2 % of the pixels of scenes/mountain-sharp.toml off by over 4 %).
    bool rough = false;
};

struct GeometryChoice {
    scene::GeometryKind kind = scene::GeometryKind::Mesh2;
    std::string reason;  ///< why, for the log and the sidecar
};

/// A mesh2 POV-Ray parses within this long (at ~4 us per triangle, measured)
/// is worth its exactness; above it, auto takes the height field.
inline constexpr double kQuickParseSeconds = 1.0;

/// The kind the scene asks for, or auto's choice: the mesh2 when POV-Ray
/// parses it within kQuickParseSeconds; else, when the surface is rough or
/// 16-bit heights would be coarser than half a pixel, the mesh2 (the
/// adaptive mesh when the grid has holes); else the height field, whose
/// drape's alpha cuts the holes.
/// An explicit height_field that cannot be (too coarse) is an error at
/// geometry.kind.
std::optional<GeometryChoice> chooseGeometry(const scene::GeometrySpec& spec, const GeometryFacts& facts,
                                             Diagnostics& diags);

}  // namespace relief::emit
