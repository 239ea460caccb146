// Compiles a CSG tree into the flat arrays the queries walk: transforms flattened into each
// leaf, nested unions flattened into n-ary unions, bounds computed bottom-up (union = hull,
// intersection = overlap, difference = left operand), empty subtrees pruned, and a BVH over
// every union with enough bounded children (and the structure --accel names over each mesh's
// faces).
#include <cmath>
#include <sstream>
#include <unordered_map>

#include "csg/Bvh.h"
#include "csg/Compiled.h"
#include "csg/Scene.h"
#include "primitives/base/Grid.h"

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

// Whether m maps each axis to an axis, exactly, with a sign and a shift: entries 0 and +-1 only
// (rotations by multiples of 90 degrees, mirrors, translations). Such a map composes with
// another one without rounding in its linear part. m has passed checkTransform.
bool isAxisPermutation(const Mat4& m) {
    if (m[0][3] != 0.0 || m[1][3] != 0.0 || m[2][3] != 0.0 || m[3][3] != 1.0) return false;
    for (int j = 0; j < 3; ++j) {
        int axes = 0;
        for (int i = 0; i < 3; ++i) {
            if (m[j][i] == 0.0) continue;
            if (std::abs(m[j][i]) != 1.0) return false;
            ++axes;
        }
        if (axes != 1) return false;  // (a repeated row would be singular: refused before)
    }
    return true;
}

// The frame group a node's leaves map the ray through (LeafGeometry::frame): the group's world
// transform, and its index in Scene::frameFromWorld_ once a leaf has needed it.
struct FrameGroup {
    Mat4 worldFromGroup{1.0};
    uint32_t index = kNoNode;
};

// Where a node sits: its world transform, its frame group, and its frame within that group
// (an axis permutation with a shift, composed exactly but for the shift).
struct Placement {
    Mat4 worldFromNode{1.0};
    FrameGroup* group = nullptr;
    Mat4 groupFromNode{1.0};
};

// Leaves the compiled scene will hold: one per placement of a primitive, so a shared subtree
// counts once for each use. Reserving for them up front avoids regrowing ~10^6-entry arrays.
size_t countLeaves(const Node* node) {
    if (!node) return 0;
    if (node->op == Op::Leaf) return 1;
    return countLeaves(node->left.get()) + countLeaves(node->right.get());
}

}  // namespace

// A node holds its slab polyhedron (CompileOptions::slabs) when along some diagonal it is
// narrower than the node's box by at least this fraction of the box's width there: a thinner
// cut rarely culls a ray the box lets through, and the test costs about as much as a box's.
constexpr double kSlabsGain = 0.1;

// The slabs of nothing in particular: every plane pair at infinity.
DiagonalSlabs unboundedSlabs() {
    DiagonalSlabs s;
    for (int i = 0; i < 4; ++i) s.lo[i] = -kInfinity, s.hi[i] = kInfinity;
    return s;
}

// The slabs around the box `local` placed by worldFromLocal: its eight corners' extents.
DiagonalSlabs slabsAround(const Bounds3& local, const Mat4& worldFromLocal) {
    if (!local.finite()) return unboundedSlabs();
    DiagonalSlabs s;
    for (int i = 0; i < 4; ++i) s.lo[i] = kInfinity, s.hi[i] = -kInfinity;
    for (int corner = 0; corner < 8; ++corner) {
        const Vec3 p((corner & 1) ? local.hi.x : local.lo.x, (corner & 2) ? local.hi.y : local.lo.y,
                     (corner & 4) ? local.hi.z : local.lo.z);
        const Vec3 q = transformPoint(worldFromLocal, p);
        for (int i = 0; i < 4; ++i) {
            const double e = glm::dot(kSlabNormals[i], q);
            s.lo[i] = std::min(s.lo[i], e), s.hi[i] = std::max(s.hi[i], e);
        }
    }
    return s;
}

