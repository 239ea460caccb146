// A bicubic Bezier patch and the contract its ray-intersection methods share.
// Notation: S(u, v) = sum_{i,j=0}^{3} B_i(u) B_j(v) P[4 i + j], (u, v) in [0, 1]^2, with B_k
// the cubic Bernstein polynomials; row i runs along v, so P[0..3] is the v-curve at u = 0.
// The ray is o + t d (d not unit length); a crossing is a t with S(u, v) = o + t d.
#pragma once

#include <array>
#include <cstdint>

#include "primitives/base/Bounds.h"
#include "primitives/base/Math.h"

namespace csg {

// How a ray meets a patch (the `method=` argument of bezier_patch in the language).
enum class PatchMethod : uint8_t {
    Groebner,       // the thesis' method, right on every ray: the float basis, certified by
                    // interval arithmetic, else the exact one (GroebnerCertified.h)
    Resultant,      // Kajiya: Sylvester resultant in u (degree <= 18), gcd for v
    Clip,           // Bezier clipping (Nishita et al.) + Newton polish: the practical default
    Newton,         // subdivision to a flatness bound, then 2-D Newton
    GroebnerExact,  // the basis over Q (GMP) on every ray: the reference (GroebnerExact.h)
    GroebnerFloat,  // the basis in doubles with the article's small-value rule, as the article
                    // has it (Groebner.h): breaks down on general bicubic patches
};

// One point where a ray meets a patch.
struct PatchCrossing {
    double t, u, v;
};

// A line meets a bicubic patch at most 18 times (Kajiya's bound on the resultant's degree).
inline constexpr int kMaxPatchCrossings = 18;
using PatchCrossings = std::array<PatchCrossing, kMaxPatchCrossings>;

struct BezierPatch {
    std::array<Vec3, 16> points;  // P[4 i + j]: i along u, j along v

    const Vec3& at(int i, int j) const { return points[4 * i + j]; }

    // Bounds of the convex hull of the control points, which contains the patch.
    Bounds3 hullBounds() const {
        Bounds3 b;  // empty
        for (const Vec3& p : points) b.extend(p);
        return b;
    }

    // The four cubic Bernstein polynomials at x, and their derivatives.
    static std::array<double, 4> bernstein(double x) {
        const double y = 1.0 - x;
        return {y * y * y, 3.0 * x * y * y, 3.0 * x * x * y, x * x * x};
    }
    static std::array<double, 4> bernsteinDerivative(double x) {
        const double y = 1.0 - x;
        return {-3.0 * y * y, 3.0 * y * (y - 2.0 * x), 3.0 * x * (2.0 * y - x), 3.0 * x * x};
    }

    Vec3 eval(double u, double v) const { return combine(bernstein(u), bernstein(v)); }
    Vec3 du(double u, double v) const { return combine(bernsteinDerivative(u), bernstein(v)); }
    Vec3 dv(double u, double v) const { return combine(bernstein(u), bernsteinDerivative(v)); }

private:
    Vec3 combine(const std::array<double, 4>& bu, const std::array<double, 4>& bv) const {
        Vec3 s(0.0);
        for (int i = 0; i < 4; ++i) {
            Vec3 row(0.0);
            for (int j = 0; j < 4; ++j) row += bv[j] * at(i, j);
            s += bu[i] * row;
        }
        return s;
    }
};

// Every method has this shape:
//   int intersectByX(const BezierPatch& patch, const Vec3& o, const Vec3& d,
//                    PatchCrossings& out);
// It returns the number of crossings written to out: all t on the whole line with (u, v) in
// [0, 1]^2 (closed, up to the method's parameter tolerance), ascending in t, each surface point
// once (a crossing on a shared edge of two patches is deduplicated by the caller, not here).
// o is already close to the patch (the caller moves it to the entry of hullBounds()).

}  // namespace csg
