#pragma once
// Stage 4 of 6 (part 1). Input: the refined GeoGrid (frame metres) and the
// LookSpec. Output: Mesh,
// in POV-Ray scene units and axes, with normals and an elevation palette.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "core/types.h"
#include "geo/curvature_drop.h"
#include "geo/geo_grid.h"
#include "scene/scene_spec.h"

namespace relief::emit {

inline constexpr int kPaletteSize = 256;

/// Tints laid over the surface's colour, node by node: [[layer]] polygons'
/// fills. fillOf[node] is 0 (none) or k, the fill fills[k - 1].
struct NodeFills {
    struct Fill {
        LinearRgb colour;
        double opacity = 0.35;
    };
    std::vector<std::uint8_t> fillOf;
    std::vector<Fill> fills;
};

/// net.unsupported = "fade": a node no sample reaches has its colour washed
/// towards a light neutral grey (sRGB 0.8), as a map greys what it was not
/// surveyed for, up to kFadeOpacity where the data are farthest; in
/// kFadeLevels steps (a mesh2's texture list holds each step's colours).
inline constexpr LinearRgb kFadeColour{0.6, 0.6, 0.6};
inline constexpr double kFadeOpacity = 0.75;
inline constexpr int kFadeLevels = 16;

/// Where the terrain sits in POV-Ray's scene, whatever geometry carries it.
/// POV-Ray's axes: x = east, y = up, z = north (left-handed, so the map is
/// not mirrored). One scene unit is `metresPerUnit` metres, a power of ten
/// chosen so the terrain spans 10-100 units: POV-Ray stores vertices as
/// 32-bit floats and treats bounding boxes over ~2e10 cubic units as infinite.
struct ScenePlacement {
    double metresPerUnit = 1;
    Vec3 originM;                 ///< frame position (metres) of the scene origin (x, y; z = 0)
    double exaggeration = 1;
    double zMinM = 0, zMaxM = 0;  ///< elevation range of the nodes with data, metres
    SceneVec3 boundsMin, boundsMax;
    /// Nodes with data on a coarse lattice (at most about 100 x 100), scene
    /// units: what the camera frames (emit::placeCamera), not the bounding box.
    std::vector<SceneVec3> outline;
    std::vector<LinearRgb> paletteColors;  ///< kPaletteSize entries over zMinM..zMaxM
    /// What colours the surface ([texture] mode), and how paletteColors is
    /// laid out: Elevation, kPaletteSize entries over zMinM..zMaxM; Slope,
    /// kPaletteSize entries over 0..kSlopePaletteMaxDeg; Blend, kBlendClasses
    /// copies of the elevation entries, each mixed further towards the rock
    /// colour; Image, the elevation entries (the walls' colours), the surface
    /// coloured by its drape.
    scene::TextureSpec::Colouring colouring = scene::TextureSpec::Colouring::Elevation;
    double rockFromDeg = 30, rockToDeg = 45;
    /// The block model's floor ([base]), as a true elevation in metres; unset:
    /// a floating surface. Bounds and outline include the floor.
    std::optional<double> baseElevationM;
    /// The Earth's fall below a local frame's tangent plane; null in UTM.
    std::shared_ptr<const geo::CurvatureDrop> curvature;
    /// render.quality = "high": per refined node (row-major), the share of the
    /// sky's light it gets, its sky-view factor (emit/sky_light.h); every
    /// geometry's colours are multiplied by it. Null: no sky light.
    std::shared_ptr<const std::vector<float>> skyLight;

    /// [[layer]] fills, per refined node (row-major); null: none.
    std::shared_ptr<const NodeFills> fills;
    /// net.unsupported = "fade": per refined node (row-major), 0..kFadeLevels,
    /// how far its colour is washed towards kFadeColour; null: none.
    std::shared_ptr<const std::vector<std::uint8_t>> fade;

