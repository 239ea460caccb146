#include "csg/mesh/TriangleBvh.h"

#include <algorithm>
#include <cmath>
#include <thread>

#include "primitives/base/ParallelFor.h"

namespace csg {

namespace {

// The squared distance from p to the nearest point of box (0 inside).
double squaredDistanceToBox(const Vec3& p, const Bounds3& box) {
    const Vec3 below = glm::max(box.lo - p, Vec3(0.0)), above = glm::max(p - box.hi, Vec3(0.0));
    const Vec3 gap = below + above;
    return glm::dot(gap, gap);
}

// Leaves hold up to this many triangles.
constexpr uint32_t kLeafSize = 4;

}  // namespace

// Median splits make a subtree's shape a function of its triangle count alone, so every
// subtree's place in the node array is known before it is built, and the halves can be built at
// once, in any order, into the same array. The subtrees of one level have at most two counts
// (floor and ceiling of n / 2^depth): this table has under 64 rows.
void TriangleBvh::tabulateNodeCounts(uint32_t n) {
    std::vector<uint32_t> sizes{n};
    for (size_t i = 0; i < sizes.size(); ++i) {
        const uint32_t count = sizes[i];
        if (count <= kLeafSize) continue;
        for (const uint32_t half : {count / 2, count - count / 2})
            if (std::find(sizes.begin(), sizes.end(), half) == sizes.end()) sizes.push_back(half);
    }
    std::sort(sizes.begin(), sizes.end());
    nodeCounts_.clear();
    for (const uint32_t count : sizes)
        nodeCounts_.push_back(
            {count,
             count <= kLeafSize ? 1 : 1 + nodeCount(count / 2) + nodeCount(count - count / 2)});
}

uint32_t TriangleBvh::nodeCount(uint32_t count) const {
    const auto it = std::lower_bound(nodeCounts_.begin(), nodeCounts_.end(),
                                     std::pair<uint32_t, uint32_t>{count, 0});
    return it->second;
}

TriangleBvh::TriangleBvh(const TriangleMesh& mesh, int threads) : mesh_(mesh) {
    const size_t n = mesh.triangles.size();
    // The split key (a triangle's box centre) sits beside its index, so the partitioning reads
    // one contiguous array instead of gathering centres through the order.
    items_.resize(n);
    const int workers = resolveThreads(threads);
    constexpr uint64_t kChunk = 4096;
    parallelFor((n + kChunk - 1) / kChunk, workers, [&](int, uint64_t chunk) {
        for (size_t i = chunk * kChunk; i < std::min<size_t>(n, (chunk + 1) * kChunk); ++i)
            items_[i] = {triangleBox(uint32_t(i)).center(), uint32_t(i)};
    });
    if (n > 0) {
        tabulateNodeCounts(uint32_t(n));
        nodes_.resize(nodeCount(uint32_t(n)));
        // Subtrees split between threads down to the level with one per worker.
        int parallelDepth = 0;
        while ((1 << parallelDepth) < workers && parallelDepth < 8) ++parallelDepth;
        build(0, uint32_t(n), 0, parallelDepth);
    }
    order_.resize(n);
    for (size_t i = 0; i < n; ++i) order_[i] = items_[i].triangle;
    items_ = {};
    nodeCounts_ = {};
}

Bounds3 TriangleBvh::triangleBox(uint32_t triangle) const {
    Bounds3 box;
    for (const uint32_t v : mesh_.triangles[triangle]) box.extend(mesh_.positions[v]);
    return box;
}

void TriangleBvh::build(uint32_t begin, uint32_t end, uint32_t index, int parallelDepth) {
    // Median splits keep the depth at log2(n / kLeafSize) (under 31), well below the
    // traversal stack. A node's box is its triangles' (a leaf) or its children's union.
    if (end - begin <= kLeafSize) {
        Bounds3 box;
        for (uint32_t i = begin; i < end; ++i) box.extend(triangleBox(items_[i].triangle));
        nodes_[index] = {box, begin, end - begin};
        return;
    }
    // Median split on the widest axis of the centres: balanced.
    Bounds3 centers;
    for (uint32_t i = begin; i < end; ++i) centers.extend(items_[i].center);
    const Vec3 e = centers.extent();
    const int axis = e.x >= e.y ? (e.x >= e.z ? 0 : 2) : (e.y >= e.z ? 1 : 2);
    const uint32_t mid = begin + (end - begin) / 2;
    std::nth_element(
        items_.begin() + begin, items_.begin() + mid, items_.begin() + end,
        [axis](const Item& p, const Item& q) { return p.center[axis] < q.center[axis]; });
    const uint32_t left = index + 1, right = index + 1 + nodeCount(mid - begin);
    if (parallelDepth > 0) {
        std::thread other([&] { build(begin, mid, left, parallelDepth - 1); });
        build(mid, end, right, parallelDepth - 1);
        other.join();
    } else {
        build(begin, mid, left, 0);
        build(mid, end, right, 0);
    }
    Bounds3 box = nodes_[left].box;
    box.extend(nodes_[right].box);
    nodes_[index] = {box, right, 0};
}

double TriangleBvh::distance(const Vec3& p, double reach) const {
    // Depth first, the nearer child first, pruning boxes farther than the best so far. A box
    // is measured once, when its parent is visited; it is skipped then if already too far, and
    // again when popped if a nearer triangle was found meanwhile.
    double best2 = reach * reach;
    bool found = false;
    struct Entry {
        uint32_t node;
        double d2;  // squared distance from p to the node's box
    };
    Entry stack[64];
    int top = 0;
    if (!nodes_.empty()) {
        const double d2 = squaredDistanceToBox(p, nodes_[0].box);
        if (d2 <= best2) stack[top++] = {0, d2};
    }
    while (top > 0) {
        const Entry entry = stack[--top];
        if (entry.d2 > best2) continue;
        const Node& node = nodes_[entry.node];
        if (node.count == 0) {
            const Entry left{entry.node + 1, squaredDistanceToBox(p, nodes_[entry.node + 1].box)};
            const Entry right{node.first, squaredDistanceToBox(p, nodes_[node.first].box)};
            const bool leftFirst = left.d2 <= right.d2;
            // Pushed last, popped first.
            for (const Entry& child : {leftFirst ? right : left, leftFirst ? left : right})
                if (child.d2 <= best2) stack[top++] = child;
            continue;
        }
        for (uint32_t i = node.first; i < node.first + node.count; ++i) {
            const auto& tri = mesh_.triangles[order_[i]];
            const Vec3 q = closestPointOnTriangle(p, mesh_.positions[tri[0]],
                                                  mesh_.positions[tri[1]], mesh_.positions[tri[2]]);
            const double d2 = glm::dot(q - p, q - p);
            if (d2 <= best2) {
                best2 = d2;
                found = true;
            }
        }
    }
    return found ? std::sqrt(best2) : kInfinity;
}

}  // namespace csg
