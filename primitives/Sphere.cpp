#include "primitives/Sphere.h"

#include "primitives/solvers/Quadratic.h"

namespace csg {

Bounds3 Sphere::boundsUnder(const Mat4& m) const {
    const Vec3 c(m[3]);
    Vec3 e;
    for (int i = 0; i < 3; ++i) e[i] = radius * std::hypot(m[0][i], m[1][i], m[2][i]);
    return {c - e, c + e};
}

void Sphere::spans(const Vec3& o, const Vec3& d, LocalSpans& out) const {
    // Move the origin to the foot of the perpendicular from the centre, so c = |f|^2 - r^2
    // is computed from a point near the sphere (no cancellation for far-away rays).
    const double dd = glm::dot(d, d);
    if (dd == 0.0) return;
    const double tFoot = -glm::dot(o, d) / dd;
    const Vec3 f = o + tFoot * d;
    double s0, s1;
    if (solveQuadratic(dd, 0.0, glm::dot(f, f) - radius * radius, s0, s1) < 2) return;
    out.add(tFoot + s0, 0, tFoot + s1, 0);
}

Vec3 Sphere::normal(const Vec3& p, uint16_t) const {
    const double len = glm::length(p);
    return len > 0.0 ? p / len : Vec3(0, 0, 1);  // the centre is never on the surface of r > 0
}

}  // namespace csg