    /// Node `node`'s sky light: the factor its colour is multiplied by.
    double skyLightAt(size_t node) const { return skyLight ? (*skyLight)[node] : 1.0; }
    /// Node `node`'s fill (0: none, k: fills->fills[k - 1]).
    unsigned fillAt(size_t node) const { return fills ? fills->fillOf[node] : 0u; }
    /// Node `node`'s fade (0: none, kFadeLevels: the most).
    unsigned fadeAt(size_t node) const { return fade ? (*fade)[node] : 0u; }
    /// Node `node`'s colour differs from its ramp's or image's before the light.
    bool tinted(size_t node) const { return fillAt(node) || fadeAt(node); }
    /// A node's colour before its sky light: its fill laid over `base` (the
    /// ramp's, or a draped image's), then its fade.
    LinearRgb tintedColour(size_t node, const LinearRgb& base) const {
        LinearRgb c = base;
        if (const unsigned f = fillAt(node)) c = mix(c, fills->fills[f - 1].colour, fills->fills[f - 1].opacity);
        if (const unsigned f = fadeAt(node)) c = mix(c, kFadeColour, kFadeOpacity * f / kFadeLevels);
        return c;
    }
    /// A node's colour as every geometry draws it: tintedColour, then its sky light.
    LinearRgb nodeColour(size_t node, const LinearRgb& base) const {
        const LinearRgb c = tintedColour(node, base);
        const double light = skyLightAt(node);
        return {c.r * light, c.g * light, c.b * light};
    }

