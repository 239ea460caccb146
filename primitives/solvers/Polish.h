// Root polishing after isolation: the lecture's iterative refiners (Newton, Laguerre,
// Bairstow), run on a polynomial whose coefficients and values are double-double
// (DoubleDouble.h), so that a simple root can come back as the double nearest to the exact one.
//
// "Exact root" here is the root of the polynomial of the double inputs: for solve() the double
// coefficients as given; for a surface or a torus, the polynomial of the line o + t d (o, d
// the local ray's doubles) on the primitive's own double coefficients (AlgebraicSurface's G,
// the torus's R and r), formed in double-double, not from the rounded ray polynomial the
// isolating solvers see. A double root of that rounded polynomial is off by the coefficients'
// rounding over |p'| (ill-conditioned near a tangency or between close shells); the polish
// removes that error.
//
// Notation: roots[0..n) is a solver's answer (Solve.h's contract: ascending, a tangency listed
// twice). The bracket of root i is the open interval between the midpoints to its neighbours
// (the range ends for the first and last): a polisher's result outside it, or one that does not
// lower |p|, is not taken.
#pragma once

#include <cstdint>

#include "primitives/solvers/DoubleDouble.h"
#include "primitives/solvers/Polynomial.h"

namespace csg {

enum class Polisher : uint8_t {
    Auto,      // Newton, on the roots a cheap condition estimate says double may miss (default)
    None,      // the isolating solver's double roots as they are
    Newton,    // Newton on every simple root: p in double-double, p' in double
    Laguerre,  // Laguerre's step (Kajiya's choice) on every simple root: p, p', p'' as above
    Bairstow,  // Bairstow's quadratic factor through the root and its nearest neighbour
};

inline constexpr Polisher kAllPolishers[] = {Polisher::Auto, Polisher::None, Polisher::Newton,
                                             Polisher::Laguerre, Polisher::Bairstow};

const char* polisherName(Polisher polisher);
// The polisher named name (as polisherName spells it); false when there is none.
bool polisherFromName(const char* name, Polisher* polisher);

// The root of p near roots[i] by method (Newton, Laguerre or Bairstow; Auto is Newton, None
// returns roots[i]), kept in the open interval (lo, hi) that holds no other root of the list;
// roots[i] itself when the method leaves it or does not lower |p|. Up to
// tol::kPolishMaxSteps steps, each ending when a step is below tol::kPolishStepRel of the root.
DoubleDouble polishRootWith(Polisher method, const PolynomialDD& p, const double* roots, int n,
                            int i, double lo, double hi);

// The bracket of roots[i] within [tlo, thi]: the midpoints to its neighbours (see above).
void rootBracket(const double* roots, int n, int i, double tlo, double thi, double* lo, double* hi);

// How far the double root x of the double polynomial p may be from p's exact root through
// evaluation rounding alone: Polynomial::eval's bound over |p'(x)| (unit: t; infinity where
// p'(x) = 0). Polisher::Auto polishes a root when this exceeds tol::kPolishConditionUlps ulps.
double rootErrorEstimate(const Polynomial& p, double x);

// ulp(x): the gap from |x| to the next double away from zero.
double ulpOf(double x);

// Polishes the simple roots in roots[0..n) of p (double coefficients, exact as given) in place,
// each rounded to the double nearest the polished value: every one for Newton, Laguerre and
// Bairstow; for Auto only those whose rootErrorEstimate exceeds tol::kPolishConditionUlps
// ulps; none for None. Tangencies (listed twice) are left alone. Returns how many were polished.
int polishRoots(Polisher polisher, const Polynomial& p, double* roots, int n, double tlo,
                double thi);

}  // namespace csg
