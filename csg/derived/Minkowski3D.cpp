#include "csg/derived/Minkowski3D.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>

#include "csg/derived/Hull3D.h"
#include "primitives/base/Tolerances.h"

namespace csg {
namespace {

// A frame whose z axis runs from a to b, with a at its origin (for a cylinder along an edge).
Mat4 frameAlong(const Vec3& a, const Vec3& b) {
    const Vec3 z = glm::normalize(b - a);
    // The axis least aligned with z gives the best-conditioned cross product.
    const Vec3 helper = std::abs(z.x) < std::abs(z.y)
                            ? (std::abs(z.x) < std::abs(z.z) ? Vec3(1, 0, 0) : Vec3(0, 0, 1))
                            : (std::abs(z.y) < std::abs(z.z) ? Vec3(0, 1, 0) : Vec3(0, 0, 1));
    const Vec3 x = glm::normalize(glm::cross(helper, z));
    const Vec3 y = glm::cross(z, x);
    Mat4 m(1.0);
    m[0] = glm::dvec4(x, 0.0);
    m[1] = glm::dvec4(y, 0.0);
    m[2] = glm::dvec4(z, 0.0);
    m[3] = glm::dvec4(a, 1.0);
    return m;
}

// The triangle's corners.
std::array<Vec3, 3> cornersOf(const TriangleMesh& mesh, const std::array<uint32_t, 3>& t) {
    return {mesh.positions[t[0]], mesh.positions[t[1]], mesh.positions[t[2]]};
}

}  // namespace

std::optional<ConvexPolytope> hullOfSums(std::span<const Vec3> a, std::span<const Vec3> b,
                                         std::string& why) {
    std::vector<Vec3> sums;
    sums.reserve(a.size() * b.size());
    for (const Vec3& p : a)
        for (const Vec3& q : b) sums.push_back(p + q);
    return convexHull3D(sums, why);
}

std::vector<NodePtr> sumsOfBoundaryWithConvex(const TriangleMesh& boundary,
                                              std::span<const Vec3> convex, Tags tags) {
    std::vector<NodePtr> leaves;
    leaves.reserve(boundary.triangles.size());
    for (const auto& t : boundary.triangles) {
        const std::array<Vec3, 3> corners = cornersOf(boundary, t);
        std::string why;
        if (std::optional<ConvexPolytope> hull = hullOfSums(corners, convex, why))
            leaves.push_back(leaf(std::move(*hull), tags));
    }
    return leaves;
}

std::vector<NodePtr> sumsOfBoundaryWithBall(const TriangleMesh& boundary, const Vec3& center,
                                            double radius, Tags tags) {
    std::vector<NodePtr> leaves;
    // Each triangle's prism: its corners moved by ±r along its normal.
    std::vector<Vec3> normals(boundary.triangles.size(), Vec3(0.0));
    static const uint32_t kPrismFaces[] = {0, 1, 2, 3, 4, 5, 0, 1, 4, 3, 1, 2, 5, 4, 2, 0, 3, 5};
    static const uint32_t kPrismStarts[] = {0, 3, 6, 10, 14, 18};
    for (size_t i = 0; i < boundary.triangles.size(); ++i) {
        const std::array<Vec3, 3> c = cornersOf(boundary, boundary.triangles[i]);
        const Vec3 n = glm::cross(c[1] - c[0], c[2] - c[0]);
        const double length = glm::length(n);
        if (!(length > 0.0)) continue;  // no area: its edges' cylinders cover it
        normals[i] = n / length;
        const Vec3 up = normals[i] * radius;
        std::vector<Vec3> prism = {c[0] + center - up, c[1] + center - up, c[2] + center - up,
                                   c[0] + center + up, c[1] + center + up, c[2] + center + up};
        ConvexPolytope p = ConvexPolytope::fromFaces(std::move(prism), kPrismFaces, kPrismStarts);
        if (!p.invalidReason()) leaves.push_back(leaf(std::move(p), tags));
    }
    // A cylinder along every edge where the surface bends (its triangles' normals differ).
    std::map<std::pair<uint32_t, uint32_t>, std::vector<size_t>> edges;
    for (size_t i = 0; i < boundary.triangles.size(); ++i)
        for (int k = 0; k < 3; ++k) {
            const uint32_t a = boundary.triangles[i][size_t(k)];
            const uint32_t b = boundary.triangles[i][size_t((k + 1) % 3)];
            edges[{std::min(a, b), std::max(a, b)}].push_back(i);
        }
    for (const auto& [edge, triangles] : edges) {
        const bool flat =
            triangles.size() == 2 && glm::dot(normals[triangles[0]], normals[triangles[1]]) >=
                                         1.0 - tol::kMinkowskiFlatEdgeCos;
        if (flat) continue;
        const Vec3 a = boundary.positions[edge.first], b = boundary.positions[edge.second];
        const double length = glm::length(b - a);
        if (!(length > 0.0)) continue;
        NodePtr cylinder = leaf(Cylinder{length, radius, radius}, tags);
        leaves.push_back(transformed(frameAlong(a + center, b + center), std::move(cylinder)));
    }
    // A ball at every corner.
    for (const Vec3& p : boundary.positions)
        leaves.push_back(
            transformed(glm::translate(Mat4(1.0), p + center), leaf(Sphere{radius}, tags)));
    return leaves;
}

}  // namespace csg
