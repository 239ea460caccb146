// Helpers every root solver shares: the numerical-zero test, Newton polishing, a bracketed
// safeguarded Newton, and the final step that turns candidate roots into the solvers' contract.
//
// The contract (see Solve.h): real roots in [tlo, thi], ascending; a root where p changes sign
// (odd multiplicity, a crossing) is listed once, a root where it does not (even multiplicity,
// a tangency) is listed twice with equal values. Roots whose separation p cannot resolve in
// double precision (|p| between them is within its rounding bound) are one such root.
#pragma once

#include "csg/Math.h"
#include "primitives/solvers/Polynomial.h"

namespace csg {

// True when |p(t)| is within tol::kRootResidualFactor of its rounding-error bound, i.e. the
// computed value has no trustworthy sign.
bool isNumericalZero(const Polynomial& p, double t);

// Newton steps from x while they lower |p|; returns the best point seen. For a simple root
// this converges quadratically to within an ulp or two.
double polishRoot(const Polynomial& p, double x);

// The root of p in [lo, hi], where p(lo) and p(hi) have opposite signs (lo < hi): Newton steps
// that leave the bracket are replaced by bisection, so it always converges, to within an ulp
// of the bracket.
double refineBracketed(const Polynomial& p, double lo, double hi);

// Sorts the n candidates in roots (crossings once, tangencies twice), merges clusters that p
// cannot resolve (a cluster of m candidates becomes one root listed once when m is odd, twice
// when even), keeps those in [tlo, thi], and returns their count.
int finalizeRoots(const Polynomial& p, double* roots, int n, double tlo, double thi);

}  // namespace csg
