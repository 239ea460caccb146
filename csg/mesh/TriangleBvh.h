// A bounding volume hierarchy over the triangles of a mesh, answering "where does this line
// first meet the mesh" with a watertight ray-triangle test (Woop, Benthin and Wald 2013): a
// ray through a shared edge or vertex hits at least one of the triangles there, never none.
#pragma once

#include <cstdint>
#include <optional>
#include <utility>
#include <vector>

#include "csg/Bounds.h"
#include "csg/mesh/TriangleMesh.h"

namespace csg {

class TriangleBvh {
public:
    // Keeps a reference to mesh, which must outlive the BVH. Built with `threads` threads (0:
    // all cores); the tree is the same for any thread count.
    explicit TriangleBvh(const TriangleMesh& mesh, int threads = 0);

    // The hit parameter of smallest |t| among the mesh's crossings of o + t d with t in
    // [tmin, tmax] (tmin may be negative: both directions), or nothing. Thread-safe; no
    // allocation.
    std::optional<double> nearestHit(const Vec3& o, const Vec3& d, double tmin, double tmax) const;

private:
    struct Node {
        Bounds3 box;
        uint32_t first = 0;  // leaf: first index into order_; inner: the right child
        uint32_t count = 0;  // leaf: triangle count; inner: 0 (the left child is next)
    };
    // Builds the subtree of order_[begin, end) into nodes_[index, index + nodeCount(end -
    // begin)); subtrees of the top `parallelDepth` levels split their halves between threads.
    void build(uint32_t begin, uint32_t end, uint32_t index, int parallelDepth);
    void tabulateNodeCounts(uint32_t n);
    Bounds3 triangleBox(uint32_t triangle) const;
    uint32_t nodeCount(uint32_t count) const;  // nodes of a subtree over count triangles

    const TriangleMesh& mesh_;
    std::vector<Node> nodes_;
    std::vector<uint32_t> order_;  // triangle indices, leaves own contiguous ranges
    struct Item {
        Vec3 center;  // of the triangle's box: the split's key
        uint32_t triangle;
    };
    std::vector<Item> items_;  // only while building; becomes order_
    // (count, nodeCount(count)) of every subtree size, ascending; only while building.
    std::vector<std::pair<uint32_t, uint32_t>> nodeCounts_;
};

// The watertight test: t of the crossing of o + t d with triangle (a, b, c), either side, or
// nothing when the line misses or lies in the triangle's plane.
std::optional<double> rayTriangle(const Vec3& o, const Vec3& d, const Vec3& a, const Vec3& b,
                                  const Vec3& c);

}  // namespace csg
