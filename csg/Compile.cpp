// Compiles a CSG tree into the flat arrays the queries walk: transforms flattened into each
// leaf, nested unions flattened into n-ary unions, bounds computed bottom-up (union = hull,
// intersection = overlap, difference = left operand), empty subtrees pruned, and a BVH over
// every union with enough bounded children.
#include <cmath>
#include <sstream>

#include "csg/Bvh.h"
#include "csg/Compiled.h"
#include "csg/Scene.h"

namespace csg {
namespace {

// Unions with fewer bounded children than this are scanned linearly: a BVH would cost more
// box tests than it saves.
constexpr uint32_t kBvhMinChildren = 4;

const char* opName(Op op) {
    switch (op) {
        case Op::Leaf:
            return "primitive";
        case Op::Union:
            return "union";
        case Op::Intersection:
            return "intersection";
        case Op::Difference:
            return "difference";
    }
    return "node";
}

// Throws CompileError unless m is a finite, invertible affine map.
void checkTransform(const Mat4& m, const Node& node, const char* what) {
    if (!isFinite(m))
        throw CompileError(
            std::string(what) + " of a " + opName(node.op) + " has a non-finite entry",
            node.tags.source);
    const Mat3 linear(m);
    const double scale =
        std::max({glm::length(linear[0]), glm::length(linear[1]), glm::length(linear[2])});
    const double det = glm::determinant(linear);
    if (!(std::abs(det) > tol::kSingularDetRel * scale * scale * scale)) {
        std::ostringstream msg;
        msg << what << " of a " << opName(node.op) << " is singular (determinant " << det
            << "): the solid would be flattened";
        throw CompileError(msg.str(), node.tags.source);
    }
}

template <class Shape>
Bounds3 worldBounds(const Shape& shape, const Mat4& worldFromLocal) {
    if constexpr (HasTightBounds<Shape>)
        return shape.boundsUnder(worldFromLocal);
    else
        return transformBounds(worldFromLocal, shape.bounds());
}

// Leaves the compiled scene will hold: one per placement of a primitive, so a shared subtree
// counts once for each use. Reserving for them up front avoids regrowing ~10^6-entry arrays.
size_t countLeaves(const Node* node) {
    if (!node) return 0;
    if (node->op == Op::Leaf) return 1;
    return countLeaves(node->left.get()) + countLeaves(node->right.get());
}

}  // namespace

struct Compiler {
    Scene& scene;
    // The innermost difference or intersection being built, if any: a sheet under it is an
    // error (it has no inside for the operation to use).
    const Node* boolean = nullptr;
    struct BooleanScope {
        Compiler& compiler;
        const Node* outer;
        BooleanScope(Compiler& c, const Node& node) : compiler(c), outer(c.boolean) {
            c.boolean = &node;
        }
        ~BooleanScope() { compiler.boolean = outer; }
    };

    // Returns the compiled node index of `node` seen through worldFromParent, or kNoNode when
    // the subtree is empty.
    uint32_t build(const Node& node, const Mat4& worldFromParent) {
        Mat4 worldFromNode = worldFromParent;
        if (node.parentFromNode != Mat4(1.0)) {
            checkTransform(node.parentFromNode, node, "the transform");
            worldFromNode = worldFromParent * node.parentFromNode;
        }
        switch (node.op) {
            case Op::Leaf:
                return buildLeaf(node, worldFromNode);
            case Op::Union: {
                std::vector<uint32_t> children;
                gatherUnion(node, worldFromNode, children);
                return buildUnion(children);
            }
            case Op::Intersection: {
                const BooleanScope scope(*this, node);
                const uint32_t a = build(*node.left, worldFromNode);
                if (a == kNoNode) return kNoNode;
                const uint32_t b = build(*node.right, worldFromNode);
                if (b == kNoNode) return kNoNode;
                const Bounds3 box = overlap(scene.nodes_[a].bounds, scene.nodes_[b].bounds);
                if (box.empty()) return kNoNode;
                markImpliedOperands(a, b);
                return addNode({NodeKind::Intersection, false, box, a, b});
            }
            case Op::Difference: {
                const BooleanScope scope(*this, node);
                const uint32_t a = build(*node.left, worldFromNode);
                if (a == kNoNode) return kNoNode;
                const uint32_t b = build(*node.right, worldFromNode);
                const Bounds3& box = scene.nodes_[a].bounds;
                if (b == kNoNode || overlap(box, scene.nodes_[b].bounds).empty()) return a;
                markImpliedOperands(a, b);
                return addNode({NodeKind::Difference, false, box, a, b});
            }
        }
        return kNoNode;
    }

    // The operands of an intersection or difference whose bounds test the parent's implies
    // (CompiledNode::boundsImplied).
    void markImpliedOperands(uint32_t left, uint32_t right) {
        scene.nodes_[left].boundsImplied = true;
        if (scene.nodes_[right].bounds.contains(scene.nodes_[left].bounds))
            scene.nodes_[right].boundsImplied = true;
    }