    double fallAt(const Vec3& p) const { return curvature ? curvature->at(p.x, p.y) : 0.0; }
    /// A frame point's elevation: its height above the ellipsoid (in UTM, its z).
    double elevation(const Vec3& p) const { return p.z - fallAt(p); }
    /// Its height as drawn, in metres before exaggeration: the elevation plus
    /// the fall divided by the exaggeration, so that exaggerating it scales the
    /// elevation and keeps the Earth's curvature as it is.
    double drawnHeight(const Vec3& p) const {
        const double fall = fallAt(p);
        return p.z - fall + fall / exaggeration;
    }
    /// Frame point p moved down (or up) to true elevation `elevationM`, in
    /// scene units: the block model's floor under a node.
    SceneVec3 scenePointAtElevation(const Vec3& p, double elevationM) const {
        return scenePoint({p.x, p.y, elevationM + fallAt(p)});
    }
    /// A frame point (metres) in scene units and axes, exaggerated.
    SceneVec3 scenePoint(const Vec3& p) const {
        const double s = 1.0 / metresPerUnit, zs = exaggeration * s;
        return {(p.x - originM.x) * s, drawnHeight(p) * zs, (p.y - originM.y) * s};
    }
    /// A scene point back in frame metres, its height divided by the
    /// exaggeration. Not scenePoint's inverse in a local frame: the Earth's
    /// fall below the tangent plane stays divided too (what the sidecar reports
    /// for the camera's eye and target).
    Vec3 unexaggerated(const SceneVec3& p) const {
        return {p.x * metresPerUnit + originM.x, p.z * metresPerUnit + originM.y, p.y * metresPerUnit / exaggeration};
    }
};

/// An elevation range this narrow is flat: refining a flat net leaves
/// rounding noise (~1e-13 m) that a ramp or a 16-bit quantization spread over
/// their whole range would show as speckles.
inline bool flatRange(double zMinM, double zMaxM) {
    return !(zMaxM - zMinM > 1e-9 * std::max({1.0, std::fabs(zMinM), std::fabs(zMaxM)}));
}

/// The palette entry of a true elevation: its place on the ramp over
/// zMinM..zMaxM, rounded to one of kPaletteSize entries. Every geometry kind
/// colours a node by it.
inline unsigned char paletteIndex(const ScenePlacement& where, double elevationM) {
    const double span = where.zMaxM > where.zMinM ? where.zMaxM - where.zMinM : 1.0;
    const double t = (elevationM - where.zMinM) / span;
    return static_cast<unsigned char>(std::clamp(std::lround(t * (kPaletteSize - 1)), 0L, long{kPaletteSize - 1}));
}

inline constexpr double kSlopePaletteMaxDeg = 60;
inline constexpr int kBlendClasses = 8;

/// How far a slope is from ground to rock: 0 below rockFromDeg, 1 above
/// rockToDeg, smoothly between.
inline double rockWeight(const ScenePlacement& where, double slopeDeg) {
    const double t = std::clamp((slopeDeg - where.rockFromDeg) / (where.rockToDeg - where.rockFromDeg), 0.0, 1.0);
    return t * t * (3 - 2 * t);
}

/// The palette entry of a point of the surface, by its true elevation and
/// slope (degrees), as where.colouring lays the palette out.
inline unsigned paletteEntry(const ScenePlacement& where, double elevationM, double slopeDeg) {
    using C = scene::TextureSpec::Colouring;
    switch (where.colouring) {
        case C::Slope:
            return static_cast<unsigned>(
                std::clamp(std::lround(slopeDeg / kSlopePaletteMaxDeg * (kPaletteSize - 1)), 0L, long{kPaletteSize - 1}));
        case C::Blend:
            return paletteIndex(where, elevationM) +
                   kPaletteSize * static_cast<unsigned>(std::lround(rockWeight(where, slopeDeg) * (kBlendClasses - 1)));
        default:
            return paletteIndex(where, elevationM);
    }
}

/// The ground's slope at node (r, c) in degrees, from true (unexaggerated)
/// elevations: central differences, one-sided at edges and masked nodes.
double slopeDeg(const geo::GeoGrid& refined, const ScenePlacement& where, int r, int c);

/// The placement of the refined grid's nodes with data: scene unit, origin
/// (centred), bounds, elevation range (collapsed to one height when flat) and
/// the ramp's palette over it.
ScenePlacement placeTerrain(const geo::GeoGrid& refined, const scene::LookSpec& look);

/// The full surface's normal at node (r, c), in scene axes: central
/// differences over the refined lattice (one-sided at its edges and next to
/// masked nodes); d/dcol runs east, d/drow north, and cross(north, east)
/// points up in POV-Ray's (x, y, z) = (E, U, N).
SceneVec3 surfaceNormal(const geo::GeoGrid& refined, const ScenePlacement& where, int r, int c);

/// The terrain as one mesh2, as a view of the refined grid: its vertices are
/// grid nodes, whose position, normal (the full surface's) and palette index
/// are computed from the grid as the writer streams them, so that a mesh
/// holds no copy of the grid (positions and normals would be 48 bytes a
/// vertex beside the grid's 24). Vertices are numbered in the grid's order.
struct Mesh : ScenePlacement {
    static constexpr std::uint32_t kNoVertex = 0xffffffffu;
    const geo::GeoGrid* grid = nullptr;  ///< the refined grid; it must outlive the mesh
    int rows = 0, cols = 0;       ///< the refined grid's lattice
    /// Per grid node: its vertex, or kNoVertex for a node that is not one (no
    /// data, or left out by the adaptive kind); empty when every node is a
    /// vertex, node i being vertex i.
    std::vector<std::uint32_t> vertexOfNode;
    size_t vertices = 0;
    long long triangles = 0;      ///< two per cell, less those touching a masked node (or faces.size())
    /// Explicit triangles as grid nodes, counter-clockwise from above, for a
    /// mesh that is not the lattice's cells (the adaptive kind); empty: two per cell.
    std::vector<std::array<std::uint32_t, 3>> faces;

