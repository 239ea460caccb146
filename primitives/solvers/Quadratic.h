// Real roots of a t^2 + b t + c = 0 without cancellation.
#pragma once

#include <cmath>
#include <utility>

#include "primitives/base/Fma.h"

namespace csg {

// Returns the number of real roots (0, 1 or 2) written to r0 <= r1. A double root is returned
// twice (count 2, r0 == r1) so a tangent ray yields a zero-length span. a == 0 degrades to the
// linear case (count 1, or 0 when b == 0 too). The larger-magnitude root comes from the
// formula whose sign avoids cancellation, the other from Vieta (r0 r1 = c / a).
inline int solveQuadratic(double a, double b, double c, double& r0, double& r1) {
    if (a == 0.0) {
        if (b == 0.0) return 0;
        r0 = r1 = -c / b;
        return 1;
    }
    // The fmas keep b^2 - 4ac accurate when the two products nearly cancel (fusedMultiplyAdd:
    // this runs per ray, see primitives/base/Fma.h).
    const double fourAC = 4.0 * a * c;
    const double disc = fusedMultiplyAdd(b, b, -fourAC) + fusedMultiplyAdd(-4.0 * a, c, fourAC);
    if (disc < 0.0) return 0;
    const double q = -0.5 * (b + std::copysign(std::sqrt(disc), b));
    if (q == 0.0) {  // b == 0 and c == 0: double root at 0
        r0 = r1 = 0.0;
        return 2;
    }
    r0 = q / a;
    r1 = c / q;
    if (r0 > r1) std::swap(r0, r1);
    return 2;
}

}  // namespace csg
