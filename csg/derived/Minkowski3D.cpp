#include "csg/derived/Minkowski3D.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <iterator>
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

// The area of the convex hull of points lying in the plane with unit normal n (Andrew's
// monotone chain in a basis of the plane, then the shoelace formula).
double hullAreaInPlane(const std::vector<Vec3>& points, const Vec3& n) {
    const Vec3 u =
        glm::normalize(glm::cross(n, std::abs(n.x) < 0.9 ? Vec3(1, 0, 0) : Vec3(0, 1, 0)));
    const Vec3 v = glm::cross(n, u);
    std::vector<Vec2> p;
    for (const Vec3& q : points) p.emplace_back(glm::dot(q, u), glm::dot(q, v));
    std::sort(p.begin(), p.end(),
              [](const Vec2& a, const Vec2& b) { return a.x < b.x || (a.x == b.x && a.y < b.y); });
    auto cross = [](const Vec2& o, const Vec2& a, const Vec2& b) {
        return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x);
    };
    std::vector<Vec2> hull(2 * p.size());
    size_t k = 0;
    for (size_t i = 0; i < p.size(); ++i) {
        while (k >= 2 && cross(hull[k - 2], hull[k - 1], p[i]) <= 0.0) --k;
        hull[k++] = p[i];
    }
    for (size_t i = p.size() - 1, lower = k + 1; i-- > 0;) {
        while (k >= lower && cross(hull[k - 2], hull[k - 1], p[i]) <= 0.0) --k;
        hull[k++] = p[i];
    }
    double area = 0.0;
    for (size_t i = 0; i + 1 < k; ++i)
        area += hull[i].x * hull[i + 1].y - hull[i + 1].x * hull[i].y;
    return 0.5 * std::abs(area);
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

std::vector<NodePtr> sumsOfBoundaries(const TriangleMesh& a, const TriangleMesh& b, Tags tags) {
    std::vector<NodePtr> leaves;
    for (const auto& s : b.triangles) {
        const std::array<Vec3, 3> corners = cornersOf(b, s);
        std::vector<NodePtr> hulls = sumsOfBoundaryWithConvex(a, corners, tags);
        leaves.insert(leaves.end(), std::make_move_iterator(hulls.begin()),
                      std::make_move_iterator(hulls.end()));
    }
    return leaves;
}

std::vector<Vec3> sheetVertices(const TriangleMesh& mesh) {
    // Union-find over the vertices, joined along each triangle.
    std::vector<uint32_t> parent(mesh.positions.size());
    for (uint32_t i = 0; i < parent.size(); ++i) parent[i] = i;
    const auto root = [&](uint32_t i) {
        while (parent[i] != i) i = parent[i] = parent[parent[i]];
        return i;
    };
    for (const auto& t : mesh.triangles) {
        parent[root(t[1])] = root(t[0]);
        parent[root(t[2])] = root(t[0]);
    }
    std::vector<Vec3> vertices;
    std::vector<bool> seen(parent.size(), false);
    for (const auto& t : mesh.triangles) {
        const uint32_t r = root(t[0]);
        if (seen[r]) continue;
        seen[r] = true;
        vertices.push_back(mesh.positions[t[0]]);
    }
    return vertices;
}

std::vector<NodePtr> sumsOfBoundaryWithBall(const TriangleMesh& boundary, const Vec3& center,
                                            double radius, Tags tags) {
    const size_t count = boundary.triangles.size();
    std::vector<Vec3> normals(count, Vec3(0.0));
    std::vector<double> areas(count, 0.0);
    for (size_t i = 0; i < count; ++i) {
        const std::array<Vec3, 3> c = cornersOf(boundary, boundary.triangles[i]);
        const Vec3 n = glm::cross(c[1] - c[0], c[2] - c[0]);
        areas[i] = 0.5 * glm::length(n);
        if (areas[i] > 0.0) normals[i] = n / (2.0 * areas[i]);
    }
    std::map<std::pair<uint32_t, uint32_t>, std::vector<size_t>> edges;
    for (size_t i = 0; i < count; ++i)
        for (int k = 0; k < 3; ++k) {
            const uint32_t a = boundary.triangles[i][size_t(k)];
            const uint32_t b = boundary.triangles[i][size_t((k + 1) % 3)];
            edges[{std::min(a, b), std::max(a, b)}].push_back(i);
        }
    auto flat = [&](const std::vector<size_t>& triangles) {
        return triangles.size() == 2 && glm::dot(normals[triangles[0]], normals[triangles[1]]) >=
                                            1.0 - tol::kMinkowskiFlatEdgeCos;
    };

    // The faces: triangles joined across flat edges (union-find).
    std::vector<size_t> parent(count);
    for (size_t i = 0; i < count; ++i) parent[i] = i;
    std::function<size_t(size_t)> root = [&](size_t i) {
        while (parent[i] != i) i = parent[i] = parent[parent[i]];
        return i;
    };
    for (const auto& [edge, triangles] : edges)
        if (flat(triangles)) parent[root(triangles[0])] = root(triangles[1]);
    std::map<size_t, std::vector<size_t>> faces;
    for (size_t i = 0; i < count; ++i)
        if (areas[i] > 0.0) faces[root(i)].push_back(i);  // no area: its edges' cylinders cover it

    std::vector<NodePtr> leaves;
    // Each face's prism, its corners moved by ±r along its normal: one convex polytope for a
    // convex face, so that no seam runs across it (a line through a seam between two prisms
    // could take its normal from their shared side), else one per triangle.
    for (const auto& [face, triangles] : faces) {
        const Vec3 up = normals[triangles.front()] * radius;
        std::vector<Vec3> corners;
        double area = 0.0;
        for (const size_t t : triangles) {
            for (const uint32_t v : boundary.triangles[t]) corners.push_back(boundary.positions[v]);
            area += areas[t];
        }
        std::vector<Vec3> prism;
        for (const Vec3& c : corners) {
            prism.push_back(c + center - up);
            prism.push_back(c + center + up);
        }
        std::string why;
        // A convex face covers the hull of its corners: the same area; a concave one less.
        if (triangles.size() > 1 && hullAreaInPlane(corners, normals[triangles.front()]) <=
                                        area * (1.0 + tol::kMinkowskiConvexRel)) {
            if (std::optional<ConvexPolytope> whole = convexHull3D(prism, why)) {
                leaves.push_back(leaf(std::move(*whole), tags));
                continue;
            }
        }
        for (size_t k = 0; k < prism.size(); k += 6) {
            std::vector<Vec3> one(prism.begin() + long(k), prism.begin() + long(k + 6));
            if (std::optional<ConvexPolytope> p = convexHull3D(one, why))
                leaves.push_back(leaf(std::move(*p), tags));
        }
    }
    // A cylinder along every edge where the surface bends (its triangles' normals differ).
    for (const auto& [edge, triangles] : edges) {
        if (flat(triangles)) continue;
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
