#include "primitives/solvers/Solve.h"

#include <algorithm>

#include "primitives/base/NamedChoice.h"
#include "primitives/solvers/Bernstein.h"
#include "primitives/solvers/Cubic.h"
#include "primitives/solvers/Descartes.h"
#include "primitives/solvers/IntervalSolver.h"
#include "primitives/solvers/Quartic.h"
#include "primitives/solvers/Roots.h"
#include "primitives/solvers/Sturm.h"
#include "primitives/solvers/Yuksel.h"

namespace csg {

const char* solverName(Solver solver) {
    switch (solver) {
        case Solver::Auto:
            return "auto";
        case Solver::ClosedForm:
            return "closed-form";
        case Solver::SturmBisection:
            return "sturm-bisection";
        case Solver::SturmIllinois:
            return "sturm-illinois";
        case Solver::Yuksel:
            return "yuksel";
        case Solver::Descartes:
            return "descartes";
        case Solver::Bernstein:
            return "bernstein";
        case Solver::Interval:
            return "interval";
    }
    return "?";
}

bool solverFromName(const char* name, Solver* solver) {
    return choiceFromName(name, kAllSolvers, solverName, solver);
}

namespace {

// True when the crossings in roots[0..n) agree in parity with p's signs at the range ends
// (when those signs are trustworthy): a cheap proof-of-consistency for a root list.
bool parityConsistent(const Polynomial& p, double tlo, double thi, const double* roots, int n) {
    if (isNumericalZero(p, tlo) || isNumericalZero(p, thi)) return true;
    int crossings = 0;
    for (int i = 0; i < n; ++i)
        if (!isTangency(roots, n, i)) ++crossings;
    const bool endsDiffer = (p(tlo) < 0.0) != (p(thi) < 0.0);
    return (crossings % 2 == 1) == endsDiffer;
}

// The roots of p (trimmed, range clamped) by the method, refined in double.
int isolate(const Polynomial& p, double tlo, double thi, double* roots, Solver solver,
            double relTol) {
    switch (solver) {
        case Solver::Auto: {
            if (p.degree() <= 2) return solveCubic(p, tlo, thi, roots);
            if (p.degree() <= 4) {
                bool verified = true;
                const int n = p.degree() == 3 ? solveCubic(p, tlo, thi, roots)
                                              : solveQuartic(p, tlo, thi, roots, &verified);
                if (verified) return n;
            }
            const int n = solveYuksel(p, tlo, thi, roots, relTol);
            if (parityConsistent(p, tlo, thi, roots, n)) return n;
            return solveIntervalSubdivision(p, tlo, thi, roots, relTol);
        }
        case Solver::ClosedForm:
            if (p.degree() <= 3) return solveCubic(p, tlo, thi, roots);
            if (p.degree() == 4) return solveQuartic(p, tlo, thi, roots);
            return solveYuksel(p, tlo, thi, roots, relTol);
        case Solver::SturmBisection:
            return solveSturm(p, tlo, thi, roots, SturmRefine::Bisection, relTol);
        case Solver::SturmIllinois:
            return solveSturm(p, tlo, thi, roots, SturmRefine::Illinois, relTol);
        case Solver::Yuksel:
            return solveYuksel(p, tlo, thi, roots, relTol);
        case Solver::Descartes:
            return solveDescartes(p, tlo, thi, roots, relTol);
        case Solver::Bernstein:
            return solveBernstein(p, tlo, thi, roots, relTol);
        case Solver::Interval:
            return solveIntervalSubdivision(p, tlo, thi, roots, relTol);
    }
    return 0;
}

}  // namespace

int solve(const Polynomial& input, double tlo, double thi, double* roots, Solver solver,
          double relTol, Polisher polisher) {
    const Polynomial p = input.trimmed();
    if (p.degree() == 0 || !(tlo <= thi)) return 0;
    // Step 1: no root lies beyond Fujiwara's bound; clamping there keeps t^n finite.
    const double bound = rootBound(p);
    tlo = std::max(tlo, -bound), thi = std::min(thi, bound);
    if (!(tlo <= thi)) return 0;
    // Step 2: isolate and refine in double by the method.
    const int n = isolate(p, tlo, thi, roots, solver, relTol);
    // Step 3: polish in double-double.
    if (relTol == 0.0) polishRoots(polisher, p, roots, n, tlo, thi);
    return n;
}

}  // namespace csg
