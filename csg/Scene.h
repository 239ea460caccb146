// A compiled scene and the three queries every client of csgray stands on.
//
//   spans(ray)          the whole span list of the ray within [tmin, tmax]
//   closest(ray)        the first surface crossing in [tmin, tmax]
//   occluded(ray)       whether any solid lies along [tmin, tmax] (stops at the first)
//
// The scene is the union of everything in the tree (OpenSCAD's implicit top-level union).
// Queries are const and thread-safe; each thread brings its own QueryContext, whose scratch
// memory grows to the largest ray seen and is then reused: no heap allocation per ray.
#pragma once

#include <limits>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "csg/Ray.h"
#include "csg/Span.h"
#include "csg/Tree.h"
#include "primitives/Polyhedron.h"
#include "primitives/base/Accel.h"
#include "primitives/base/Bounds.h"

namespace csg {

// A tree that cannot be compiled (singular or non-finite transform, bad primitive parameter).
// source is the offending node's Tags::source, for io/ to turn into file:line:col.
struct CompileError : std::runtime_error {
    uint32_t source;
    CompileError(const std::string& message, uint32_t sourceTag)
        : std::runtime_error(message), source(sourceTag) {}
};

// Work counters of one context, summed over its queries (benchmarks and --stats read them).
struct QueryStats {
    uint64_t rays = 0;
    uint64_t nodeVisits = 0;      // CSG nodes and BVH slots whose boxes were tested, grid cells
                                  // entered
    uint64_t primitiveTests = 0;  // primitive solves after their bounds were hit
    uint64_t slabCulls = 0;       // nodes whose box the ray met and slab polyhedron it missed
};

// The top-level object (a child of the scene's root union) that last blocked an occluded()
// ray of a coherent stream (one thread's shadow rays toward one light), tried first by the
// next: neighbouring pixels are mostly shadowed by the same object. A union's answer is the OR
// of its children's, so the cache changes how soon the answer is found, never the answer.
// (Tried for closest() on primary rays too: the front-to-back BVH walk already finds the
// first hit early, and a cached object that is missed costs a whole evaluation: csg_grid got
// slower, bench/README.md at 68b03c3.)
struct ObjectCache {
    uint32_t node = std::numeric_limits<uint32_t>::max();  // none yet
};

// Per-thread scratch: a stack of spans holding every intermediate list of one query.
class QueryContext {
public:
    QueryContext() { stack_.resize(256); }
    QueryStats stats;

private:
    friend class Scene;
    friend struct SpanWalk;
    std::vector<Span> stack_;
    // The grid walks' mailbox: stamp_[p] == walk means the child at position p of
    // Scene::children_ was visited by the walk numbered walk. Each walk takes a new number, so
    // nothing is cleared per ray; the vector grows once per scene to its children's count.
    std::vector<uint32_t> stamp_;
    uint32_t walks_ = 0;
};

// What a leaf's surface looks like at a hit, computed only on request.
struct SurfacePoint {
    Vec3 point;   // world position o + t d
    Vec3 normal;  // outward unit normal of the solid (difference cuts already flipped)
};

struct LeafGeometry;
struct LeafFrame;
struct CompiledNode;
struct BvhNode;
struct BoundingBall;
struct DiagonalSlabs;
struct UniformGrid;
struct HalvingGrid;

// What Scene::compile builds beyond the tree: neither changes a span's extent on a closed mesh
// away from its edges, only the time, the memory and, for polygon meshes, the edge cases and
// normals.
struct CompileOptions {
    // The structure over each union's objects and each mesh's faces (primitives/base/Accel.h).
    Accel accel = Accel::Sah;
    // The crossing test of every polygon mesh (primitives/Polyhedron.h).
    PolygonMethod polygonMethod = PolygonMethod::Watertight;
    // Kay and Kajiya's slab polyhedra (csg/Compiled.h DiagonalSlabs) on the nodes where they are
    // tighter than the axis boxes, tested after the box and the bounding ball.
    bool slabs = false;
};

class Scene {
public:
    // Throws CompileError. root may be nullptr (the empty scene). options.accel picks the
    // structure over the objects of each union and the faces of each mesh
    // (primitives/base/Accel.h); every choice gives the same answers.
    static Scene compile(const NodePtr& root, const CompileOptions& options = {});

    Scene();
    ~Scene();
    Scene(Scene&&) noexcept;
    Scene& operator=(Scene&&) noexcept;

    // Spans within [ray.tmin, ray.tmax], sorted, disjoint, regularized. An end at tmin or tmax
    // that is not a surface has face kClipFace. The view lives in ctx until its next query.
    std::span<const Span> spans(const Ray& ray, QueryContext& ctx) const;
    // The first span end in [tmin, tmax] that is a surface, or nothing.
    std::optional<Hit> closest(const Ray& ray, QueryContext& ctx) const;
    // True when a span of positive length lies within [tmin, tmax].
    bool occluded(const Ray& ray, QueryContext& ctx) const;
    // The same answer, trying cache's object first and remembering the one that blocks.
    bool occluded(const Ray& ray, QueryContext& ctx, ObjectCache& cache) const;

    SurfacePoint surface(const Ray& ray, const Hit& hit) const;
    // Point-membership classification of the closed solid, from the primitives' inside tests.
    bool inside(const Vec3& p) const;

    Bounds3 bounds() const;
    size_t leafCount() const;
    const Tags& leafTags(uint32_t leaf) const;
    // Index of the leaf's primitive in Primitive (the variant), and the primitive itself.
    const Primitive& leafPrimitive(uint32_t leaf) const;
    const Mat4& leafWorldFromLocal(uint32_t leaf) const;
    // Per leaf, a box outside which its surface cannot bound the part: the overlap of its own
    // bounds with those of every operator above it (an intersection's bounds are its operands'
    // overlap, a difference's its left operand's), so a difference's right operand reaches
    // only as far as the left one does. Empty for a leaf that nothing of the part can show.
    std::vector<Bounds3> leafReach() const;

    // Bytes held by the structures over unions' children and over meshes' faces (BVH nodes,
    // grids and their lists; a mesh placed many times counts once): what --accel changes in
    // memory.
    size_t structureBytes() const;

private:
    friend struct SpanWalk;
    friend struct Compiler;
    std::vector<LeafGeometry> leaves_;    // indexed by Hit::leaf; read by the ray loop
    std::vector<LeafFrame> frames_;       // same index; read on request
    std::vector<Affine> frameFromWorld_;  // the leaves' frame groups (LeafGeometry::frame)
    std::vector<uint8_t> worldFrames_;    // same index: 1 where the group's frame is the world's
    std::vector<CompiledNode> nodes_;
    std::vector<uint32_t> children_;  // child node indices of n-ary unions
    std::vector<BvhNode> bvh_;
    std::vector<UniformGrid> grids_;         // CompiledNode::grid
    std::vector<HalvingGrid> halvingGrids_;  // CompiledNode::grid when halving
    std::vector<BoundingBall> balls_;        // CompiledNode::ball
    std::vector<DiagonalSlabs> slabs_;       // CompiledNode::slabs
    uint32_t root_ = 0;
    bool hasSheets_ = false;  // a leaf is a sheet: unions must look for sheet crossings
};

}  // namespace csg
