// Axis-aligned boxes: the bounds of primitives and subtrees, and the ray-box slab test.
#pragma once

#include <algorithm>

#include "primitives/base/Math.h"
#include "primitives/base/Tolerances.h"

namespace csg {

// A closed box [lo, hi]. Empty when lo > hi on some axis (the default is empty).
// Components may be infinite (a half-space is unbounded).
struct Bounds3 {
    Vec3 lo{kInfinity};
    Vec3 hi{-kInfinity};

    static Bounds3 everything() { return {Vec3(-kInfinity), Vec3(kInfinity)}; }

    bool empty() const { return lo.x > hi.x || lo.y > hi.y || lo.z > hi.z; }
    bool finite() const {
        return std::isfinite(lo.x) && std::isfinite(lo.y) && std::isfinite(lo.z) &&
               std::isfinite(hi.x) && std::isfinite(hi.y) && std::isfinite(hi.z);
    }
    Vec3 center() const { return 0.5 * (lo + hi); }
    Vec3 extent() const { return hi - lo; }
    // Half the surface area (the SAH cost weight); 0 for an empty box.
    double halfArea() const {
        if (empty()) return 0.0;
        const Vec3 e = extent();
        return e.x * e.y + e.y * e.z + e.z * e.x;
    }
    void extend(const Vec3& p) {
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
    }
    void extend(const Bounds3& b) {
        lo = glm::min(lo, b.lo);
        hi = glm::max(hi, b.hi);
    }
    bool contains(const Vec3& p) const {
        return p.x >= lo.x && p.x <= hi.x && p.y >= lo.y && p.y <= hi.y && p.z >= lo.z &&
               p.z <= hi.z;
    }
    // Whether b lies inside this box (an empty b lies inside every box).
    bool contains(const Bounds3& b) const {
        return b.empty() || (contains(b.lo) && contains(b.hi));
    }
};

inline Bounds3 hull(const Bounds3& a, const Bounds3& b) {
    return {glm::min(a.lo, b.lo), glm::max(a.hi, b.hi)};
}
inline Bounds3 overlap(const Bounds3& a, const Bounds3& b) {
    return {glm::max(a.lo, b.lo), glm::min(a.hi, b.hi)};
}

// Bounds of the image of box b under the affine map m. An unbounded box maps to everything
// (its corners are infinite and 0 * inf would give NaN).
Bounds3 transformBounds(const Mat4& m, const Bounds3& b);

// Precomputed reciprocal direction for repeated slab tests against one ray.
struct SlabRay {
    Vec3 o;
    Vec3 invD;
    explicit SlabRay(const Vec3& origin, const Vec3& d) : o(origin), invD(1.0 / d) {}
    struct Reciprocal {};  // tag: the vector given is already 1 / d, per component
    SlabRay(const Vec3& origin, const Vec3& inverseD, Reciprocal) : o(origin), invD(inverseD) {}
};

// Clips [t0, t1] to the part of the ray inside box b; returns false when nothing is left.
// NaN from 0 * inf (a ray in a slab's plane, d = 0 on that axis) must count as "inside that
// slab": every update keeps the running bound on the right of the comparison, so a NaN
// candidate never replaces it. The result is widened by tol::kSlabWiden once at the end (the
// widening is monotone, so this equals widening each axis) so that rounding never culls a box
// the exact test would hit.
inline bool clipToBox(const SlabRay& r, const Bounds3& b, double& t0, double& t1) {
    for (int a = 0; a < 3; ++a) {
        double tNear = (b.lo[a] - r.o[a]) * r.invD[a];
        double tFar = (b.hi[a] - r.o[a]) * r.invD[a];
        if (tNear > tFar) std::swap(tNear, tFar);
        t0 = tNear > t0 ? tNear : t0;
        t1 = tFar < t1 ? tFar : t1;
    }
    // Scale rather than add, so an infinite end stays infinite instead of inf - inf: t0 by
    // 1 - w when positive and 1 + w when negative (t1 the other way round), which is the
    // smaller (larger) of the two products; that takes no sign extraction, same values.
    constexpr double kDown = 1.0 - tol::kSlabWiden, kUp = 1.0 + tol::kSlabWiden;
    t0 = std::min(t0 * kDown, t0 * kUp);
    t1 = std::max(t1 * kDown, t1 * kUp);
    return t0 <= t1;
}

}  // namespace csg
