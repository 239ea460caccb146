// A trivariate polynomial F(x, y, z) of total degree <= 16 with double coefficients, and its
// restriction to a line as a univariate Polynomial. Dense storage: the C(n + 3, 3) monomials
// of degree n (969 for n = 16), built once per surface, never per ray.
//
// Notation: c(i, j, k) is the coefficient of x^i y^j z^k, i + j + k <= degree. Along the line
// p + s u, each variable is a linear polynomial in s (x = p.x + s u.x, ...), and F becomes
//   F(s) = sum_i X^i sum_j Y^j sum_k Z^k c(i, j, k)
// evaluated by nested Horner's rule whose values are polynomials in s: no power of a
// coordinate is ever expanded into monomials in s, so nothing cancels beyond what F itself
// does at the point (the cancellation-prone route is expanding (p + s u)^i binomially).
#pragma once

#include <array>
#include <cassert>

#include "primitives/base/Math.h"
#include "primitives/solvers/DoubleDouble.h"
#include "primitives/solvers/Polynomial.h"

namespace csg {

class Trivariate {
public:
    // A surface's degree: 16 (969 coefficients), below Polynomial's 20, which only the solvers'
    // measurements use.
    static constexpr int kMaxDegree = 16;
    static constexpr int kMaxTerms = (kMaxDegree + 1) * (kMaxDegree + 2) * (kMaxDegree + 3) / 6;

    Trivariate() = default;
    explicit Trivariate(int degree) : degree_(degree) {
        assert(degree >= 0 && degree <= kMaxDegree);
    }

    int degree() const { return degree_; }
    // Coefficient of x^i y^j z^k (i + j + k <= degree()).
    double& at(int i, int j, int k) { return c_[index(i, j, k)]; }
    double at(int i, int j, int k) const { return c_[index(i, j, k)]; }
    // The number of stored coefficients: C(degree + 3, 3).
    int termCount() const { return offsetX(degree_ + 1); }
    double maxMagnitude() const;

    // F at a point (nested Horner, one rounding per step).
    double operator()(const Vec3& p) const;
    // dF/dx, dF/dy, dF/dz (each of degree degree() - 1).
    Trivariate partial(int axis) const;
    // F(p + s u) as a polynomial in s of degree degree() (nested Horner on polynomials in s).
    Polynomial along(const Vec3& p, const Vec3& u) const;
    // The same in double-double, from a point given as hi + lo per axis: each coefficient within
    // ~2^-100 of the exact one for these inputs (what the root polish needs; formed per ray only
    // when a root is polished).
    PolynomialDD alongDD(const DoubleDouble p[3], const Vec3& u) const;

private:
    // Layout: x-major, then y, then z: block i holds the (y, z) triangle of degree n - i.
    int offsetX(int i) const {
        // sum over i' < i of C(n - i' + 2, 2)
        int o = 0;
        for (int a = 0; a < i; ++a) o += (degree_ - a + 1) * (degree_ - a + 2) / 2;
        return o;
    }
    int index(int i, int j, int k) const {
        assert(i >= 0 && j >= 0 && k >= 0 && i + j + k <= degree_);
        const int m = degree_ - i;  // the (y, z) triangle's degree
        // rows j' < j hold m - j' + 1 entries each
        return offsetX(i) + j * (m + 1) - j * (j - 1) / 2 + k;
    }

    std::array<double, kMaxTerms> c_{};
    int degree_ = 0;
};

}  // namespace csg
