#include "model/terrain_model.h"

#include <algorithm>
#include <cctype>
#include <cmath>

#include "emit/block_base.h"

namespace relief::model {

namespace {

constexpr ModelFormatRow kFormats[] = {
    {ModelFormat::Glb, ".glb", "binary glTF 2.0", true, false},
    {ModelFormat::Gltf, ".gltf", "glTF 2.0 (its buffer inside, as a data URI)", true, false},
    {ModelFormat::Stl, ".stl", "binary STL (a closed solid, for printing)", false, true},
    {ModelFormat::Obj, ".obj", "Wavefront OBJ (vertex colours after each vertex)", true, false},
    {ModelFormat::Ply, ".ply", "PLY (vertex colours)", false, false},
};

// A frame point (metres) of the model from a scene point (POV-Ray's east, up, north, in scene units).
Vec3 modelPoint(const emit::ScenePlacement& where, const SceneVec3& p) {
    return {p.x * where.metresPerUnit, p.z * where.metresPerUnit, p.y * where.metresPerUnit};
}

// The surface's triangles as vertex numbers, counter-clockwise from above: the mesh's own faces,
// or each cell of the lattice cut along its south-east to north-west diagonal (as the .pov's).
std::vector<std::array<std::uint32_t, 3>> surfaceFaces(const emit::Mesh& mesh) {
    std::vector<std::array<std::uint32_t, 3>> faces;
    faces.reserve(static_cast<size_t>(mesh.triangles));
    mesh.forEachFace([&](size_t a, size_t b, size_t c) { faces.push_back({mesh.vertexOf(a), mesh.vertexOf(b), mesh.vertexOf(c)}); });
    return faces;
}

// The surface's edges that one triangle alone has, as that triangle runs them (a to b): those
// whose reverse no triangle runs, looked up among b's edges out (a lattice's vertex has six).
std::vector<std::array<std::uint32_t, 2>> outlineEdges(const std::vector<std::array<std::uint32_t, 3>>& faces,
                                                       size_t vertices) {
    std::vector<std::uint32_t> first(vertices + 1, 0), to(3 * faces.size());
    for (const auto& f : faces)
        for (const std::uint32_t v : f) ++first[v + 1];
    for (size_t v = 0; v < vertices; ++v) first[v + 1] += first[v];
    std::vector<std::uint32_t> next(first.begin(), first.end() - 1);
    for (const auto& f : faces)
        for (int k = 0; k < 3; ++k) to[next[f[k]]++] = f[(k + 1) % 3];
    std::vector<std::array<std::uint32_t, 2>> outline;
    for (const auto& f : faces)
        for (int k = 0; k < 3; ++k) {
            const std::uint32_t a = f[k], b = f[(k + 1) % 3];
            if (std::find(to.begin() + first[b], to.begin() + first[b + 1], a) == to.begin() + first[b + 1])
                outline.push_back({a, b});
        }
    return outline;
}

}  // namespace

std::span<const ModelFormatRow> modelFormats() { return kFormats; }

const ModelFormatRow* modelFormatOf(const std::filesystem::path& path) {
    std::string ext = path.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
    for (const ModelFormatRow& row : kFormats)
        if (ext == row.extension) return &row;
    return nullptr;
}

std::string modelExtensionsListed() {
    std::string out;
    for (size_t i = 0; i < std::size(kFormats); ++i)
        out += (i == 0 ? "" : i + 1 == std::size(kFormats) ? " or " : ", ") + std::string("`") + kFormats[i].extension + "`";
    return out;
}

size_t TerrainModel::triangles() const {
    size_t n = 0;
    for (const ModelPart& p : parts) n += p.faces.size();
    return n;
}

const ModelPart* TerrainModel::part(const std::string& name) const {
    for (const ModelPart& p : parts)
        if (p.name == name) return &p;
    return nullptr;
}

TerrainModel terrainModel(const emit::Mesh& mesh, std::optional<double> floorElevationM,
                          std::span<const LinearRgb> nodeColours) {
    TerrainModel model;
    const auto& points = mesh.grid->grid.points;
    model.positions.resize(mesh.vertices);
    model.colours.resize(mesh.vertices);
    model.normals.resize(mesh.vertices);
    std::vector<std::uint32_t> nodeOfVertex(mesh.vertices);
    for (size_t node = 0; node < points.size(); ++node) {
        if (!mesh.isVertex(node)) continue;
        const std::uint32_t v = mesh.vertexOf(node);
        nodeOfVertex[v] = static_cast<std::uint32_t>(node);
        model.positions[v] = modelPoint(mesh, mesh.position(node));
        model.colours[v] =
            nodeColours.empty() ? mesh.nodeColour(node, mesh.paletteColors[mesh.basePalette(node)]) : nodeColours[node];
        const SceneVec3 n = mesh.normal(node);
        model.normals[v] = {n.x, n.z, n.y};
    }
    model.parts.push_back({"surface", surfaceFaces(mesh)});
    if (!floorElevationM) return model;

    // The floor: a vertex under each of the surface's, its triangles theirs turned over.
    const auto top = static_cast<std::uint32_t>(mesh.vertices);
    const LinearRgb wall = emit::blockWallColour(mesh);
    const auto add = [&](const Vec3& p, const Vec3& normal) {
        model.positions.push_back(p), model.colours.push_back(wall), model.normals.push_back(normal);
        return static_cast<std::uint32_t>(model.positions.size() - 1);
    };
    for (std::uint32_t v = 0; v < top; ++v)
        add(modelPoint(mesh, mesh.scenePointAtElevation(points[nodeOfVertex[v]], *floorElevationM)), {0, 0, -1});
    ModelPart walls{"walls", {}}, floor{"floor", {}};
    floor.faces.reserve(model.parts.front().faces.size());
    for (const auto& f : model.parts.front().faces) floor.faces.push_back({top + f[0], top + f[2], top + f[1]});
    // A wall under each outline edge a -> b (the surface to its left, seen from above), facing
    // out (to the edge's right), its four corners its own.
    for (const auto& [a, b] : outlineEdges(model.parts.front().faces, top)) {
        const Vec3 along = {model.positions[b].x - model.positions[a].x, model.positions[b].y - model.positions[a].y, 0};
        const double length = std::hypot(along.x, along.y);
        const Vec3 out = length > 0 ? Vec3{along.y / length, -along.x / length, 0} : Vec3{0, 0, 0};
        const Vec3 pa = model.positions[a], pb = model.positions[b], fa = model.positions[top + a],
                   fb = model.positions[top + b];
        const std::uint32_t ta = add(pa, out), tb = add(pb, out), ba = add(fa, out), bb = add(fb, out);
        walls.faces.push_back({ta, ba, bb});
        walls.faces.push_back({ta, bb, tb});
    }
    model.parts.push_back(std::move(walls));
    model.parts.push_back(std::move(floor));
    return model;
}

void scaleAcross(TerrainModel& model, double acrossMM) {
    if (model.positions.empty()) return;
    double xmin = model.positions[0].x, xmax = xmin, ymin = model.positions[0].y, ymax = ymin;
    for (const Vec3& p : model.positions) {
        xmin = std::min(xmin, p.x), xmax = std::max(xmax, p.x);
        ymin = std::min(ymin, p.y), ymax = std::max(ymax, p.y);
    }
    const double across = std::max(xmax - xmin, ymax - ymin);
    if (!(across > 0)) return;
    const double s = acrossMM / across;
    for (Vec3& p : model.positions) p = {p.x * s, p.y * s, p.z * s};
    model.unitsPerMetre *= s;
}

}  // namespace relief::model
