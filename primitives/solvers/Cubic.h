// Real roots of a cubic in closed form, done robustly (Kahan's QBC: one root by a Newton
// iteration that converges monotonically from a guaranteed start, deflation, and the stable
// quadratic), each root polished by Newton on the cubic and judged by its residual.
#pragma once

#include "primitives/solvers/Polynomial.h"

namespace csg {

// All real roots of c3 t^3 + c2 t^2 + c1 t + c0 with the contract of Roots.h (ascending, a
// tangency listed twice), at most 3. Degrades to the quadratic when c3 == 0 or is so small
// that the monic form overflows; returns 0 for a constant.
int solveCubicAll(double c3, double c2, double c1, double c0, double* roots);

// The roots of a polynomial of degree <= 3 in [tlo, thi] (the common interface of Solve.h).
int solveCubic(const Polynomial& p, double tlo, double thi, double* roots);

// Real roots of a t^2 + b t + c of the quadratic factor of polynomial `whole`, appended to
// roots (returns how many): two when the discriminant is >= 0; a tangency (listed twice) at
// the vertex when it is slightly negative but whole is numerically zero there; else none.
int appendQuadraticFactorRoots(const Polynomial& whole, double a, double b, double c,
                               double* roots);

}  // namespace csg
