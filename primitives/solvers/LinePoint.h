// Points of a line o + t d computed with one rounding per component.
#pragma once

#include "primitives/base/Fma.h"
#include "primitives/base/Math.h"

namespace csg {

// o + t d with the product kept exact (fma): when o is far away, t d nearly cancels o, and
// rounding the product first would cost an error of ulp(|o|) in a point that is near the
// primitive; with fma the error is ulp of the result. Runs once per leaf per ray, hence
// fusedMultiplyAdd (primitives/base/Fma.h), not a libm call.
inline Vec3 pointOnLine(const Vec3& o, const Vec3& d, double t) {
    return {fusedMultiplyAdd(t, d.x, o.x), fusedMultiplyAdd(t, d.y, o.y),
            fusedMultiplyAdd(t, d.z, o.z)};
}

}  // namespace csg
