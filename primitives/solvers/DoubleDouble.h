// Double-double arithmetic: a value is the unevaluated sum hi + lo of two doubles with
// |lo| <= ulp(hi) / 2, ~106 bits, built from the error-free transformations of ErrorFree.h
// (Dekker, Knuth; the "sloppy" add and the fma product of Hida, Li & Bailey's QD library, whose
// Debian package libqd-dev is not used: its dd_real is a class around the same few lines and
// would add a shared library to every build for them). What the root polishers (Polish.h)
// evaluate polynomials with, so that a residual near a root keeps its sign and size.
//
// Error: add and mul are within ~2^-104 of the exact result relative to the operands' sizes
// (|a| + |b| for add, |a| |b| for mul), which is what Horner's rule needs; nothing here is
// rounded outward. Plain values, no heap, all inline.
#pragma once

#include <cmath>

#include "primitives/solvers/ErrorFree.h"
#include "primitives/solvers/Polynomial.h"

namespace csg {

struct DoubleDouble {
    double hi = 0.0, lo = 0.0;

    DoubleDouble() = default;
    constexpr DoubleDouble(double h) : hi(h) {}  // NOLINT: a double is a double-double
    constexpr DoubleDouble(double h, double l) : hi(h), lo(l) {}

    // The double nearest hi + lo (hi is already, when normalized; the sum rounds ties right).
    double value() const { return hi + lo; }
};

// hi + lo renormalized, assuming |a| >= |b| or a == 0 (Dekker's fastTwoSum).
inline DoubleDouble quickSum(double a, double b) {
    const double s = a + b;
    return {s, b - (s - a)};
}

inline DoubleDouble operator+(const DoubleDouble& a, const DoubleDouble& b) {
    const Sum2 s = twoSum(a.hi, b.hi);
    return quickSum(s.hi, s.lo + (a.lo + b.lo));
}
inline DoubleDouble operator-(const DoubleDouble& a) {
    return {-a.hi, -a.lo};
}
inline DoubleDouble operator-(const DoubleDouble& a, const DoubleDouble& b) {
    return a + (-b);
}
inline DoubleDouble operator*(const DoubleDouble& a, const DoubleDouble& b) {
    const Sum2 p = twoProduct(a.hi, b.hi);
    return quickSum(p.hi, p.lo + (a.hi * b.lo + a.lo * b.hi));
}
// a / b: the double quotient, then one correction from the remainder a - q b in double-double.
inline DoubleDouble operator/(const DoubleDouble& a, const DoubleDouble& b) {
    const double q1 = a.hi / b.hi;
    const DoubleDouble r = a - b * DoubleDouble(q1);
    const double q2 = r.hi / b.hi;
    return quickSum(q1, q2);
}
// sqrt(a) for a >= 0: the double root and one Newton step in double-double (NaN for a < 0).
inline DoubleDouble ddSqrt(const DoubleDouble& a) {
    if (!(a.hi > 0.0)) return a.hi == 0.0 ? DoubleDouble(0.0) : DoubleDouble(std::sqrt(a.hi));
    const double y = std::sqrt(a.hi);
    const Sum2 yy = twoProduct(y, y);
    const DoubleDouble r = a - DoubleDouble(yy.hi, yy.lo);
    return quickSum(y, r.hi / (2.0 * y));
}
inline bool operator<(const DoubleDouble& a, const DoubleDouble& b) {
    return a.hi < b.hi || (a.hi == b.hi && a.lo < b.lo);
}
inline DoubleDouble ddAbs(const DoubleDouble& a) {
    return a.hi < 0.0 || (a.hi == 0.0 && a.lo < 0.0) ? -a : a;
}

// A univariate polynomial with double-double coefficients (ascending, as Polynomial), degree
// <= Polynomial::kMaxDegree: the ray's polynomial formed from the ray and the surface's own
// coefficients without rounding them to double.
struct PolynomialDD {
    DoubleDouble c[Polynomial::kMaxDegree + 1];
    int degree = 0;

    PolynomialDD() = default;
    // The same polynomial (each double is exactly a double-double).
    explicit PolynomialDD(const Polynomial& p) : degree(p.degree()) {
        for (int i = 0; i <= degree; ++i) c[i] = p[i];
    }
    // The coefficients rounded to double.
    Polynomial rounded() const {
        Polynomial p = Polynomial::ofDegree(degree);
        for (int i = 0; i <= degree; ++i) p[i] = c[i].value();
        return p;
    }

    // p, p' and p'' / 2 at x, one Horner pass in double-double.
    struct Values {
        DoubleDouble p, dp, halfDdp;
    };
    Values at(const DoubleDouble& x) const {
        Values v{c[degree], 0.0, 0.0};
        for (int i = degree - 1; i >= 0; --i) {
            v.halfDdp = v.halfDdp * x + v.dp;
            v.dp = v.dp * x + v.p;
            v.p = v.p * x + c[i];
        }
        return v;
    }
    DoubleDouble operator()(const DoubleDouble& x) const {
        DoubleDouble y = c[degree];
        for (int i = degree - 1; i >= 0; --i) y = y * x + c[i];
        return y;
    }
};

}  // namespace csg
