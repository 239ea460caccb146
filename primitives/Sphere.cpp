// Notation: t is the parameter of the line o + t d; s = t - tFoot is measured from the foot of
// the perpendicular from the centre, where the line is nearest the sphere.
#include "primitives/Sphere.h"

#include <cmath>

#include "primitives/solvers/LinePoint.h"
#include "primitives/solvers/Quadratic.h"

namespace csg {

Bounds3 Sphere::boundsUnder(const Mat4& m) const {
    const Vec3 c(m[3]);
    Vec3 e;
    for (int i = 0; i < 3; ++i) e[i] = radius * std::hypot(m[0][i], m[1][i], m[2][i]);
    return {c - e, c + e};
}

void Sphere::spans(const Vec3& o, const Vec3& d, LocalSpans& out) const {
    const double dd = glm::dot(d, d);
    if (dd == 0.0) return;
    // Step 1: move to the foot of the perpendicular from the centre, so |f|^2 - r^2 is
    // computed from a point near the sphere (no cancellation for far-away rays).
    const double tFoot = -glm::dot(o, d) / dd;
    const Vec3 f = pointOnLine(o, d, tFoot);
    // Step 2: solve |f + s d|^2 = r^2. The linear term f.d is 0 in exact arithmetic but not
    // after rounding tFoot; keeping it makes the ends independent of that rounding (for a ray
    // from 1e6 away it is the difference between 4e-10 and 1e-16 of the radius).
    double s0, s1;
    const double b = 2.0 * glm::dot(f, d), c = glm::dot(f, f) - radius * radius;
    if (solveQuadratic(dd, b, c, s0, s1) < 2) return;
    out.add(tFoot + s0, 0, tFoot + s1, 0);
}

Vec3 Sphere::normal(const Vec3& p, uint16_t) const {
    const double len = glm::length(p);
    return len > 0.0 ? p / len : Vec3(0, 0, 1);  // the centre is never on the surface of r > 0
}

}  // namespace csg
