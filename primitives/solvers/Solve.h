// The one door to the real-root solvers: pick a method, get the roots of p in a t range.
//
// Contract of every solver: the real roots of p in the closed range [tlo, thi] (finite),
// ascending; a crossing (odd multiplicity: p changes sign) is listed once, a tangency (even
// multiplicity) twice with equal values, so a ray through a solid p <= 0 is inside exactly
// between roots 2i and 2i + 1 of the whole line and a tangency makes a zero-length span.
// Roots p cannot resolve in double precision form one root. roots must hold p.degree() values.
#pragma once

#include <cstdint>

#include "primitives/solvers/Polish.h"
#include "primitives/solvers/Polynomial.h"

namespace csg {

enum class Solver : uint8_t {
    Auto,            // by degree and conditioning: see solve()
    ClosedForm,      // degree <= 4 only: quadratic, Kahan's cubic, Ferrari-OdM quartic
    SturmBisection,  // Sturm isolation, bisection refinement (the thesis' baseline)
    SturmIllinois,   // Sturm isolation, Illinois refinement
    Yuksel,          // critical points bracket the roots, recursively (HPG 2022)
    Descartes,       // Descartes' rule, Vincent-Collins-Akritas bisection (Descartes.h)
    Bernstein,       // Bernstein-basis subdivision by de Casteljau (Bernstein.h)
    Interval,        // interval-arithmetic subdivision, outward rounding (IntervalSolver.h)
};

inline constexpr Solver kAllSolvers[] = {
    Solver::Auto,   Solver::ClosedForm, Solver::SturmBisection, Solver::SturmIllinois,
    Solver::Yuksel, Solver::Descartes,  Solver::Bernstein,      Solver::Interval};

const char* solverName(Solver solver);
// The solver named name (as solverName spells it); false when there is none.
bool solverFromName(const char* name, Solver* solver);

// Auto: degree <= 2 by the stable quadratic; degree 3 and 4 by the closed form when its own
// residual checks pass (see Quartic.h), else by Yuksel; higher degrees by Yuksel, checked
// against the parity of p's sign change over the range (an odd number of crossings iff the
// ends' signs differ) and redone by interval subdivision, which cannot lose a root, when the
// check fails. ClosedForm on a degree above 4 falls back to Yuksel.
//
// relTol > 0 lets the iterative solvers stop a root's bracket at width relTol * max(1, |t|)
// (Roots.h, bracketSmallEnough) instead of at double resolution: accuracy traded for time.
// The closed forms ignore it. Every solver first clamps [tlo, thi] to Fujiwara's root bound
// (Roots.h), so values of p are never taken where t^n overflows.
//
// polisher then refines the simple roots in double-double (Polish.h, polishRoots) against p's
// exact value: Auto (the default) only the roots whose condition estimate says double may be
// more than half an ulp off, so that every simple root is within an ulp of p's exact root;
// Newton, Laguerre or Bairstow every simple root; None none. No polish when relTol > 0.
int solve(const Polynomial& p, double tlo, double thi, double* roots, Solver solver = Solver::Auto,
          double relTol = 0.0, Polisher polisher = Polisher::Auto);

}  // namespace csg
