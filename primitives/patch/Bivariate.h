// A polynomial in (u, v) of degree <= kMaxDegreeV in v and <= kMaxDegreeU in u, stored inline
// (no heap), for the algebraic patch methods (Groebner.h, Resultant.h).
// Notation: f(u, v) = sum c[j][i] u^i v^j. Terms are ordered lexicographically with v > u:
// u^a v^b > u^c v^d iff b > d, or b == d and a > c. So the leading term of f is its highest
// power of v with the highest power of u beside it, and an element with no v at all is a
// polynomial in u only: the eliminant the Groebner method solves.
#pragma once

#include <array>
#include <cmath>

#include "primitives/base/Math.h"
#include "primitives/patch/BezierPatch.h"

namespace csg {

// The monomial u^(this->u) v^(this->v): exponents; a leading term names the largest nonzero
// coefficient of a polynomial.
struct Monomial {
    int u = 0, v = 0;
    bool divides(const Monomial& m) const { return u <= m.u && v <= m.v; }
};

class Bivariate {
public:
    // Reductions in lex order v > u never raise the v-degree above the inputs' (a bicubic
    // pair: 3); the u-degree grows through S-polynomials, up to 18 in an eliminant of a
    // bicubic pair (Kajiya's bound) and beyond in intermediate elements.
    static constexpr int kMaxDegreeV = 3;
    static constexpr int kMaxDegreeU = 31;

    double operator()(int i, int j) const { return c_[j][i]; }  // coefficient of u^i v^j
    double& operator()(int i, int j) { return c_[j][i]; }

    bool isZero() const;
    // The largest nonzero term in lex v > u; {-1, -1} for the zero polynomial.
    Monomial leading() const;
    double leadingCoefficient() const {
        const Monomial m = leading();
        return m.u < 0 ? 0.0 : c_[m.v][m.u];
    }
    // The highest power of v (of u) with a nonzero coefficient; -1 for the zero polynomial.
    int degreeV() const { return leading().v; }
    int degreeU() const;
    double maxMagnitude() const;

    // k f.
    void scale(double k);
    // f -= k u^du v^dv g. False, and f unchanged, when the product would exceed the capacity.
    bool subtractMultiple(double k, const Monomial& shift, const Bivariate& g);
    // Sets every coefficient with |c| <= threshold to 0 (the small-value rule, Groebner.cpp).
    void dropBelow(double threshold);

    // f(u, .) as coefficients of v^0 .. v^kMaxDegreeV.
    std::array<double, kMaxDegreeV + 1> atU(double u) const;
    double operator()(double u, double v) const;
    // (df/du, df/dv) at (u, v).
    Vec2 gradient(double u, double v) const;
    // sum |c| |u|^i |v|^j: the size of the terms that cancel in f(u, v), for residual tests.
    double termMagnitude(double u, double v) const;

    // n . (S(u, v) - o) of a bicubic patch in the monomial basis.
    static Bivariate planeDistance(const BezierPatch& patch, const Vec3& n, const Vec3& o);

private:
    std::array<std::array<double, kMaxDegreeU + 1>, kMaxDegreeV + 1> c_{};
};

}  // namespace csg
