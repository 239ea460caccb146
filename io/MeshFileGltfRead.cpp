// Reading GLB and glTF for comparison through tinygltf, with node transforms applied.
#include <tiny_gltf.h>

#include <glm/gtc/quaternion.hpp>

#include <cstring>
#include <fstream>

#include "io/MeshFileDetail.h"

namespace io::detail {

namespace {

// The node's parent-from-node matrix (matrix, or translation * rotation * scale).
csg::Mat4 localMatrix(const tinygltf::Node& node) {
    if (node.matrix.size() == 16) {
        csg::Mat4 m;
        for (int c = 0; c < 4; ++c)
            for (int r = 0; r < 4; ++r) m[c][r] = node.matrix[size_t(4 * c + r)];
        return m;
    }
    csg::Mat4 m(1.0);
    if (node.translation.size() == 3)
        m = glm::translate(
            m, csg::Vec3(node.translation[0], node.translation[1], node.translation[2]));
    if (node.rotation.size() == 4) {
        const glm::dquat q(node.rotation[3], node.rotation[0], node.rotation[1], node.rotation[2]);
        m = m * glm::mat4_cast(q);
    }
    if (node.scale.size() == 3)
        m = glm::scale(m, csg::Vec3(node.scale[0], node.scale[1], node.scale[2]));
    return m;
}

// Reads accessor element i as doubles (float, or unsigned integer indices).
bool readAccessor(const tinygltf::Model& model, int index, std::vector<double>& out, int& width) {
    if (index < 0 || size_t(index) >= model.accessors.size()) return false;
    const tinygltf::Accessor& a = model.accessors[size_t(index)];
    if (a.bufferView < 0) return false;
    const tinygltf::BufferView& view = model.bufferViews[size_t(a.bufferView)];
    const tinygltf::Buffer& buffer = model.buffers[size_t(view.buffer)];
    width = tinygltf::GetNumComponentsInType(uint32_t(a.type));
    const int component = tinygltf::GetComponentSizeInBytes(uint32_t(a.componentType));
    if (width <= 0 || component <= 0) return false;
    const size_t stride = view.byteStride ? view.byteStride : size_t(width * component);
    const size_t base = view.byteOffset + a.byteOffset;
    if (a.count > 0 &&
        base + (a.count - 1) * stride + size_t(width * component) > buffer.data.size())
        return false;
    out.resize(a.count * size_t(width));
    for (size_t i = 0; i < a.count; ++i)
        for (int k = 0; k < width; ++k) {
            const unsigned char* p = buffer.data.data() + base + i * stride + size_t(k * component);
            double v = 0.0;
            switch (a.componentType) {
                case TINYGLTF_COMPONENT_TYPE_FLOAT: {
                    float f;
                    std::memcpy(&f, p, 4);
                    v = f;
                    break;
                }
                case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: {
                    uint32_t u;
                    std::memcpy(&u, p, 4);
                    v = u;
                    break;
                }
                case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
                    uint16_t u;
                    std::memcpy(&u, p, 2);
                    v = u;
                    break;
                }
                case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
                    v = *p;
                    break;
                default:
                    return false;
            }
            out[i * size_t(width) + size_t(k)] = v;
        }
    return true;
}

bool addNode(const tinygltf::Model& model, int index, const csg::Mat4& parent,
             csg::TriangleMesh& out, int depth) {
    if (index < 0 || size_t(index) >= model.nodes.size() || depth > 64) return false;
    const tinygltf::Node& node = model.nodes[size_t(index)];
    const csg::Mat4 world = parent * localMatrix(node);
    if (node.mesh >= 0 && size_t(node.mesh) < model.meshes.size()) {
        for (const tinygltf::Primitive& prim : model.meshes[size_t(node.mesh)].primitives) {
            if (prim.mode != TINYGLTF_MODE_TRIANGLES && prim.mode != -1) continue;
            const auto pos = prim.attributes.find("POSITION");
            if (pos == prim.attributes.end()) continue;
            std::vector<double> p, idx;
            int width = 0, iw = 0;
            if (!readAccessor(model, pos->second, p, width) || width != 3) return false;
            const uint32_t first = uint32_t(out.positions.size());
            for (size_t i = 0; i + 2 < p.size(); i += 3)
                out.positions.push_back(csg::transformPoint(world, {p[i], p[i + 1], p[i + 2]}));
            if (prim.indices >= 0) {
                if (!readAccessor(model, prim.indices, idx, iw) || iw != 1) return false;
            } else {
                for (size_t i = 0; i < p.size() / 3; ++i) idx.push_back(double(i));
            }
            for (size_t i = 0; i + 2 < idx.size(); i += 3) {
                std::array<uint32_t, 3> tri{first + uint32_t(idx[i]), first + uint32_t(idx[i + 1]),
                                            first + uint32_t(idx[i + 2])};
                if (tri[0] >= out.positions.size() || tri[1] >= out.positions.size() ||
                    tri[2] >= out.positions.size())
                    return false;
                out.triangles.push_back(tri);
            }
        }
    }
    for (const int child : node.children)
        if (!addNode(model, child, world, out, depth + 1)) return false;
    return true;
}

}  // namespace

MeshReadResult readGltf(const std::filesystem::path& file, bool binary) {
    MeshReadResult result;
    if (!std::ifstream(file, std::ios::binary)) {
        result.error = "cannot open the mesh";
        result.unreadable = true;
        return result;
    }
    tinygltf::TinyGLTF loader;
    tinygltf::Model model;
    std::string err, warn;
    const bool ok = binary ? loader.LoadBinaryFromFile(&model, &err, &warn, file.string())
                           : loader.LoadASCIIFromFile(&model, &err, &warn, file.string());
    if (!ok) {
        result.error = "tinygltf: " + (err.empty() ? std::string("cannot parse") : err);
        return result;
    }
    // glTF's world is Y-up, a part's Z-up: (x, y, z) -> (x, -z, y) undoes the root rotation
    // csgray writes, and puts any other tool's glTF into the part's frame the same way.
    const csg::Mat4 zUpFromYUp(csg::Vec4(1, 0, 0, 0), csg::Vec4(0, 0, 1, 0), csg::Vec4(0, -1, 0, 0),
                               csg::Vec4(0, 0, 0, 1));
    csg::TriangleMesh mesh;
    const int sceneIndex = model.defaultScene >= 0 ? model.defaultScene : 0;
    if (size_t(sceneIndex) < model.scenes.size())
        for (const int node : model.scenes[size_t(sceneIndex)].nodes)
            if (!addNode(model, node, zUpFromYUp, mesh, 0)) {
                result.error = "malformed glTF mesh data";
                return result;
            }
    result.mesh = std::move(mesh);
    return result;
}

}  // namespace io::detail
