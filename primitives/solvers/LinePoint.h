// Points of a line o + t d computed with one rounding per component.
#pragma once

#include <cmath>

#include "csg/Math.h"

namespace csg {

// o + t d with the product kept exact (fma): when o is far away, t d nearly cancels o, and
// rounding the product first would cost an error of ulp(|o|) in a point that is near the
// primitive; with fma the error is ulp of the result.
inline Vec3 pointOnLine(const Vec3& o, const Vec3& d, double t) {
    return {std::fma(t, d.x, o.x), std::fma(t, d.y, o.y), std::fma(t, d.z, o.z)};
}

}  // namespace csg