// The slabs around both solids (their union), and around what they share (their intersection).
DiagonalSlabs hullOf(const DiagonalSlabs& a, const DiagonalSlabs& b) {
    DiagonalSlabs s;
    for (int i = 0; i < 4; ++i)
        s.lo[i] = std::min(a.lo[i], b.lo[i]), s.hi[i] = std::max(a.hi[i], b.hi[i]);
    return s;
}
DiagonalSlabs overlapOf(const DiagonalSlabs& a, const DiagonalSlabs& b) {
    DiagonalSlabs s;
    for (int i = 0; i < 4; ++i)
        s.lo[i] = std::max(a.lo[i], b.lo[i]), s.hi[i] = std::min(a.hi[i], b.hi[i]);
    return s;
}

struct Compiler {
    Scene& scene;
    CompileOptions options;
    // Per node, the extents of its solid along kSlabNormals (a superset: a leaf's are its
    // local box's), whether or not the node holds them (holdSlabs). Empty unless
    // CompileOptions::slabs asks for slabs: a leaf's cost eight corner transforms.
    std::vector<DiagonalSlabs> extents{};
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

    // The placement of node under parent. A transform that is not an axis permutation starts
    // a new frame group, kept in `started` (which must outlive the node's subtree's build).
    static Placement place(const Node& node, const Placement& parent, FrameGroup& started) {
        if (node.parentFromNode == Mat4(1.0)) return parent;
        checkTransform(node.parentFromNode, node, "the transform");
        Placement p{parent.worldFromNode * node.parentFromNode, parent.group, Mat4(1.0)};
        if (isAxisPermutation(node.parentFromNode)) {
            p.groupFromNode = parent.groupFromNode * node.parentFromNode;
        } else {
            started = FrameGroup{p.worldFromNode};
            p.group = &started;
        }
        return p;
    }

    // Returns the compiled node index of `node` placed under `parent`, or kNoNode when the
    // subtree is empty.
    uint32_t build(const Node& node, const Placement& parent) {
        FrameGroup started;
        const Placement placement = place(node, parent, started);
        switch (node.op) {
            case Op::Leaf:
                return buildLeaf(node, placement);
            case Op::Union: {
                std::vector<uint32_t> children;
                gatherUnion(node, placement, children);
                return buildUnion(children);
            }
            case Op::Intersection: {
                const BooleanScope scope(*this, node);
                const uint32_t a = build(*node.left, placement);
                if (a == kNoNode) return kNoNode;
                const uint32_t b = build(*node.right, placement);
                if (b == kNoNode) return kNoNode;
                const Bounds3 box = overlap(scene.nodes_[a].bounds, scene.nodes_[b].bounds);
                if (box.empty()) return kNoNode;
                markImpliedOperands(a, b);
                const uint32_t added = addNode({Op::Intersection, false, box, a, b});
                takeBall(added, ballRadius(b) < ballRadius(a) ? b : a);  // the smaller ball
                setSlabs(
                    added, [&] { return overlapOf(extents[a], extents[b]); }, a);
                return added;
            }
            case Op::Difference: {
                const BooleanScope scope(*this, node);
                const uint32_t a = build(*node.left, placement);
                if (a == kNoNode) return kNoNode;
                const uint32_t b = build(*node.right, placement);
                const Bounds3& box = scene.nodes_[a].bounds;
                if (b == kNoNode || overlap(box, scene.nodes_[b].bounds).empty()) return a;
                markImpliedOperands(a, b);
                const uint32_t added = addNode({Op::Difference, false, box, a, b});
                takeBall(added, a);
                setSlabs(
                    added, [&] { return extents[a]; }, a);
                return added;
            }
        }
        return kNoNode;
    }

    // The radius of the node's bounding ball; infinite when it has none.
    double ballRadius(uint32_t node) const {
        const uint32_t ball = scene.nodes_[node].ball;
        return ball == kNoNode ? kInfinity : scene.balls_[ball].radius;
    }

    // Moves the operand's bounding ball, if any, up to its parent (CompiledNode::ball).
    void takeBall(uint32_t parent, uint32_t operand) {
        scene.nodes_[parent].ball = scene.nodes_[operand].ball;
        scene.nodes_[operand].ball = kNoNode;
    }

