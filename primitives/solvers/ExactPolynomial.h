// Building a trivariate polynomial F(x, y, z) exactly, for algebraic surfaces: the API the
// language maps an expression such as "(x^2 + y^2 + z^2 - 1)^3 - x^2 z^3" onto.
//
//   number           ExactPolynomial::constant(v)
//   x, y, z          ExactPolynomial::x(), y(), z()      (or variable(0 | 1 | 2))
//   a + b, a - b, -a operators (never fail)
//   a * b            a.times(b)      std::nullopt when the degree would exceed 16
//   a ^ k            a.power(k)      k >= 0 an integer; std::nullopt beyond degree 16
//   a / v            a.dividedBy(v)  v a nonzero constant (a polynomial divisor is not one)
//   finally          toTrivariate()  the double coefficients a surface is made of
//
// Coefficients are kept in double-double arithmetic (an unevaluated sum hi + lo, ~106 bits,
// error-free products by fma), so expanding products and powers is exact whenever the exact
// coefficients fit in 106 bits (integer data raised to any power allowed here, and any
// product of short decimals), and otherwise off by ~1e-32 relative; toTrivariate() rounds
// each coefficient once. A value type: copies are deep; each holds 17^3 double pairs on the
// heap, which is fine at parse time and never used per ray.
#pragma once

#include <optional>
#include <vector>

#include "primitives/base/Math.h"
#include "primitives/solvers/Trivariate.h"

namespace csg {

class ExactPolynomial {
public:
    static constexpr int kMaxDegree = Trivariate::kMaxDegree;

    ExactPolynomial();  // the zero polynomial
    static ExactPolynomial constant(double value);
    static ExactPolynomial variable(int axis);  // 0: x, 1: y, 2: z
    static ExactPolynomial x() { return variable(0); }
    static ExactPolynomial y() { return variable(1); }
    static ExactPolynomial z() { return variable(2); }
    // c x^i y^j z^k (i + j + k <= kMaxDegree).
    static ExactPolynomial monomial(double c, int i, int j, int k);

    // Total degree of the nonzero terms (0 for a constant, also for the zero polynomial).
    int degree() const;
    bool isZero() const;
    // The coefficient of x^i y^j z^k, rounded to double.
    double coefficient(int i, int j, int k) const;

    friend ExactPolynomial operator+(const ExactPolynomial& a, const ExactPolynomial& b);
    friend ExactPolynomial operator-(const ExactPolynomial& a, const ExactPolynomial& b);
    ExactPolynomial operator-() const;
    std::optional<ExactPolynomial> times(const ExactPolynomial& b) const;
    std::optional<ExactPolynomial> power(int k) const;
    std::optional<ExactPolynomial> dividedBy(double v) const;
    // F(x + c.x, y + c.y, z + c.z): the same surface seen from a frame whose origin is c
    // (Taylor shift along each axis in double-double).
    ExactPolynomial shifted(const Vec3& c) const;

    // The coefficients rounded to double, as a Trivariate of degree degree().
    Trivariate toTrivariate() const;

private:
    struct DD {
        double hi = 0.0, lo = 0.0;
    };
    static constexpr int kSide = kMaxDegree + 1;
    static int index(int i, int j, int k) { return (i * kSide + j) * kSide + k; }
    static DD add(DD a, DD b);
    static DD mul(DD a, DD b);
    std::vector<DD> c_;
};

}  // namespace csg
