// The one door to the real-root solvers: pick a method, get the roots of p in a t range.
//
// Contract of every solver: the real roots of p in the closed range [tlo, thi] (finite),
// ascending; a crossing (odd multiplicity: p changes sign) is listed once, a tangency (even
// multiplicity) twice with equal values, so a ray through a solid p <= 0 is inside exactly
// between roots 2i and 2i + 1 of the whole line and a tangency makes a zero-length span.
// Roots p cannot resolve in double precision form one root. roots must hold p.degree() values.
#pragma once

#include <cstdint>

#include "primitives/solvers/Polynomial.h"

namespace csg {

enum class Solver : uint8_t {
    Auto,            // by degree and conditioning: see solve()
    ClosedForm,      // degree <= 4 only: quadratic, Kahan's cubic, Ferrari-OdM quartic
    SturmBisection,  // Sturm isolation, bisection refinement (the thesis' baseline)
    SturmIllinois,   // Sturm isolation, Illinois refinement
    Yuksel,          // critical points bracket the roots, recursively (HPG 2022)
};

inline constexpr Solver kAllSolvers[] = {Solver::Auto, Solver::ClosedForm, Solver::SturmBisection,
                                         Solver::SturmIllinois, Solver::Yuksel};

const char* solverName(Solver solver);

// Auto: degree <= 2 by the stable quadratic; degree 3 and 4 by the closed form when its own
// residual checks pass (see Quartic.h), else by Yuksel; higher degrees by Yuksel.
// ClosedForm on a degree above 4 falls back to Yuksel.
int solve(const Polynomial& p, double tlo, double thi, double* roots, Solver solver = Solver::Auto);

}  // namespace csg
