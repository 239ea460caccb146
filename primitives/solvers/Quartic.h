// Real roots of a quartic in closed form, done robustly: Ferrari's factorization into two
// real quadratics from the largest root of the resolvent cubic, with the factor coefficients
// chosen among equivalent formulas by their residual and refined by Newton on the
// factorization (the idea of Orellana & De Michele, ACM TOMS Algorithm 1010), then every
// root polished by Newton on the quartic and judged by its residual.
#pragma once

#include "primitives/solvers/Polynomial.h"

namespace csg {

// All real roots of p (degree <= 4 after trimming) with the contract of Roots.h, at most 4.
// *verified (when given) is set false when a check says the closed form may be wrong here: a
// polished root whose residual is above its rounding bound, or a quadratic factor with
// complex roots at whose vertex p has the sign opposite to its leading coefficient (so real
// roots were lost). The dispatcher then falls back to an iterative solver.
int solveQuarticAll(const Polynomial& p, double* roots, bool* verified = nullptr);

// The roots of p (degree <= 4) in [tlo, thi] (the common interface of Solve.h).
int solveQuartic(const Polynomial& p, double tlo, double thi, double* roots,
                 bool* verified = nullptr);

}  // namespace csg
