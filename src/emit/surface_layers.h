#pragma once
// Stage 4, the scene's vector layers ([[layer]]) on the terrain: lines and
// polygon outlines as ribbons lying on the surface (surface_ribbons.h),
// polygons' fills as tints of the surface's own colour (NodeFills, every
// geometry kind draws them), points as markers standing on the surface, so
// that the terrain hides what it hides. Their labels are annotate/'s: this
// stage says where each point is and whether the eye sees it.

#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "core/diagnostics.h"
#include "emit/camera.h"
#include "emit/surface_ribbons.h"
#include "geo/geo_grid.h"
#include "geo/vector_layer.h"
#include "scene/scene_spec.h"

namespace relief::emit {

/// What became of a layer's features, for the sidecar.
struct LayerCounts {
    long long read = 0;        ///< features read (a multi-geometry's parts each one)
    long long drawn = 0;       ///< with some of them on the terrain
    long long offTerrain = 0;  ///< wholly off the terrain (or on its nodes without data)
    long long vertices = 0;    ///< read from the file
    long long ribbonPoints = 0;  ///< after simplifying to the still's resolution
    long long points = 0, lines = 0, polygons = 0;  ///< features read of each kind
};

/// A layer's point on the terrain: where it stands (frame metres, on the
/// refined surface) and its label.
struct LayerPoint {
    int layer = 0;       ///< index into the scene's layers
    long long fid = 0;
    Vec3 groundM;
    std::string label;
};

struct SurfaceLayers {
    std::vector<Ribbons> lines;       ///< a layer's lines and outlines, one a layer
    std::vector<LayerPoint> points;   ///< on the terrain, in the layers' and files' order
    std::vector<LayerCounts> counts;  ///< a layer's
    std::shared_ptr<const NodeFills> fills;  ///< null: no layer fills a polygon
    long long triangles() const;
    double sdlBytes() const;
};

/// The layers read from their files (geo::readVectorLayer), placed on
/// `refined`: each vertex carried into the frame, lines simplified to a
/// quarter of their width and cut at the refined spacing (so that a track
/// follows the ground), points stood on the surface. A feature off the
/// terrain is a warning naming the layer and the feature (the first few a
/// layer). `metresPerPixel`: at the centre of the view, as the lines' widths
/// are given.
SurfaceLayers placeLayers(const std::vector<scene::LayerSpec>& specs, const std::vector<geo::VectorLayer>& read,
                          const geo::GeoGrid& refined, const ScenePlacement& where, double metresPerPixel,
                          Diagnostics& diags);

/// The layers' SDL: their ribbons, then their points' markers, each a layer's
/// colour, each marker its size on a still `widthPx` wide seen by `view`.
void writeSurfaceLayers(std::FILE* out, const SurfaceLayers& layers, const std::vector<scene::LayerSpec>& specs,
                        const ScenePlacement& where, const CameraView& view, int widthPx);

/// Whether the eye of `view` sees scene point `p`: the segment from it to the
/// eye (orthographic: towards the camera) marched at half the refined grid's
/// spacing against the refined surface, `p` lifted by `liftUnits`. Masked
/// nodes and the grid's outside hide nothing.
bool seenFromEye(const geo::GeoGrid& refined, const ScenePlacement& where, const CameraView& view, const SceneVec3& p,
                 double liftUnits);

/// Scene units a pixel of a still `widthPx` wide covers at scene point `p`.
double unitsPerPixelAt(const CameraView& view, const SceneVec3& p, int widthPx);

}  // namespace relief::emit
