// Real roots by a Sturm sequence: the thesis' baseline. The sequence counts the distinct real
// roots in an interval; bisection with those counts isolates each root, then a refinement
// converges on it: plain bisection, or the Illinois variant of regula falsi (superlinear,
// safeguarded by bisection when it stalls).
#pragma once

#include "primitives/solvers/Polynomial.h"

namespace csg {

enum class SturmRefine { Bisection, Illinois };

// The roots of p in [tlo, thi] (finite) with the contract of Roots.h; roots holds
// p.degree() entries. Known weakness, kept on purpose as the baseline: the sequence is built in
// floating point, so clustered or high-degree roots can be miscounted.
// relTol > 0 stops the refinement at that bracket width (Roots.h, bracketSmallEnough).
int solveSturm(const Polynomial& p, double tlo, double thi, double* roots, SturmRefine refine,
               double relTol = 0.0);

}  // namespace csg
