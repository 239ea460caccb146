// glTF 2.0 through tinygltf: one buffer; per material one primitive with its own compact
// vertex range (POSITION and NORMAL as float VEC3, indices as uint32), so every accessor's
// min/max is exact for the floats written and every block is 4-byte aligned. The part's Z-up
// frame becomes glTF's Y-up by a -90 degree rotation about x at the root node. Vertices are
// split along creases (csg/mesh/CreaseNormals.h) so edges shade flat; readers that check
// topology weld by position (readMesh does).
#include <tiny_gltf.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>
#include <sstream>

#include "csg/mesh/CreaseNormals.h"
#include "io/mesh/MeshFileDetail.h"
#include "primitives/base/AtomicFile.h"

namespace io::detail {

namespace {

// Appends raw bytes to the buffer and returns a new buffer view over them.
int addView(tinygltf::Model& model, const void* data, size_t bytes, int target) {
    std::vector<unsigned char>& buf = model.buffers[0].data;
    const size_t offset = buf.size();  // every block is a multiple of 4 bytes long
    buf.resize(offset + bytes);
    std::memcpy(buf.data() + offset, data, bytes);
    tinygltf::BufferView view;
    view.buffer = 0;
    view.byteOffset = offset;
    view.byteLength = bytes;
    view.target = target;
    model.bufferViews.push_back(view);
    return int(model.bufferViews.size() - 1);
}

int addAccessor(tinygltf::Model& model, int view, int componentType, int type, size_t count,
                std::vector<double> lo = {}, std::vector<double> hi = {}) {
    tinygltf::Accessor a;
    a.bufferView = view;
    a.componentType = componentType;
    a.type = type;
    a.count = count;
    a.minValues = std::move(lo);
    a.maxValues = std::move(hi);
    model.accessors.push_back(a);
    return int(model.accessors.size() - 1);
}

// A shading material as glTF PBR: base colour from color (alpha blends when below 1),
// non-metallic unless it mirrors, roughness from the Phong exponent (alpha^2 = 2 / (n + 2),
// the usual Blinn-Phong to microfacet match, roughness = sqrt(alpha)).
tinygltf::Material pbrOf(const Material& m, uint32_t index) {
    tinygltf::Material g;
    g.name = "material_" + std::to_string(index);
    g.pbrMetallicRoughness.baseColorFactor = {m.color.r, m.color.g, m.color.b, m.color.a};
    g.pbrMetallicRoughness.metallicFactor = std::clamp(m.reflect, 0.0, 1.0);
    g.pbrMetallicRoughness.roughnessFactor =
        std::clamp(std::sqrt(std::sqrt(2.0 / (std::max(m.shininess, 0.0) + 2.0))), 0.0, 1.0);
    if (m.color.a < 1.0) g.alphaMode = "BLEND";
    return g;
}

// One material's triangles: its vertices renumbered compactly, positions and normals as float.
void addPrimitive(tinygltf::Model& model, tinygltf::Mesh& gmesh, const csg::TriangleMesh& mesh,
                  const std::vector<uint32_t>& triangles, int material) {
    std::vector<uint32_t> remap(mesh.positions.size(), UINT32_MAX);
    std::vector<float> positions, normals;
    std::vector<uint32_t> indices;
    indices.reserve(triangles.size() * 3);
    for (const uint32_t t : triangles) {
        for (const uint32_t v : mesh.triangles[t]) {
            if (remap[v] == UINT32_MAX) {
                remap[v] = uint32_t(positions.size() / 3);
                const csg::Vec3& p = mesh.positions[v];
                positions.insert(positions.end(), {float(p.x), float(p.y), float(p.z)});
                // Unit length after rounding to float, as the validator checks it.
                csg::Vec3 n = mesh.normals.empty() ? csg::Vec3(0, 0, 1) : mesh.normals[v];
                if (!(glm::length(n) > 0.0)) n = csg::Vec3(0, 0, 1);
                const glm::vec3 nf = glm::normalize(glm::vec3(n));
                normals.insert(normals.end(), {nf.x, nf.y, nf.z});
            }
            indices.push_back(remap[v]);
        }
    }
    const size_t count = positions.size() / 3;
    std::vector<double> lo(3, INFINITY), hi(3, -INFINITY);
    for (size_t i = 0; i < count; ++i)
        for (int a = 0; a < 3; ++a) {
            lo[size_t(a)] = std::min(lo[size_t(a)], double(positions[i * 3 + size_t(a)]));
            hi[size_t(a)] = std::max(hi[size_t(a)], double(positions[i * 3 + size_t(a)]));
        }
    tinygltf::Primitive prim;
    prim.mode = TINYGLTF_MODE_TRIANGLES;
    prim.material = material;
    prim.attributes["POSITION"] = addAccessor(
        model, addView(model, positions.data(), positions.size() * 4, TINYGLTF_TARGET_ARRAY_BUFFER),
        TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, count, lo, hi);
    prim.attributes["NORMAL"] = addAccessor(
        model, addView(model, normals.data(), normals.size() * 4, TINYGLTF_TARGET_ARRAY_BUFFER),
        TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, count);
    prim.indices = addAccessor(
        model,
        addView(model, indices.data(), indices.size() * 4, TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER),
        TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT, TINYGLTF_TYPE_SCALAR, indices.size());
    gmesh.primitives.push_back(prim);
}

}  // namespace

std::optional<std::string> writeGltf(const std::filesystem::path& file,
                                     const csg::TriangleMesh& welded,
                                     const std::vector<Material>& materials, bool binary) {
    const csg::TriangleMesh mesh = csg::splitAtCreases(welded, csg::tol::kShadingCreaseDegrees);
    tinygltf::Model model;
    model.asset.version = "2.0";
    model.asset.generator = "csgray";
    tinygltf::Scene scene;
    scene.name = file.stem().string();

    if (!mesh.empty()) {
        // Step 1: triangles grouped by material, in material order.
        std::map<uint32_t, std::vector<uint32_t>> groups;
        for (uint32_t t = 0; t < mesh.triangles.size(); ++t)
            groups[mesh.triangleMaterial.empty() ? 0 : mesh.triangleMaterial[t]].push_back(t);

        // Step 2: one buffer, one mesh with a primitive and a material per group.
        model.buffers.emplace_back();
        tinygltf::Mesh gmesh;
        gmesh.name = scene.name;
        for (const auto& [id, triangles] : groups) {
            const Material& m = id < materials.size() ? materials[id] : Material{};
            model.materials.push_back(pbrOf(m, id));
            addPrimitive(model, gmesh, mesh, triangles, int(model.materials.size() - 1));
        }
        model.meshes.push_back(gmesh);

        // Step 3: the root node turns Z-up into Y-up: (x, y, z) -> (x, z, -y).
        tinygltf::Node root, part;
        root.name = "z_up_to_y_up";
        root.rotation = {-std::sqrt(0.5), 0.0, 0.0, std::sqrt(0.5)};
        root.children = {1};
        part.name = scene.name;
        part.mesh = 0;
        model.nodes = {root, part};
        scene.nodes = {0};
    }
    model.scenes.push_back(scene);
    model.defaultScene = 0;

    // Step 4: serialize to memory (the buffer embedded: GLB's BIN chunk, or a data URI in a
    // .gltf so the file stands alone), then atomically to the target.
    std::ostringstream bytes;
    tinygltf::TinyGLTF writer;
    if (!writer.WriteGltfSceneToStream(&model, bytes, !binary, binary))
        return "tinygltf could not serialize the glTF";
    if (std::string error = csg::writeFileAtomically(file, bytes.view()); !error.empty())
        return error;
    return std::nullopt;
}

}  // namespace io::detail
