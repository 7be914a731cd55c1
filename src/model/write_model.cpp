// The model's file: glTF by tinygltf (the format's own library: a .glb, or a
// .gltf holding its buffer as a data URI, so that the file is whole under
// any name), STL, OBJ and PLY by Assimp's exporters (binary STL; OBJ without
// a material file, for the same reason; ASCII PLY, because Assimp 5.2's
// binary PLY declares a byte a colour component and writes a float, which
// no reader can read back).
#include <assimp/Exporter.hpp>
#include <assimp/scene.h>
#include <tiny_gltf.h>

#include <cmath>
#include <cstring>
#include <memory>
#include <sstream>
#include <stdexcept>

#include <fmt/format.h>

#include "core/atomic_file.h"
#include "model/terrain_model.h"

namespace relief::model {

namespace {

// A point of the model in a format's axes: y up (x east, y up, z south) or as it is (z up).
std::array<float, 3> axesOf(const Vec3& p, bool yUp) {
    if (yUp) return {static_cast<float>(p.x), static_cast<float>(p.z), static_cast<float>(-p.y)};
    return {static_cast<float>(p.x), static_cast<float>(p.y), static_cast<float>(p.z)};
}

// A linear component as sRGB encodes it (IEC 61966-2-1): what OBJ's and PLY's readers show.
float srgbOf(double linear) {
    const double c = std::clamp(linear, 0.0, 1.0);
    return static_cast<float>(c <= 0.0031308 ? 12.92 * c : 1.055 * std::pow(c, 1 / 2.4) - 0.055);
}

// Appends `values`' bytes to `buffer` (4-byte aligned, as glTF's accessors need) as a buffer view.
template <class T>
int addView(tinygltf::Model& gltf, const std::vector<T>& values, int target) {
    auto& bytes = gltf.buffers[0].data;
    while (bytes.size() % 4) bytes.push_back(0);
    tinygltf::BufferView view;
    view.buffer = 0;
    view.byteOffset = bytes.size();
    view.byteLength = values.size() * sizeof(T);
    view.target = target;
    const auto* p = reinterpret_cast<const unsigned char*>(values.data());
    bytes.insert(bytes.end(), p, p + view.byteLength);
    gltf.bufferViews.push_back(std::move(view));
    return static_cast<int>(gltf.bufferViews.size() - 1);
}

int addAccessor(tinygltf::Model& gltf, int view, int componentType, size_t count, int type) {
    tinygltf::Accessor a;
    a.bufferView = view;
    a.componentType = componentType;
    a.count = count;
    a.type = type;
    gltf.accessors.push_back(std::move(a));
    return static_cast<int>(gltf.accessors.size() - 1);
}

std::string gltfBytes(const TerrainModel& model, const ModelFormatRow& format, const std::string& generator) {
    tinygltf::Model gltf;
    gltf.asset.version = "2.0";
    gltf.asset.generator = generator;
    gltf.buffers.resize(1);
    std::vector<float> positions, colours, normals;
    positions.reserve(3 * model.positions.size());
    colours.reserve(3 * model.colours.size());
    normals.reserve(3 * model.normals.size());
    std::vector<double> lo(3, INFINITY), hi(3, -INFINITY);
    for (size_t v = 0; v < model.positions.size(); ++v) {
        const auto p = axesOf(model.positions[v], format.yUp);
        for (int k = 0; k < 3; ++k) lo[k] = std::min<double>(lo[k], p[k]), hi[k] = std::max<double>(hi[k], p[k]);
        positions.insert(positions.end(), p.begin(), p.end());
        const LinearRgb& c = model.colours[v];
        colours.insert(colours.end(), {static_cast<float>(c.r), static_cast<float>(c.g), static_cast<float>(c.b)});
        const auto n = axesOf(model.normals[v], format.yUp);
        normals.insert(normals.end(), n.begin(), n.end());
    }
    const int position = addAccessor(gltf, addView(gltf, positions, TINYGLTF_TARGET_ARRAY_BUFFER),
                                     TINYGLTF_COMPONENT_TYPE_FLOAT, model.positions.size(), TINYGLTF_TYPE_VEC3);
    gltf.accessors[position].minValues = lo, gltf.accessors[position].maxValues = hi;
    const int colour = addAccessor(gltf, addView(gltf, colours, TINYGLTF_TARGET_ARRAY_BUFFER),
                                   TINYGLTF_COMPONENT_TYPE_FLOAT, model.colours.size(), TINYGLTF_TYPE_VEC3);
    const int normal = addAccessor(gltf, addView(gltf, normals, TINYGLTF_TARGET_ARRAY_BUFFER),
                                   TINYGLTF_COMPONENT_TYPE_FLOAT, model.normals.size(), TINYGLTF_TYPE_VEC3);
    // One matte material; the colours are the vertices' (COLOR_0 times a white base).
    tinygltf::Material matte;
    matte.name = "terrain";
    matte.pbrMetallicRoughness.metallicFactor = 0;
    matte.pbrMetallicRoughness.roughnessFactor = 1;
    gltf.materials.push_back(std::move(matte));
    tinygltf::Scene scene;
    for (const ModelPart& part : model.parts) {
        std::vector<std::uint32_t> indices;
        indices.reserve(3 * part.faces.size());
        for (const auto& f : part.faces) indices.insert(indices.end(), f.begin(), f.end());
        tinygltf::Primitive primitive;
        primitive.attributes = {{"POSITION", position}, {"NORMAL", normal}, {"COLOR_0", colour}};
        primitive.indices = addAccessor(gltf, addView(gltf, indices, TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER),
                                        TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT, indices.size(), TINYGLTF_TYPE_SCALAR);
        primitive.material = 0;
        primitive.mode = TINYGLTF_MODE_TRIANGLES;
        tinygltf::Mesh mesh;
        mesh.name = part.name;
        mesh.primitives.push_back(std::move(primitive));
        gltf.meshes.push_back(std::move(mesh));
        tinygltf::Node node;
        node.name = part.name;
        node.mesh = static_cast<int>(gltf.meshes.size() - 1);
        gltf.nodes.push_back(std::move(node));
        scene.nodes.push_back(static_cast<int>(gltf.nodes.size() - 1));
    }
    scene.name = "terrain";
    gltf.scenes.push_back(std::move(scene));
    gltf.defaultScene = 0;
    // Written to memory (a .gltf's buffer as a data URI), then to the file by relief, which checks
    // every write: tinygltf 2.7 does not check its stream's.
    std::ostringstream bytes;
    tinygltf::TinyGLTF writer;
    if (!writer.WriteGltfSceneToStream(&gltf, bytes, false, format.format == ModelFormat::Glb))
        throw std::runtime_error("tinygltf could not write it");
    return std::move(bytes).str();
}

// The model as one Assimp mesh (every part's triangles; colours sRGB, as OBJ's and PLY's readers
// take them). `facets`: three vertices of its own a triangle, each with the triangle's normal,
// which is what Assimp's STL writer takes a facet's normal from.
std::unique_ptr<aiScene> assimpScene(const TerrainModel& model, bool yUp, bool facets) {
    auto scene = std::make_unique<aiScene>();
    scene->mRootNode = new aiNode("terrain");
    scene->mRootNode->mNumMeshes = 1;
    scene->mRootNode->mMeshes = new unsigned[1]{0};
    scene->mNumMaterials = 1;
    scene->mMaterials = new aiMaterial*[1]{new aiMaterial()};
    auto* mesh = new aiMesh();
    scene->mNumMeshes = 1;
    scene->mMeshes = new aiMesh*[1]{mesh};
    mesh->mName = "terrain";
    mesh->mMaterialIndex = 0;
    mesh->mPrimitiveTypes = aiPrimitiveType_TRIANGLE;
    mesh->mNumFaces = static_cast<unsigned>(model.triangles());
    mesh->mFaces = new aiFace[mesh->mNumFaces];
    const auto n = facets ? 3 * mesh->mNumFaces : static_cast<unsigned>(model.positions.size());
    mesh->mNumVertices = n;
    mesh->mVertices = new aiVector3D[n];
    mesh->mColors[0] = new aiColor4D[n];
    mesh->mNormals = new aiVector3D[n];
    const auto vertex = [&](unsigned at, std::uint32_t v) {
        const auto p = axesOf(model.positions[v], yUp), normal = axesOf(model.normals[v], yUp);
        mesh->mVertices[at] = aiVector3D(p[0], p[1], p[2]);
        mesh->mNormals[at] = aiVector3D(normal[0], normal[1], normal[2]);
        const LinearRgb& c = model.colours[v];
        mesh->mColors[0][at] = aiColor4D(srgbOf(c.r), srgbOf(c.g), srgbOf(c.b), 1);
    };
    if (!facets)
        for (unsigned v = 0; v < n; ++v) vertex(v, v);
    unsigned i = 0;
    for (const ModelPart& part : model.parts)
        for (const auto& f : part.faces) {
            aiFace& face = mesh->mFaces[i];
            face.mNumIndices = 3;
            face.mIndices = facets ? new unsigned[3]{3 * i, 3 * i + 1, 3 * i + 2} : new unsigned[3]{f[0], f[1], f[2]};
            if (facets) {
                for (unsigned k = 0; k < 3; ++k) vertex(3 * i + k, f[k]);
                const aiVector3D* v = mesh->mVertices + 3 * i;
                const aiVector3D normal = ((v[1] - v[0]) ^ (v[2] - v[0])).NormalizeSafe();
                for (unsigned k = 0; k < 3; ++k) mesh->mNormals[3 * i + k] = normal;
            }
            ++i;
        }
    return scene;
}

// Assimp's exporter ids for the formats it writes here.
const char* assimpFormatId(ModelFormat format) {
    switch (format) {
        case ModelFormat::Stl: return "stlb";
        case ModelFormat::Obj: return "objnomtl";
        case ModelFormat::Ply: return "ply";
        default: return nullptr;
    }
}

}  // namespace

std::string modelBytes(const TerrainModel& model, const ModelFormatRow& format, const std::string& generator) {
    if (format.format == ModelFormat::Glb || format.format == ModelFormat::Gltf) return gltfBytes(model, format, generator);
    const auto scene = assimpScene(model, format.yUp, format.format == ModelFormat::Stl);
    // To memory, then to the file by relief, which checks every write (Assimp's file system does not).
    Assimp::Exporter exporter;
    const aiExportDataBlob* blob = exporter.ExportToBlob(scene.get(), assimpFormatId(format.format));
    if (!blob) throw std::runtime_error(fmt::format("Assimp could not write it: {}", exporter.GetErrorString()));
    return std::string(static_cast<const char*>(blob->data), blob->size);
}

void writeModel(const TerrainModel& model, const ModelFormatRow& format, const std::filesystem::path& path,
                const std::string& generator) {
    writeFileAtomically(path, modelBytes(model, format, generator));
}

}  // namespace relief::model
