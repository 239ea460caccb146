#include "primitives/base/TrianglePoint.h"

#include <algorithm>

namespace csg {

namespace {

// The point of segment [s, e] nearest p (s itself when the segment is a point).
Vec3 closestPointOnSegment(const Vec3& p, const Vec3& s, const Vec3& e) {
    const Vec3 se = e - s;
    const double len2 = glm::dot(se, se);
    const double u = len2 > 0.0 ? std::clamp(glm::dot(p - s, se) / len2, 0.0, 1.0) : 0.0;
    return s + u * se;
}

// A triangle of zero area (a repeated corner, or three points on a line) is the union of its
// edges. Ericson's regions would divide 0 by 0 there (the edge ab of a == b).
Vec3 closestPointOnEdges(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
    Vec3 best = closestPointOnSegment(p, a, b);
    for (const Vec3& q : {closestPointOnSegment(p, b, c), closestPointOnSegment(p, c, a)})
        if (glm::dot(q - p, q - p) < glm::dot(best - p, best - p)) best = q;
    return best;
}

}  // namespace

Vec3 closestPointOnTriangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
    const Vec3 ab = b - a, ac = c - a;
    const Vec3 n = glm::cross(ab, ac);
    if (glm::dot(n, n) == 0.0) return closestPointOnEdges(p, a, b, c);
    // Ericson, Real-Time Collision Detection 5.1.5: find the Voronoi region of p among the
    // vertices, edges and face by the signs of dot products, then project onto that feature.
    const Vec3 ap = p - a;
    const double d1 = glm::dot(ab, ap), d2 = glm::dot(ac, ap);
    if (d1 <= 0.0 && d2 <= 0.0) return a;
    const Vec3 bp = p - b;
    const double d3 = glm::dot(ab, bp), d4 = glm::dot(ac, bp);
    if (d3 >= 0.0 && d4 <= d3) return b;
    const double vc = d1 * d4 - d3 * d2;
    if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) return a + (d1 / (d1 - d3)) * ab;
    const Vec3 cp = p - c;
    const double d5 = glm::dot(ab, cp), d6 = glm::dot(ac, cp);
    if (d6 >= 0.0 && d5 <= d6) return c;
    const double vb = d5 * d2 - d1 * d6;
    if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) return a + (d2 / (d2 - d6)) * ac;
    const double va = d3 * d6 - d5 * d4;
    if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0)
        return b + ((d4 - d3) / ((d4 - d3) + (d5 - d6))) * (c - b);
    // The face region: va + vb + vc is |n|^2 in exact arithmetic; a sliver can round it to
    // zero or below, and its edges then answer instead of a division by it.
    const double sum = va + vb + vc;
    if (!(sum > 0.0)) return closestPointOnEdges(p, a, b, c);
    return a + (vb / sum) * ab + (vc / sum) * ac;
}

}  // namespace csg
