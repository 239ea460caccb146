// Reading GLB and glTF for comparison through tinygltf, with node transforms applied.
#include <tiny_gltf.h>

#include <glm/gtc/quaternion.hpp>

#include <cstring>
#include <limits>
#include <optional>
#include <string>

#include "io/mesh/MeshFileDetail.h"

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

// An accessor's elements as doubles (float, or unsigned integers), width components each; an
// error when it does not fit its buffer.
std::optional<std::string> readAccessor(const tinygltf::Model& model, int index,
                                        std::vector<double>& out, int& width) {
    if (index < 0 || size_t(index) >= model.accessors.size()) return "no such accessor";
    const tinygltf::Accessor& a = model.accessors[size_t(index)];
    if (a.bufferView < 0 || size_t(a.bufferView) >= model.bufferViews.size())
        return "an accessor without a buffer view";
    const tinygltf::BufferView& view = model.bufferViews[size_t(a.bufferView)];
    if (view.buffer < 0 || size_t(view.buffer) >= model.buffers.size())
        return "a buffer view without a buffer";
    const tinygltf::Buffer& buffer = model.buffers[size_t(view.buffer)];
    width = tinygltf::GetNumComponentsInType(uint32_t(a.type));
    const int component = tinygltf::GetComponentSizeInBytes(uint32_t(a.componentType));
    if (width <= 0 || component <= 0) return "an accessor of unknown type";
    const size_t element = size_t(width * component);
    const size_t stride = view.byteStride ? view.byteStride : element;
    // Each element takes at least one byte of the buffer, so a count past the buffer's size
    // is refused before the products below, which then cannot overflow.
    const size_t base = view.byteOffset + a.byteOffset;
    if (a.count > buffer.data.size() || base > buffer.data.size() ||
        (a.count > 0 && base + (a.count - 1) * stride + element > buffer.data.size()))
        return "an accessor reaching past its buffer";
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
                    return "an accessor of a component type compare does not read";
            }
            out[i * size_t(width) + size_t(k)] = v;
        }
    return std::nullopt;
}

// Adds the triangles of node index and its children, placed by parent * their matrices; the
// error, if any. glTF's nodes form trees, so a node met twice (visited) is an error: a file
// whose nodes shared children at every level would otherwise take exponential time.
std::optional<std::string> addNode(const tinygltf::Model& model, int index, const csg::Mat4& parent,
                                   csg::TriangleMesh& out, std::vector<bool>& visited, int depth) {
    if (index < 0 || size_t(index) >= model.nodes.size()) return "no such node";
    if (visited[size_t(index)]) return "a node reached twice (glTF nodes form trees)";
    visited[size_t(index)] = true;
    if (depth > 64) return "nodes nested deeper than 64";
    const tinygltf::Node& node = model.nodes[size_t(index)];
    const csg::Mat4 world = parent * localMatrix(node);
    if (node.mesh >= 0 && size_t(node.mesh) < model.meshes.size()) {
        for (const tinygltf::Primitive& prim : model.meshes[size_t(node.mesh)].primitives) {
            if (prim.mode != TINYGLTF_MODE_TRIANGLES && prim.mode != -1) continue;
            const auto pos = prim.attributes.find("POSITION");
            if (pos == prim.attributes.end()) continue;
            std::vector<double> p, idx;
            int width = 0, iw = 0;
            if (auto error = readAccessor(model, pos->second, p, width)) return error;
            if (width != 3) return "POSITION is not a VEC3";
            const size_t first = out.positions.size(), count = p.size() / 3;
            for (size_t i = 0; i < count; ++i) {
                const csg::Vec3 q =
                    csg::transformPoint(world, {p[3 * i], p[3 * i + 1], p[3 * i + 2]});
                if (!measurable(q)) return kUnmeasurableCoordinate;
                out.positions.push_back(q);
            }
            if (prim.indices >= 0) {
                if (auto error = readAccessor(model, prim.indices, idx, iw)) return error;
                if (iw != 1 || model.accessors[size_t(prim.indices)].componentType ==
                                   TINYGLTF_COMPONENT_TYPE_FLOAT)
                    return "indices are not unsigned integer scalars";
            } else {
                for (size_t i = 0; i < count; ++i) idx.push_back(double(i));
            }
            for (size_t i = 0; i + 2 < idx.size(); i += 3) {
                if (idx[i] >= double(count) || idx[i + 1] >= double(count) ||
                    idx[i + 2] >= double(count))
                    return "an index past the primitive's vertices";
                out.triangles.push_back({uint32_t(first + size_t(idx[i])),
                                         uint32_t(first + size_t(idx[i + 1])),
                                         uint32_t(first + size_t(idx[i + 2]))});
            }
        }
    }
    for (const int child : node.children)
        if (auto error = addNode(model, child, world, out, visited, depth + 1)) return error;
    return std::nullopt;
}

// Images are not needed to compare shapes: they are left undecoded.
bool skipImage(tinygltf::Image*, const int, std::string*, std::string*, int, int,
               const unsigned char*, int, void*) {
    return true;
}

}  // namespace

MeshReadResult parseGltf(std::string_view bytes, bool binary,
                         const std::filesystem::path& baseDir) {
    MeshReadResult result;
    if (bytes.size() > std::numeric_limits<unsigned int>::max()) {
        result.error = "glTF files over 4 GiB are not read";
        return result;
    }
    tinygltf::TinyGLTF loader;
    loader.SetImageLoader(skipImage, nullptr);
    tinygltf::Model model;
    std::string err, warn;
    const unsigned int size = static_cast<unsigned int>(bytes.size());
    const bool ok =
        binary
            ? loader.LoadBinaryFromMemory(&model, &err, &warn,
                                          reinterpret_cast<const unsigned char*>(bytes.data()),
                                          size, baseDir.string())
            : loader.LoadASCIIFromString(&model, &err, &warn, bytes.data(), size, baseDir.string());
    if (!ok) {
        result.error = "tinygltf: " + (err.empty() ? std::string("cannot parse") : err);
        return result;
    }
    // glTF's world is Y-up, a part's Z-up: (x, y, z) -> (x, -z, y) undoes the root rotation
    // csgray writes, and puts any other tool's glTF into the part's frame the same way.
    const csg::Mat4 zUpFromYUp(csg::Vec4(1, 0, 0, 0), csg::Vec4(0, 0, 1, 0), csg::Vec4(0, -1, 0, 0),
                               csg::Vec4(0, 0, 0, 1));
    csg::TriangleMesh mesh;
    std::vector<bool> visited(model.nodes.size(), false);
    const int sceneIndex = model.defaultScene >= 0 ? model.defaultScene : 0;
    if (size_t(sceneIndex) < model.scenes.size())
        for (const int node : model.scenes[size_t(sceneIndex)].nodes)
            if (auto error = addNode(model, node, zUpFromYUp, mesh, visited, 0)) {
                result.error = "malformed glTF mesh data: " + *error;
                return result;
            }
    result.mesh = std::move(mesh);
    return result;
}

}  // namespace io::detail
