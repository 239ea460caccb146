// Real roots by Yuksel's method (C. Yuksel, "High-Performance Polynomial Root Finding for
// Graphics", HPG 2022): the roots of p' split [tlo, thi] into pieces on which p is monotone,
// so each piece holds at most one root, bracketed by a sign change and found by a safeguarded
// Newton iteration. The roots of p' come from the same method one degree down (recursion),
// so no isolation step is needed. Added here: at a critical point where p is numerically zero
// the root is a tangency (listed twice) rather than lost for want of a sign change.
#pragma once

#include "primitives/solvers/Polynomial.h"

namespace csg {

// The roots of p in [tlo, thi] (finite) with the contract of Roots.h; roots holds
// p.degree() entries. relTol > 0 stops each bracketed refinement (the roots' and, one degree
// down, the critical points') at that width (Roots.h, bracketSmallEnough).
int solveYuksel(const Polynomial& p, double tlo, double thi, double* roots, double relTol = 0.0);

}  // namespace csg