    // A leaf's world bounding ball from its local one, when worldFromLocal is a similarity: the
    // columns of its linear part are orthogonal and of one length (to tol::kSimilarityRel).
    uint32_t worldBall(const LocalBall& ball, const Mat4& worldFromLocal) {
        const Vec3 c0(worldFromLocal[0]), c1(worldFromLocal[1]), c2(worldFromLocal[2]);
        const double l0 = glm::length(c0), l1 = glm::length(c1), l2 = glm::length(c2);
        const double scale = std::max({l0, l1, l2});
        if (!(std::min({l0, l1, l2}) >= scale * (1.0 - tol::kSimilarityRel))) return kNoNode;
        const double square = scale * scale;
        if (std::abs(glm::dot(c0, c1)) > tol::kSimilarityRel * square ||
            std::abs(glm::dot(c0, c2)) > tol::kSimilarityRel * square ||
            std::abs(glm::dot(c1, c2)) > tol::kSimilarityRel * square)
            return kNoNode;
        const Vec3 center = transformPoint(worldFromLocal, ball.center);
        const double radius = ball.radius * scale;
        if (!isFinite(worldFromLocal) || !std::isfinite(radius)) return kNoNode;
        scene.balls_.push_back({center, radius, glm::length(center) + radius});
        return static_cast<uint32_t>(scene.balls_.size() - 1);
    }

    // With CompileOptions::slabs: sets the node's extents to make()'s and holds them where they
    // pay (holdSlabs). `left`: the left operand of an intersection or difference, or kNoNode.
    template <class Make>
    void setSlabs(uint32_t node, Make&& make, uint32_t left = kNoNode) {
        if (!options.slabs) return;
        extents[node] = make();
        holdSlabs(node, left);
    }

    // Gives the node its slab polyhedron (extents[node]) when it is tighter than its box
    // (kSlabsGain); the left operand of an intersection or difference (`left`, or kNoNode) then
    // gives up its own, which the parent's test implies.
    void holdSlabs(uint32_t node, uint32_t left) {
        const Bounds3& box = scene.nodes_[node].bounds;
        if (!box.finite()) return;
        DiagonalSlabs& s = extents[node];
        const DiagonalSlabs ofBox = slabsAround(box, Mat4(1.0));  // the box's own extents
        bool tighter = false;
        double size = 0.0;
        for (int i = 0; i < 4; ++i) {
            if (!(s.lo[i] <= s.hi[i]) || !std::isfinite(s.lo[i]) || !std::isfinite(s.hi[i])) return;
            const double width = ofBox.hi[i] - ofBox.lo[i];
            tighter = tighter || width - (s.hi[i] - s.lo[i]) >= kSlabsGain * width;
            size = std::max({size, std::abs(s.lo[i]), std::abs(s.hi[i])});
        }
        if (!tighter) return;
        s.margin = tol::kBallMarginRel * size;
        scene.nodes_[node].slabs = static_cast<uint32_t>(scene.slabs_.size());
        scene.slabs_.push_back(s);
        if (left != kNoNode) scene.nodes_[left].slabs = kNoNode;
    }

    // The operands of an intersection or difference whose bounds test the parent's implies
    // (CompiledNode::boundsImplied).
    void markImpliedOperands(uint32_t left, uint32_t right) {
        scene.nodes_[left].boundsImplied = true;
        if (scene.nodes_[right].bounds.contains(scene.nodes_[left].bounds))
            scene.nodes_[right].boundsImplied = true;
    }

    // Collects the non-empty operands of a maximal chain of unions.
    void gatherUnion(const Node& node, const Placement& placement, std::vector<uint32_t>& out) {
        for (const NodePtr& child : {node.left, node.right}) {
            if (!child) continue;
            if (child->op == Op::Union) {
                FrameGroup started;
                gatherUnion(*child, place(*child, placement, started), out);
            } else if (const uint32_t c = build(*child, placement); c != kNoNode) {
                out.push_back(c);
            }
        }
    }

