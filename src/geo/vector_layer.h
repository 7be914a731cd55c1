#pragma once
// A layer of a vector file a scene draws on its terrain ([[layer]]): every
// point, line and polygon (with its holes) of one layer of any file GDAL/OGR
// reads, in whatever CRS the file declares (or the scene's `crs` for one that
// declares none), given back in WGS84, each with its label: an attribute's
// value or a fixed text, kept as the bytes it is (annotate/ draws it as text).
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "core/diagnostics.h"
#include "core/types.h"
#include "scene/scene_spec.h"

namespace relief::geo {

enum class FeatureKind { Point, Line, Polygon };

struct VectorFeature {
    FeatureKind kind = FeatureKind::Point;
    long long fid = 0;  ///< the file's feature id
    /// Point: one part, one vertex. Line: a part a line. Polygon: its rings,
    /// the exterior first, then its holes (a multipolygon is a feature a polygon).
    std::vector<std::vector<GeoPoint>> parts;
    std::string label;
};

struct VectorLayer {
    std::string name;  ///< the layer's own name in the file
    std::vector<VectorFeature> features;
    long long vertices = 0;
    long long withoutGeometry = 0;  ///< features with no geometry, or an empty one: not drawn
};

/// The layer `spec` names (its `layer`, or the file's first layer holding a
/// feature), every vertex within `maxVertices`. Nullopt after an error at the
/// key it concerns: a file GDAL cannot read, a layer it does not have (the
/// error lists its layers), a label attribute it does not have (listing its
/// attributes), a CRS that cannot be placed, more vertices than the limit
/// (naming both counts). An empty layer is a warning, and an empty layer given back.
std::optional<VectorLayer> readVectorLayer(const scene::LayerSpec& spec, long long maxVertices, Diagnostics& diags);

}  // namespace relief::geo