    bool isVertex(size_t node) const { return vertexOfNode.empty() || vertexOfNode[node] != kNoVertex; }
    std::uint32_t vertexOf(size_t node) const {
        return vertexOfNode.empty() ? static_cast<std::uint32_t>(node) : vertexOfNode[node];
    }
    /// Node `node`'s vertex in scene units, relative to `originM`.
    SceneVec3 position(size_t node) const { return scenePoint(grid->grid.points[node]); }
    /// Calls face(a, b, c) for each triangle, as grid nodes counter-clockwise
    /// from above: `faces`, or two a cell of the lattice, its south-west,
    /// south-east, north-east and north-west corners cut along the south-east
    /// to north-west diagonal as POV-Ray cuts a height_field's cells, so that
    /// the two kinds make the same surface (a triangle with a node that is not
    /// a vertex left out). `done(fraction)` hears how far it is, about a
    /// hundred times.
    template <class Face, class Done>
    void forEachFace(const Face& face, const Done& done) const {
        const size_t step = std::max<size_t>(faces.size() / 100, 1);
        for (size_t i = 0; i < faces.size(); ++i) {
            if (i % step == 0) done(static_cast<double>(i) / faces.size());
            face(faces[i][0], faces[i][1], faces[i][2]);
        }
        const size_t lattice = static_cast<size_t>(cols);
        for (size_t r = 0; faces.empty() && r + 1 < static_cast<size_t>(rows); ++r) {
            done(static_cast<double>(r) / rows);
            for (size_t c = 0; c + 1 < lattice; ++c) {
                const size_t sw = r * lattice + c, se = sw + 1, nw = sw + lattice, ne = nw + 1;
                if (!isVertex(se) || !isVertex(nw)) continue;
                if (isVertex(sw)) face(sw, se, nw);
                if (isVertex(ne)) face(se, ne, nw);
            }
        }
    }
    template <class Face>
    void forEachFace(const Face& face) const {
        forEachFace(face, [](double) {});
    }
    /// The full surface's unit normal at node `node`, scene axes (surfaceNormal).
    SceneVec3 normal(size_t node) const;
    /// Node `node`'s entry of paletteColors: its true elevation on the ramp
    /// (and its slope, when the colouring uses it).
    unsigned palette(size_t node) const { return litTexture.empty() ? basePalette(node) : litTexture[node]; }
    /// The colours palette() indexes: paletteColors, or the lit and filled ones.
    const std::vector<LinearRgb>& textureColours() const { return litTexture.empty() ? paletteColors : litColours; }
    /// With sky light or fills (nodeTextures, emit/sky_light.h): each node's
    /// entry of litColours, and those colours (the palette entries filled and
    /// times the sky light, quantized).
    std::vector<std::uint32_t> litTexture;
    std::vector<LinearRgb> litColours;

    /// Node `node`'s entry of paletteColors, without sky light.
    unsigned basePalette(size_t node) const {
        const double e = elevation(grid->grid.points[node]);
        using C = scene::TextureSpec::Colouring;
        if (colouring != C::Slope && colouring != C::Blend) return paletteIndex(*this, e);
        return paletteEntry(*this, e, slopeDeg(*grid, *this, static_cast<int>(node / static_cast<size_t>(cols)),
                                                static_cast<int>(node % static_cast<size_t>(cols))));
    }
};

/// The full mesh2 of `refined` (which it refers to): centred on the origin,
/// exaggerated, normals from the grid (central differences, one-sided at the
/// edges and next to masked nodes), each vertex's true elevation on the
/// palette. Masked nodes are left out, with every triangle that touches one;
/// bounds and the palette's range are those of the rest.
Mesh buildMesh(const geo::GeoGrid& refined, const ScenePlacement& where);
Mesh buildMesh(geo::GeoGrid&& refined, const ScenePlacement& where) = delete;  // the mesh refers to the grid
/// The same, placed as placeTerrain places it.
inline Mesh buildMesh(const geo::GeoGrid& refined, const scene::LookSpec& look) {
    return buildMesh(refined, placeTerrain(refined, look));
}
Mesh buildMesh(geo::GeoGrid&& refined, const scene::LookSpec& look) = delete;

}  // namespace relief::emit