    // The structure over a mesh's faces that --accel asks for, built once per mesh however
    // many leaves place it (Polyhedron::organize).
    std::unordered_map<const PolyhedronData*, std::shared_ptr<const MeshStructure>> meshes{};
    std::shared_ptr<const MeshStructure> meshStructure(const PolyhedronData& data) {
        const auto [at, added] = meshes.try_emplace(&data);
        if (added) at->second = Polyhedron::organize(data, options.accel);
        return at->second;
    }

    uint32_t buildLeaf(const Node& node, const Placement& placement) {
        const Mat4& worldFromLocal = placement.worldFromNode;
        checkTransform(worldFromLocal, node, "the accumulated transform");
        const Mat4 localFromWorld = glm::inverse(worldFromLocal);
        if (!isFinite(localFromWorld))
            throw CompileError("the accumulated transform cannot be inverted", node.tags.source);
        LeafGeometry geometry{node.primitive, {}};
        if (auto* mesh = std::get_if<Polyhedron>(&geometry.shape)) {
            mesh->method = options.polygonMethod;
            if (mesh->data) mesh->structure = meshStructure(*mesh->data);
        }
        setFrame(geometry, placement, node);
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
        LeafFrame& frame =
            scene.frames_.emplace_back(LeafFrame{Affine(localFromWorld), worldFromLocal,
                                                 glm::transpose(Mat3(localFromWorld)), node.tags});
        if (isPlanar(node.primitive)) {
            frame.planeNormal = worldNormal(frame, primitiveNormal(node.primitive, Vec3(0.0), 0));
            frame.planeNormalKnown = true;
        }
        const uint32_t added = addNode({Op::Leaf, false, box, index});
        // In the world's frame, evalLeaf's test of the leaf's own box is this test or a tighter
        // one (CompiledNode::boundsImplied).
        if (scene.worldFrames_[geometry.frame] && !geometry.permuted &&
            box.contains(geometry.localBounds))
            scene.nodes_[added].boundsImplied = true;
        if (const std::optional<LocalBall> ball = boundingBall(node.primitive))
            scene.nodes_[added].ball = worldBall(*ball, worldFromLocal);
        setSlabs(added, [&] { return slabsAround(geometry.localBounds, worldFromLocal); });
        return added;
    }

