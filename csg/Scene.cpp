#include "csg/Scene.h"

#include <unordered_set>

#include "csg/Compiled.h"
#include "primitives/base/Grid.h"

namespace csg {

Scene::Scene() = default;

size_t Scene::structureBytes() const {
    size_t bytes = sizeof(BvhNode) * bvh_.capacity();
    for (const UniformGrid& g : grids_) bytes += g.bytes();
    for (const HalvingGrid& g : halvingGrids_) bytes += g.bytes();
    std::unordered_set<const void*> counted;
    for (const LeafGeometry& leaf : leaves_) {
        const auto* mesh = std::get_if<Polyhedron>(&leaf.shape);
        if (!mesh || !mesh->data) continue;
        if (mesh->structure) {
            if (counted.insert(mesh->structure.get()).second) bytes += mesh->structure->bytes();
        } else if (counted.insert(mesh->data.get()).second) {
            bytes += sizeof(BvhNode) * mesh->data->nodes.capacity();
        }
    }
    return bytes;
}

Scene::~Scene() = default;
Scene::Scene(Scene&&) noexcept = default;
Scene& Scene::operator=(Scene&&) noexcept = default;

SurfacePoint Scene::surface(const Ray& ray, const Hit& hit) const {
    SurfacePoint sp{ray.at(hit.t), Vec3(0.0)};
    if (!hit.isSurface()) return sp;
    const LeafFrame& frame = frames_[hit.leaf];
    if (frame.planeNormalKnown) {
        sp.normal = frame.planeNormal;
    } else {
        const Vec3 local = transformPoint(frame.localFromWorld, sp.point);
        sp.normal = worldNormal(frame, primitiveNormal(leaves_[hit.leaf].shape, local, hit.face));
    }
    if (hit.flipped) sp.normal = -sp.normal;
    // A sheet has two sides and no outside: the one facing the ray's origin is shown.
    if (hit.sheet && glm::dot(sp.normal, ray.d) > 0.0) sp.normal = -sp.normal;
    return sp;
}

namespace {

bool insideNode(const std::vector<CompiledNode>& nodes, const std::vector<LeafGeometry>& leaves,
                const std::vector<LeafFrame>& frames, const std::vector<uint32_t>& children,
                uint32_t index, const Vec3& p) {
    const CompiledNode& node = nodes[index];
    if (!node.bounds.contains(p)) return false;
    auto inside = [&](uint32_t i) { return insideNode(nodes, leaves, frames, children, i, p); };
    switch (node.kind) {
        case Op::Leaf: {
            const Vec3 local = transformPoint(frames[node.first].localFromWorld, p);
            return std::visit([&](const auto& shape) { return shape.inside(local); },
                              leaves[node.first].shape);
        }
        case Op::Union:
            for (uint32_t i = 0; i < node.count; ++i)
                if (inside(children[node.first + i])) return true;
            return false;
        case Op::Intersection:
            return inside(node.first) && inside(node.second);
        case Op::Difference:
            return inside(node.first) && !inside(node.second);
    }
    return false;
}

}  // namespace

std::vector<Bounds3> Scene::leafReach() const {
    std::vector<Bounds3> reach(leaves_.size());
    if (nodes_.empty()) return reach;
    struct Visit {
        uint32_t node;
        Bounds3 within;
    };
    const Bounds3 everywhere{Vec3(-kInfinity), Vec3(kInfinity)};
    std::vector<Visit> stack{{root_, everywhere}};
    while (!stack.empty()) {
        const Visit v = stack.back();
        stack.pop_back();
        const CompiledNode& node = nodes_[v.node];
        const Bounds3 within = overlap(v.within, node.bounds);
        switch (node.kind) {
            case Op::Leaf:
                reach[node.first] = within;
                break;
            case Op::Union:
                for (uint32_t k = 0; k < node.count; ++k)
                    stack.push_back({children_[node.first + k], within});
                break;
            case Op::Intersection:
            case Op::Difference:
                stack.push_back({node.first, within});
                stack.push_back({node.second, within});
                break;
        }
    }
    return reach;
}

bool Scene::inside(const Vec3& p) const {
    return insideNode(nodes_, leaves_, frames_, children_, root_, p);
}

Bounds3 Scene::bounds() const {
    return nodes_[root_].bounds;
}
size_t Scene::leafCount() const {
    return leaves_.size();
}
const Tags& Scene::leafTags(uint32_t leaf) const {
    return frames_[leaf].tags;
}
const Primitive& Scene::leafPrimitive(uint32_t leaf) const {
    return leaves_[leaf].shape;
}
const Mat4& Scene::leafWorldFromLocal(uint32_t leaf) const {
    return frames_[leaf].worldFromLocal;
}

}  // namespace csg
