// A ray o + t d over the closed parameter range [tmin, tmax].
#pragma once

#include "primitives/base/Math.h"

namespace csg {

// d need not be unit length and is *not* renormalized when the ray is mapped into a
// leaf's local frame, so a value of t names the same point in every frame.
struct Ray {
    Vec3 o{0.0};
    Vec3 d{0.0, 0.0, 1.0};
    double tmin = 0.0;
    double tmax = kInfinity;

    Vec3 at(double t) const { return o + t * d; }
};

}  // namespace csg
