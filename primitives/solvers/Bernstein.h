// Real roots by Bernstein-basis subdivision. On [tlo, thi], p = sum_k b[k] B_k^n(x) with the
// Bernstein polynomials B_k^n(x) = C(n, k) x^k (1 - x)^(n - k), x = (t - tlo) / (thi - tlo).
// The curve (k / n, b[k]) has its control polygon around the graph of p (convex hull
// property), and the sign changes of b bound the roots in (tlo, thi), equal mod 2 (variation
// diminishing; the same count as Descartes' rule after the Moebius map, see Descartes.h). So
// no sign change: no root; one: exactly one, refined on p; more: split at the middle by de
// Casteljau's algorithm, whose steps are averages (no cancellation, no growth), which is why
// this basis is better conditioned on an interval than the monomial one.
#pragma once

#include "primitives/solvers/Polynomial.h"

namespace csg {

// The roots of p in [tlo, thi] (finite) with the contract of Roots.h; roots holds
// p.degree() entries. relTol > 0 stops splitting and refining at that width.
int solveBernstein(const Polynomial& p, double tlo, double thi, double* roots, double relTol = 0.0);

// Bernstein coefficients of p on [tlo, thi], b[0..n]; b[0] = p(tlo) and b[n] = p(thi) up to
// rounding. noise (when given) receives a bound on each coefficient's rounding error.
void toBernstein(const Polynomial& p, double tlo, double thi, double* b, double* noise = nullptr);

}  // namespace csg
