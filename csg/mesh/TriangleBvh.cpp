#include "csg/mesh/TriangleBvh.h"

#include <algorithm>
#include <cmath>

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

TriangleBvh::TriangleBvh(const TriangleMesh& mesh) : mesh_(mesh) {
    const size_t n = mesh.triangles.size();
    order_.resize(n);
    triBox_.resize(n);
    center_.resize(n);
    for (size_t i = 0; i < n; ++i) {
        order_[i] = uint32_t(i);
        Bounds3 box;
        for (const uint32_t v : mesh.triangles[i]) box.extend(mesh.positions[v]);
        triBox_[i] = box;
        center_[i] = box.center();
    }
    nodes_.reserve(2 * n / 4 + 1);
    if (n > 0) build(0, uint32_t(n), 0);
    center_ = {};
}

uint32_t TriangleBvh::build(uint32_t begin, uint32_t end, int depth) {
    const uint32_t index = uint32_t(nodes_.size());
    nodes_.push_back({});
    Bounds3 box, centers;
    for (uint32_t i = begin; i < end; ++i) {
        box.extend(triBox_[order_[i]]);
        centers.extend(center_[order_[i]]);
    }
    nodes_[index].box = box;
    // Leaves of up to 4 triangles; depth capped well below the traversal stack size.
    if (end - begin <= 4 || depth >= 48) {
        nodes_[index].first = begin;
        nodes_[index].count = end - begin;
        return index;
    }
    // Median split on the widest axis of the centres: balanced, so depth ~ log2(n / 4).
    const Vec3 e = centers.extent();
    const int axis = e.x >= e.y ? (e.x >= e.z ? 0 : 2) : (e.y >= e.z ? 1 : 2);
    const uint32_t mid = begin + (end - begin) / 2;
    std::nth_element(order_.begin() + begin, order_.begin() + mid, order_.begin() + end,
                     [&](uint32_t p, uint32_t q) { return center_[p][axis] < center_[q][axis]; });
    build(begin, mid, depth + 1);
    const uint32_t right = build(mid, end, depth + 1);
    nodes_[index].first = right;
    nodes_[index].count = 0;
    return index;
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
