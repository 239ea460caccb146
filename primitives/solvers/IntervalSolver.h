// Real roots by interval-arithmetic subdivision (the lecture's interval method): an interval
// whose enclosure of p (Interval.h: centred form, outward rounding) excludes 0 holds no root;
// one whose
// enclosure of p' excludes 0 holds at most one, bracketed by a sign change and refined; any
// other is halved. The exclusion tests are proofs (the enclosures are rigorous for the
// stored coefficients), so a root is never lost; multiple and clustered roots are split down
// to double resolution and then decided by clusterRoots() (Roots.h).
#pragma once

#include "primitives/solvers/Polynomial.h"

namespace csg {

// The roots of p in [tlo, thi] (finite) with the contract of Roots.h; roots holds
// p.degree() entries. relTol > 0 stops splitting and refining at that width.
int solveIntervalSubdivision(const Polynomial& p, double tlo, double thi, double* roots,
                             double relTol = 0.0);

}  // namespace csg
