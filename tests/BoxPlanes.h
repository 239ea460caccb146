// Test helper: how far a point is from the nearest of an axis-aligned box's six face planes, for
// tests that check every vertex of a box's mesh lies on a face (0 for a point on one).
#pragma once

#include <algorithm>
#include <cmath>

#include "primitives/base/Math.h"

namespace csg {

inline double offBoxSurface(const Vec3& p, const Vec3& lo, const Vec3& hi) {
    double best = INFINITY;
    for (int a = 0; a < 3; ++a)
        best = std::min({best, std::abs(p[a] - lo[a]), std::abs(p[a] - hi[a])});
    return best;
}

}  // namespace csg