    // Collects the non-empty operands of a maximal chain of unions.
    void gatherUnion(const Node& node, const Mat4& worldFromNode, std::vector<uint32_t>& out) {
        for (const NodePtr& child : {node.left, node.right}) {
            if (!child) continue;
            if (child->op == Op::Union) {
                Mat4 worldFromChild = worldFromNode;
                if (child->parentFromNode != Mat4(1.0)) {
                    checkTransform(child->parentFromNode, *child, "the transform");
                    worldFromChild = worldFromNode * child->parentFromNode;
                }
                gatherUnion(*child, worldFromChild, out);
            } else if (const uint32_t c = build(*child, worldFromNode); c != kNoNode) {
                out.push_back(c);
            }
        }
    }

    uint32_t buildLeaf(const Node& node, const Mat4& worldFromLocal) {
        checkTransform(worldFromLocal, node, "the accumulated transform");
        const Mat4 localFromWorld = glm::inverse(worldFromLocal);
        if (!isFinite(localFromWorld))
            throw CompileError("the accumulated transform cannot be inverted", node.tags.source);
        LeafGeometry geometry{node.primitive, Affine(localFromWorld), {}};
        Bounds3 box;
        std::visit(
            [&](const auto& shape) {
                if constexpr (HasValidation<std::decay_t<decltype(shape)>>) {
                    if (const char* why = shape.invalidReason())
                        throw CompileError(why, node.tags.source);
                }
                if constexpr (HasSheet<std::decay_t<decltype(shape)>>) {
                    if (boolean && shape.isSheet())
                        throw CompileError(
                            std::string("a surface (solid=false) cannot be an operand of ") +
                                opName(boolean->op) +
                                ": it has no inside; use it as a top-level object, or declare a "
                                "closed patch set solid=true",
                            node.tags.source);
                    if (shape.isSheet()) scene.hasSheets_ = true;
                }
                geometry.localBounds = shape.bounds();
                box = worldBounds(shape, worldFromLocal);
            },
            node.primitive);
        const uint32_t index = static_cast<uint32_t>(scene.leaves_.size());
        scene.leaves_.push_back(geometry);
        scene.frames_.push_back({worldFromLocal, glm::transpose(Mat3(localFromWorld)), node.tags});
        return addNode({NodeKind::Leaf, false, box, index});
    }

    uint32_t buildUnion(std::vector<uint32_t>& children) {
        if (children.empty()) return kNoNode;
        if (children.size() == 1) return children[0];
        // Bounded children first (they go in the BVH), unbounded ones after.
        auto firstUnbounded =
            std::stable_partition(children.begin(), children.end(),
                                  [&](uint32_t c) { return scene.nodes_[c].bounds.finite(); });
        CompiledNode u;
        u.first = static_cast<uint32_t>(scene.children_.size());
        u.count = static_cast<uint32_t>(children.size());
        u.bounded = static_cast<uint32_t>(firstUnbounded - children.begin());
        for (uint32_t c : children) u.bounds.extend(scene.nodes_[c].bounds);
        if (u.bounded >= kBvhMinChildren) {
            u.bvhRoot =
                buildBvh(std::span(children.data(), u.bounded), scene.nodes_, u.first, scene.bvh_);
            // The BVH root's box is the hull of the same children, i.e. u.bounds.
            u.boundsImplied = u.bounded == u.count;
        }
        scene.children_.insert(scene.children_.end(), children.begin(), children.end());
        return addNode(u);
    }

    uint32_t addNode(const CompiledNode& n) {
        scene.nodes_.push_back(n);
        return static_cast<uint32_t>(scene.nodes_.size() - 1);
    }
};

Scene Scene::compile(const NodePtr& root) {
    Scene scene;
    Compiler compiler{scene};
    const size_t leaves = countLeaves(root.get());
    scene.leaves_.reserve(leaves);
    scene.frames_.reserve(leaves);
    scene.nodes_.reserve(2 * leaves + 1);
    // The root is always a union (of the top-level objects): closest() relies on it.
    std::vector<uint32_t> top;
    if (root) {
        if (root->op == Op::Union) {
            Mat4 world(1.0);
            if (root->parentFromNode != Mat4(1.0)) {
                checkTransform(root->parentFromNode, *root, "the transform");
                world = root->parentFromNode;
            }
            compiler.gatherUnion(*root, world, top);
        } else if (const uint32_t c = compiler.build(*root, Mat4(1.0)); c != kNoNode) {
            top.push_back(c);
        }
    }
    const uint32_t rootUnion = compiler.buildUnion(top);
    if (rootUnion != kNoNode && scene.nodes_[rootUnion].kind == NodeKind::Union) {
        scene.root_ = rootUnion;
    } else {
        // Zero or one top-level object: wrap it in a union of its own.
        CompiledNode u;
        u.first = static_cast<uint32_t>(scene.children_.size());
        if (rootUnion != kNoNode) {
            scene.children_.push_back(rootUnion);
            u.count = 1;
            u.bounds = scene.nodes_[rootUnion].bounds;
            u.bounded = u.bounds.finite() ? 1 : 0;
        }
        scene.root_ = compiler.addNode(u);
    }
    return scene;
}

}  // namespace csg
