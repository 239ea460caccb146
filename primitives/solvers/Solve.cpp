#include "primitives/solvers/Solve.h"

#include "primitives/solvers/Cubic.h"
#include "primitives/solvers/Quartic.h"
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
    }
    return "?";
}

int solve(const Polynomial& input, double tlo, double thi, double* roots, Solver solver) {
    const Polynomial p = input.trimmed();
    if (p.degree() == 0 || !(tlo <= thi)) return 0;
    switch (solver) {
        case Solver::Auto: {
            if (p.degree() <= 2) return solveCubic(p, tlo, thi, roots);
            if (p.degree() <= 4) {
                bool verified = true;
                const int n = p.degree() == 3 ? solveCubic(p, tlo, thi, roots)
                                              : solveQuartic(p, tlo, thi, roots, &verified);
                if (verified) return n;
            }
            return solveYuksel(p, tlo, thi, roots);
        }
        case Solver::ClosedForm:
            if (p.degree() <= 3) return solveCubic(p, tlo, thi, roots);
            if (p.degree() == 4) return solveQuartic(p, tlo, thi, roots);
            return solveYuksel(p, tlo, thi, roots);
        case Solver::SturmBisection:
            return solveSturm(p, tlo, thi, roots, SturmRefine::Bisection);
        case Solver::SturmIllinois:
            return solveSturm(p, tlo, thi, roots, SturmRefine::Illinois);
        case Solver::Yuksel:
            return solveYuksel(p, tlo, thi, roots);
    }
    return 0;
}

}  // namespace csg
