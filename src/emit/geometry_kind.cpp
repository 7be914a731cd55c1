#include "emit/geometry_kind.h"

#include <fmt/format.h>

#include "subdiv/budget.h"

namespace relief::emit {

std::optional<GeometryChoice> chooseGeometry(const scene::GeometrySpec& spec, const GeometryFacts& facts,
                                             Diagnostics& diags) {
    using scene::GeometryKind;
    // One 16-bit level, exaggerated, against half a pixel where the terrain
    // fills the still's width (the camera fits it so).
    const double stepM = facts.zRangeM / 65535.0 * facts.exaggeration;
    const double halfPixelM = 0.5 * facts.extentM / facts.widthPx;
    const double parseSeconds = facts.triangles * subdiv::kParseSecondsPerTriangle;
    if (spec.kind == GeometryKind::Mesh2) return GeometryChoice{GeometryKind::Mesh2, "geometry.kind = \"mesh2\""};
    if (spec.kind == GeometryKind::Adaptive)
        return GeometryChoice{GeometryKind::Adaptive, "geometry.kind = \"adaptive\""};
    if (spec.kind == GeometryKind::HeightField) {
        const SourceLoc at = spec.locs.has("geometry.kind") ? spec.locs.at("geometry.kind") : SourceLoc{};
        if (stepM > halfPixelM) {
            diags.error(at, fmt::format("a height_field's 16-bit heights step by {:.3g} m (exaggerated), more than "
                                        "half a pixel ({:.3g} m): use kind = \"mesh2\"",
                                        stepM, halfPixelM));
            return std::nullopt;
        }
        return GeometryChoice{GeometryKind::HeightField, "geometry.kind = \"height_field\""};
    }
    if (parseSeconds <= kQuickParseSeconds)
        return GeometryChoice{GeometryKind::Mesh2,
                              fmt::format("auto: POV-Ray parses its {:.3g} triangles in about {:.2g} s", facts.triangles,
                                          parseSeconds)};
    // A mesh2 too slow to parse, and a height field that would show less:
    // the adaptive mesh when nodes are left out (fewer triangles, the same holes).
    const GeometryKind exact = facts.masked ? GeometryKind::Adaptive : GeometryKind::Mesh2;
    if (facts.rough)
        return GeometryChoice{exact,
                              "auto: the surface is rough (Hölder exponent below 1), where a height_field's "
                              "normals part from the mesh2's"};
    if (stepM > halfPixelM)
        return GeometryChoice{
            exact, fmt::format("auto: 16-bit heights would step by {:.3g} m, more than half a pixel", stepM)};
    // Nodes without data are holes in the drape (alpha 0), which POV-Ray
    // traces through: the same holes at a height field's cost, where an adaptive mesh
    // of a rough DEM keeps most of its triangles (3.8x the seconds of the
    // height field on a 1197 x 643 SRTM DEM with a masked border).
    return GeometryChoice{GeometryKind::HeightField,
                          fmt::format("auto: a mesh2 of {:.3g} triangles would take POV-Ray about {:.0f} s to "
                                      "parse; 16-bit heights step by {:.2g} m (half a pixel: {:.2g} m){}",
                                      facts.triangles, parseSeconds, stepM, halfPixelM,
                                      facts.masked ? "; nodes without data are holes in its drape" : "")};
}

}  // namespace relief::emit
