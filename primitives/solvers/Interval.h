// A closed interval of doubles with outward rounding, its arithmetic, enclosures of cos and
// sin, and rigorous enclosures of a polynomial and its derivative over an interval. Rounding outward is done after the fact: the
// round-to-nearest result moved one ulp outward (std::nextafter) contains the exact one, as
// round-to-nearest is off by at most half an ulp. No rounding-mode switches, so it is safe in
// any thread and under any compiler flags short of -ffast-math.
#pragma once

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>

#include "primitives/base/Math.h"
#include "primitives/base/Tolerances.h"
#include "primitives/solvers/Polynomial.h"

namespace csg {

struct Interval {
    double lo = 0.0, hi = 0.0;

    bool containsZero() const { return lo <= 0.0 && hi >= 0.0; }
    double magnitude() const { return std::max(-lo, hi); }
};

// The next double toward -inf / +inf: the outward step after a rounded operation. The same
// values as std::nextafter(x, -inf / +inf), stepped on the bits inline: libm's nextafter is a
// call that cost more than the arithmetic it widens (twice per interval operation).
inline double up(double x) {
    if (!(x < kInfinity)) return x;  // +inf and NaN stay
    if (x == 0.0) return std::numeric_limits<double>::denorm_min();
    const uint64_t bits = std::bit_cast<uint64_t>(x);
    return std::bit_cast<double>(x > 0.0 ? bits + 1 : bits - 1);
}
inline double down(double x) {
    return -up(-x);
}

// Interval arithmetic, rounded outward: each bound is the round-to-nearest result moved one
// ulp outward, so the result encloses every exact result of the operands' points. The
// operands must be finite (an infinite bound makes inf - inf or 0 * inf, a NaN bound): a NaN
// bound makes every test below false, which callers treat as "undecided", never as a proof.
inline Interval pointInterval(double x) {
    return {x, x};
}
inline Interval operator+(Interval a, Interval b) {
    return {down(a.lo + b.lo), up(a.hi + b.hi)};
}
inline Interval operator-(Interval a, Interval b) {
    return {down(a.lo - b.hi), up(a.hi - b.lo)};
}
inline Interval operator-(Interval a) {
    return {-a.hi, -a.lo};
}
inline Interval operator+(Interval a, double b) {
    return {down(a.lo + b), up(a.hi + b)};
}
inline Interval operator+(double a, Interval b) {
    return b + a;
}
inline Interval operator-(Interval a, double b) {
    return {down(a.lo - b), up(a.hi - b)};
}
inline Interval operator-(double a, Interval b) {
    return {down(a - b.hi), up(a - b.lo)};
}
inline Interval operator*(double a, Interval b) {
    return a >= 0.0 ? Interval{down(a * b.lo), up(a * b.hi)}
                    : Interval{down(a * b.hi), up(a * b.lo)};
}
inline Interval operator*(Interval a, double b) {
    return b * a;
}
inline Interval operator*(Interval a, Interval b) {
    const double p0 = a.lo * b.lo, p1 = a.lo * b.hi, p2 = a.hi * b.lo, p3 = a.hi * b.hi;
    return {down(std::min(std::min(p0, p1), std::min(p2, p3))),
            up(std::max(std::max(p0, p1), std::max(p2, p3)))};
}
// a / b for a double b != 0.
inline Interval operator/(Interval a, double b) {
    return b > 0.0 ? Interval{down(a.lo / b), up(a.hi / b)}
                   : Interval{down(a.hi / b), up(a.lo / b)};
}
// The square, tighter than a * a when a straddles 0 (the dependency of the two factors).
inline Interval sqr(Interval a) {
    if (a.lo >= 0.0) return {down(a.lo * a.lo), up(a.hi * a.hi)};
    if (a.hi <= 0.0) return {down(a.hi * a.hi), up(a.lo * a.lo)};
    const double m = std::max(-a.lo, a.hi);
    return {0.0, up(m * m)};
}
// The symmetric interval [-r, r] (r >= 0).
inline Interval plusMinus(double r) {
    return {-r, r};
}
// Whether a and b may share a point: false only when they are provably disjoint (a NaN bound
// proves nothing).
inline bool overlaps(Interval a, Interval b) {
    return !(a.hi < b.lo || b.hi < a.lo);
}
// The sign of every point of a: +1 or -1, or 0 when a holds 0 or a bound is NaN.
inline int provenSign(Interval a) {
    return a.lo > 0.0 ? 1 : a.hi < 0.0 ? -1 : 0;
}
// Enclosures of cos and sin over a, from libm's value at a's midpoint: both are 1-Lipschitz,
// so they stay within a's half-width of it, and glibc's cos and sin are within
// tol::kLibmTrigError of the exact value at any double (its documented 1-ulp bound).
inline Interval enclosedCos(Interval a) {
    const double m = a.lo + 0.5 * (a.hi - a.lo);
    const double e = up(up(std::max(a.hi - m, m - a.lo)) + tol::kLibmTrigError);
    const double c = std::cos(m);
    return {std::max(-1.0, down(c - e)), std::min(1.0, up(c + e))};
}
inline Interval enclosedSin(Interval a) {
    const double m = a.lo + 0.5 * (a.hi - a.lo);
    const double e = up(up(std::max(a.hi - m, m - a.lo)) + tol::kLibmTrigError);
    const double s = std::sin(m);
    return {std::max(-1.0, down(s - e)), std::min(1.0, up(s + e))};
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
