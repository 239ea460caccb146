// Real roots by Descartes' rule of signs with Vincent-Collins-Akritas bisection (Collins &
// Akritas 1976; the lecture's Collins method). On a piece [a, b] of the range, q(x) = p(a +
// (b - a) x) is mapped to (0, inf) by x = 1 / (1 + y); the sign variations V of the
// coefficients of (1 + y)^n q(1 / (1 + y)) bound the number of roots in (a, b) and equal it
// mod 2: V = 0 means none, V = 1 exactly one (then refined on p by a safeguarded Newton), and
// V >= 2 halves the piece. In floating point the coefficients' signs can be wrong where they
// are rounding noise, so clusters and multiple roots are split down to double resolution and
// decided there by clusterRoots() (Roots.h).
#pragma once

#include "primitives/solvers/Polynomial.h"

namespace csg {

// The roots of p in [tlo, thi] (finite) with the contract of Roots.h; roots holds
// p.degree() entries. relTol > 0 stops splitting and refining at that width.
int solveDescartes(const Polynomial& p, double tlo, double thi, double* roots, double relTol = 0.0);

}  // namespace csg