    // The leaf's frame group (made on its first leaf) and its frame within the group: a group
    // point p is groupFromLocal * local, so along each local axis j, p[i] = s local[j] + c[i]
    // for the one row i where column j holds s = +-1, and local[j] = s p[i] - s c[i].
    void setFrame(LeafGeometry& geometry, const Placement& placement, const Node& node) {
        FrameGroup& group = *placement.group;
        if (group.index == kNoNode) {
            const Mat4 groupFromWorld = glm::inverse(group.worldFromGroup);
            if (!isFinite(groupFromWorld))
                throw CompileError("the accumulated transform cannot be inverted",
                                   node.tags.source);
            group.index = static_cast<uint32_t>(scene.frameFromWorld_.size());
            scene.frameFromWorld_.push_back(Affine(groupFromWorld));
            scene.worldFrames_.push_back(groupFromWorld == Mat4(1.0));
        }
        geometry.frame = group.index;
        const Mat4& groupFromLocal = placement.groupFromNode;
        if (groupFromLocal == Mat4(1.0)) return;
        geometry.permuted = true;
        for (int j = 0; j < 3; ++j) {
            for (int i = 0; i < 3; ++i) {
                if (groupFromLocal[j][i] == 0.0) continue;
                geometry.axis[j] = static_cast<uint8_t>(i);
                geometry.sign[j] = groupFromLocal[j][i];
            }
            geometry.offset[j] = -geometry.sign[j] * groupFromLocal[3][geometry.axis[j]];
        }
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
        Accel accel = options.accel;
        std::vector<Bounds3> boxes;
        if (u.bounded >= kBvhMinChildren &&
            (accel == Accel::Grid || accel == Accel::NonUniformGrid ||
             (accel == Accel::Auto && u.bounded >= kAutoGridMinItems))) {
            boxes.resize(u.bounded);
            for (uint32_t i = 0; i < u.bounded; ++i) boxes[i] = scene.nodes_[children[i]].bounds;
        }
        // auto: the grid is built to be judged, and kept when chosen.
        UniformGrid judged;
        if (accel == Accel::Auto) {
            accel = Accel::Sah;
            if (!boxes.empty()) {
                judged = buildUniformGrid(boxes, u.first);
                if (gridPays(judged)) accel = Accel::Grid;
            }
        }
        if (u.bounded >= kBvhMinChildren &&
            (accel == Accel::Grid || accel == Accel::NonUniformGrid)) {
            // A grid lists each child by its position in children_ (the union's run starts at
            // u.first), in the order given; the children's own bounds are tested as they are
            // visited (boundsImplied stays false).
            u.halving = accel == Accel::NonUniformGrid;
            if (u.halving) {
                u.grid = static_cast<uint32_t>(scene.halvingGrids_.size());
                scene.halvingGrids_.push_back(buildHalvingGrid(boxes, u.first));
            } else {
                u.grid = static_cast<uint32_t>(scene.grids_.size());
                scene.grids_.push_back(judged.cellStart.empty() ? buildUniformGrid(boxes, u.first)
                                                                : std::move(judged));
            }
        } else if (u.bounded >= kBvhMinChildren) {
            const BvhMethod method = accel == Accel::Median            ? BvhMethod::Median
                                     : accel == Accel::GoldsmithSalmon ? BvhMethod::GoldsmithSalmon
                                                                       : BvhMethod::Sah;
            u.bvhRoot = buildBvh(std::span(children.data(), u.bounded), scene.nodes_, u.first,
                                 scene.bvh_, method);
            // The BVH root's slots cover the same children: a ray that misses u.bounds misses
            // them all, so testing u.bounds first would only add a test.
            u.boundsImplied = u.bounded == u.count;
            // A leaf slot of one child has that child's box, tested just before it.
            for (size_t b = u.bvhRoot; b < scene.bvh_.size(); ++b) {
                const BvhNode& node = scene.bvh_[b];
                for (int k = 0; k < node.slots; ++k)
                    if (node.leafCount[k] == 1)
                        scene.nodes_[children[node.slot[k] - u.first]].boundsImplied = true;
            }
        }
        scene.children_.insert(scene.children_.end(), children.begin(), children.end());
        const uint32_t added = addNode(u);
        setSlabs(added, [&] {
            DiagonalSlabs all = extents[children[0]];
            for (const uint32_t c : children) all = hullOf(all, extents[c]);
            return all;
        });
        return added;
    }

    // Adds a node (with CompileOptions::slabs, its extents unbounded until its builder sets
    // them).
    uint32_t addNode(const CompiledNode& n) {
        scene.nodes_.push_back(n);
        if (options.slabs) extents.push_back(unboundedSlabs());
        return static_cast<uint32_t>(scene.nodes_.size() - 1);
    }
};

Scene Scene::compile(const NodePtr& root, const CompileOptions& options) {
    Scene scene;
    Compiler compiler{scene, options};
    const size_t leaves = countLeaves(root.get());
    scene.leaves_.reserve(leaves);
    scene.frames_.reserve(leaves);
    scene.nodes_.reserve(2 * leaves + 1);
    // The root is always a union (of the top-level objects): closest() relies on it.
    std::vector<uint32_t> top;
    FrameGroup worldGroup;
    const Placement world{Mat4(1.0), &worldGroup, Mat4(1.0)};
    if (root) {
        if (root->op == Op::Union) {
            FrameGroup started;
            compiler.gatherUnion(*root, Compiler::place(*root, world, started), top);
        } else if (const uint32_t c = compiler.build(*root, world); c != kNoNode) {
            top.push_back(c);
        }
    }
    const uint32_t rootUnion = compiler.buildUnion(top);
    if (rootUnion != kNoNode && scene.nodes_[rootUnion].kind == Op::Union) {
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
