// A closed interval of doubles with outward rounding, and rigorous enclosures of a polynomial
// and its derivative over an interval. Rounding outward is done after the fact: the
// round-to-nearest result moved one ulp outward (std::nextafter) contains the exact one, as
// round-to-nearest is off by at most half an ulp. No rounding-mode switches, so it is safe in
// any thread and under any compiler flags short of -ffast-math.
#pragma once

#include <algorithm>
#include <cmath>

#include "primitives/base/Math.h"
#include "primitives/base/Tolerances.h"
#include "primitives/solvers/Polynomial.h"

namespace csg {

struct Interval {
    double lo = 0.0, hi = 0.0;

    bool containsZero() const { return lo <= 0.0 && hi >= 0.0; }
    double magnitude() const { return std::max(-lo, hi); }
};

// The next double toward -inf / +inf: the outward step after a rounded operation.
inline double down(double x) {
    return std::nextafter(x, -kInfinity);
}
inline double up(double x) {
    return std::nextafter(x, kInfinity);
}

// Enclosures of p and p' over [m - r, m + r] (r >= 0) in centred (Taylor) form:
//   p(m + h) = sum_k q[k] h^k with q = p shifted to m, |h| <= r,
// so p lies in q[0] +- sum_{k>=1} |q[k]| r^k and p' in q[1] +- sum_{k>=2} k |q[k]| r^(k-1).
// Unlike Horner's rule in interval arithmetic (whose width stays ~ r sum |k c_k t^(k-1)| and
// never resolves a cluster), the width here is ~ |p'(m)| r: it shrinks with the polynomial
// near its roots. Rigour: q is computed in floating point, off by at most gamma(2n) times the
// same shift applied to |p| at |m| (all terms positive, no cancellation); those bounds are
// added to every |q[k]|, and each positive sum is rounded up by a proven factor and one ulp.
struct TaylorEnclosure {
    Interval value, slope;
};

inline TaylorEnclosure enclose(const Polynomial& p, double m, double r) {
    const int n = p.degree();
    // Step 1: Taylor coefficients at m and their error bounds.
    const Polynomial q = p.shifted(m);
    Polynomial a = Polynomial::ofDegree(n);
    for (int i = 0; i <= n; ++i) a[i] = std::abs(p[i]);
    a = a.shifted(std::abs(m));
    const double g = tol::gamma(2 * n + 2);
    // Step 2: the positive sums by Horner in r, then rounded up.
    double s = 0.0, sd = 0.0;
    for (int k = n; k >= 1; --k) {
        const double ck = std::abs(q[k]) + g * a[k];
        s = std::fma(s, r, ck);
        if (k >= 2) sd = std::fma(sd, r, k * ck);
    }
    const double grow = 1.0 + tol::gamma(2 * n + 4);
    s = up(up(s * r) * grow + g * a[0]);
    sd = up(up(sd * r) * grow + g * a[1]);
    // Step 3: the centre values widened outward.
    return {{down(q[0] - s), up(q[0] + s)},
            {down(n >= 1 ? q[1] - sd : -sd), up(n >= 1 ? q[1] + sd : sd)}};
}

}  // namespace csg
