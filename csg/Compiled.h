// The compiled scene's flat arrays (private to csg/). Built by Compile.cpp, read by Query.cpp.
#pragma once

#include <cstdint>
#include <limits>

#include "csg/Tree.h"
#include "primitives/base/Bounds.h"
#include "primitives/base/WideBvh.h"

namespace csg {

inline constexpr uint32_t kNoNode = std::numeric_limits<uint32_t>::max();

// A leaf with its transforms flattened, split by who reads it: the ray loop touches only the
// hot part (what it needs to solve), so a million leaves cost ~160 bytes each in the cache
// (sizeof(LeafGeometry) on x86-64) instead of ~460; surface(), inside() and accessors read the
// cold part.
//
// Leaves share a *frame group*: the frame of the nearest transform above them that is not a
// signed axis permutation plus a shift (rotate by multiples of 90 degrees, mirror, translate,
// center=true). The ray loop maps the ray into a group's frame once (Scene::frameFromWorld_)
// and reaches each leaf's own frame from there by a swizzle, exact but for the shift's one
// rounding: in a part like (box n sphere) - three turned cylinders that is one matrix
// transform and one reciprocal of d for five leaves instead of five.
struct LeafGeometry {
    Primitive shape;
    Bounds3 localBounds;  // where the ray origin is moved before solving
    uint32_t frame = 0;   // index into Scene::frameFromWorld_
    // Local from frame, when not the identity (permuted): component j of a local point is
    // sign[j] * p[axis[j]] + offset[j] for the frame point p, of a vector sign[j] * v[axis[j]].
    bool permuted = false;
    uint8_t axis[3] = {0, 1, 2};
    double sign[3] = {1.0, 1.0, 1.0};
    Vec3 offset{0.0};
};

struct LeafFrame {
    Affine localFromWorld;  // for surface() and inside(); the ray loop uses the frame group
    Mat4 worldFromLocal;
    Mat3 normalFromLocal;  // inverse transpose of worldFromLocal's linear part
    Tags tags;
    // A planar leaf's one normal (isPlanar: a half-space), as surface() would compute it at
    // any of its points: it is asked for at every hit on a floor, and costs a square root and
    // divisions each time.
    bool planeNormalKnown = false;
    Vec3 planeNormal{0.0};
};

// The unit world normal of a leaf whose local normal is n (surface() and the compile).
inline Vec3 worldNormal(const LeafFrame& frame, const Vec3& n) {
    const Vec3 world = frame.normalFromLocal * n;
    const double len = glm::length(world);
    return len > 0.0 ? world / len : n;
}

// A ball (world frame) that contains a node's solid: the ball of a leaf that has one (a sphere,
// primitives/Primitive.h HasBoundingBall) placed by a similarity
// (rotation, mirror, uniform scale, shift), which bounds every intersection and difference
// it is the left operand of. A line is tested against it with a dot product and no division,
// before any leaf's frame is entered: a cheaper exact reject than the leaves' own tests, and
// tighter than the axis-aligned box of a turned part (bench/scenes/csg_grid: most rays that
// meet a part's box miss the part).
struct BoundingBall {
    Vec3 center;
    double radius = 0.0;
    double size = 0.0;  // |center| + radius: the scale of the test's rounding (kBallMarginRel)
};

// The lecture's slab polyhedron (Kay and Kajiya, "Ray tracing complex scenes", 1986) around a
// node's solid, beyond its axis box: the extent of n . x over the solid along the four body
// diagonals kSlabNormals. With the box's three pairs of planes that is a polyhedron of up to 14
// faces, which hugs a turned part far tighter than its box (a unit cube turned 45 degrees about z
// reaches 1.914 along (1, 1, 1) in its box, 1.207 itself). A ray forms n . o and 1 / (n . d)
// once for all nodes (SpanWalk); a node then costs four subtract-multiply pairs per plane pair.
// margin: tol::kBallMarginRel times the largest |lo|, |hi|, the planes' own share of the
// rounding allowance (the ray's share is its origin's).
inline constexpr Vec3 kSlabNormals[4] = {
    {1.0, 1.0, 1.0}, {1.0, 1.0, -1.0}, {1.0, -1.0, 1.0}, {-1.0, 1.0, 1.0}};
struct DiagonalSlabs {
    double lo[4], hi[4];
    double margin = 0.0;
};

// Leaf:         first = leaf index.
// Intersection, Difference: first = left node, second = right node.
// Union:        children_[first, first + count) are the child nodes; the first `bounded`
//               of them are organized by the union's structure (primitives/base/Accel.h): its BVH
//               (rooted at bvhRoot) or its grid (grid), or neither for a short union scanned
//               linearly; the rest have unbounded bounds.
struct CompiledNode {
    Op kind = Op::Union;
    // The ray loop does not test this node's bounds, because a test that has just passed
    // implies this one, or one that follows does its work:
    // - the left operand of an intersection or difference: the parent's bounds (the overlap,
    //   or the left operand's own) lie inside it, and the parent evaluates it over the same
    //   [t0, t1]; the slab test is monotone in the box under rounding, so it would pass;
    // - the right operand of one whose bounds contain the left operand's: it is evaluated
    //   only over the hull of the left operand's spans, which lies in the left's box, hence
    //   in its own (a skipped cull only ever costs work: the bounds are conservative, so the
    //   spans found are the same);
    // - a union whose children all lie in its BVH: the BVH root's slots are tested first,
    //   over the same range, and a ray that misses this box misses them all;
    // - a union's child alone in a BVH leaf slot: the slot's box is the child's, tested over
    //   a range [t0, t1'] with t1' no lower than the child is evaluated over, and the walk
    //   skips the child when its entry lies past the lowered t1 (anyCached, which tries an
    //   object outside the BVH walk, tests the object's box itself);
    // - a leaf in the world's frame whose bounds contain its local box: evalLeaf clips the ray
    //   to that box before anything else, the same test or a tighter one.
    bool boundsImplied = false;
    Bounds3 bounds;
    uint32_t first = 0;
    uint32_t second = 0;
    uint32_t count = 0;
    uint32_t bounded = 0;
    uint32_t bvhRoot = kNoNode;
    // The union's grid instead of a BVH (primitives/base/Grid.h): an index into Scene::grids_ or
    // Scene::halvingGrids_ (halving), or kNoNode.
    uint32_t grid = kNoNode;
    bool halving = false;
    // Index into Scene::balls_, or kNoNode. Held only by the topmost node it bounds: an
    // intersection or difference takes over its operand's ball, which is then not tested
    // again (the operand is evaluated only after the parent's test passed, and a line test
    // does not depend on the range).
    uint32_t ball = kNoNode;
    // Index into Scene::slabs_, or kNoNode (CompileOptions::slabs): held where the slab
    // polyhedron is tighter than the box, except by the left operand of an intersection or
    // difference, which is evaluated only inside its parent's (no larger) polyhedron.
    uint32_t slabs = kNoNode;

    // Whether a union's bounded children are walked through a structure, not scanned.
    bool structured() const { return bvhRoot != kNoNode || grid != kNoNode; }
};

// The 4-wide BVH over a union's bounded children is made of BvhNode
// (primitives/base/WideBvh.h): a leaf slot is a run of Scene::children_, a node slot an index
// into Scene::bvh_.

}  // namespace csg
