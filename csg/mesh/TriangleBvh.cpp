#include "csg/mesh/TriangleBvh.h"

#include <algorithm>
#include <cmath>
#include <thread>

#include "csg/mesh/ParallelFor.h"

namespace csg {

std::optional<double> rayTriangle(const Vec3& o, const Vec3& d, const Vec3& a, const Vec3& b,
                                  const Vec3& c) {
    // Step 1: the axis of largest |d| becomes z; swapping x and y keeps the winding.
    const Vec3 ad = glm::abs(d);
    const int kz = ad.x >= ad.y ? (ad.x >= ad.z ? 0 : 2) : (ad.y >= ad.z ? 1 : 2);
    int kx = (kz + 1) % 3, ky = (kx + 1) % 3;
    if (d[kz] < 0.0) std::swap(kx, ky);
    const double sx = d[kx] / d[kz], sy = d[ky] / d[kz], sz = 1.0 / d[kz];

    // Step 2: shear the vertices so the ray is the +z axis through the origin.
    const Vec3 pa = a - o, pb = b - o, pc = c - o;
    const double ax = pa[kx] - sx * pa[kz], ay = pa[ky] - sy * pa[kz];
    const double bx = pb[kx] - sx * pb[kz], by = pb[ky] - sy * pb[kz];
    const double cx = pc[kx] - sx * pc[kz], cy = pc[ky] - sy * pc[kz];

    // Step 3: edge functions; computed the same way for both triangles of an edge, so a ray
    // through the edge sees consistent signs (zero counts as inside for both).
    const double u = cx * by - cy * bx, v = ax * cy - ay * cx, w = bx * ay - by * ax;
    if ((u < 0.0 || v < 0.0 || w < 0.0) && (u > 0.0 || v > 0.0 || w > 0.0)) return std::nullopt;
    const double det = u + v + w;
    if (det == 0.0) return std::nullopt;

    // Step 4: the scaled hit distance.
    const double t = (u * sz * pa[kz] + v * sz * pb[kz] + w * sz * pc[kz]) / det;
    return t;
}

namespace {

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

std::optional<double> TriangleBvh::nearestHit(const Vec3& o, const Vec3& d, double tmin,
                                              double tmax) const {
    if (nodes_.empty()) return std::nullopt;
    const SlabRay slab(o, d);
    double best = kInfinity;
    std::optional<double> bestT;
    uint32_t stack[64];
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
        const Node& node = nodes_[stack[--top]];
        double t0 = tmin, t1 = tmax;
        if (!clipToBox(slab, node.box, t0, t1)) continue;
        // The box cannot hold a hit nearer the origin than one already found.
        const double nearest =
            t0 <= 0.0 && t1 >= 0.0 ? 0.0 : std::min(std::fabs(t0), std::fabs(t1));
        if (nearest >= best) continue;
        if (node.count == 0) {
            stack[top++] = node.first;
            stack[top++] = uint32_t(&node - nodes_.data()) + 1;
            continue;
        }
        for (uint32_t i = node.first; i < node.first + node.count; ++i) {
            const auto& tri = mesh_.triangles[order_[i]];
            const auto t = rayTriangle(o, d, mesh_.positions[tri[0]], mesh_.positions[tri[1]],
                                       mesh_.positions[tri[2]]);
            if (t && *t >= tmin && *t <= tmax && std::fabs(*t) < best) {
                best = std::fabs(*t);
                bestT = t;
            }
        }
    }
    return bestT;
}

}  // namespace csg
