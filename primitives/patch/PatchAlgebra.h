// Steps the two algebraic patch methods (Groebner.h, Resultant.h) share: the ray as two
// plane equations on the patch, real roots in u of a polynomial that may exceed the solvers'
// degree 16, the check that a candidate (u, v) is a common root, and the final crossing list.
// Notation: F_k(u, v) = n_k . (S(u, v) - o) with n_1, n_2 of RayPlanes (RayPlanes.h): unit,
// orthogonal to d and to each other, so F_1 = F_2 = 0 exactly on the line;
// t = d . (S(u, v) - o) / |d|^2.
#pragma once

#include "primitives/base/Tolerances.h"
#include "primitives/patch/Bivariate.h"

namespace csg {

// How the algebraic methods run (the defaults are the methods; tests and the benchmark vary
// them to show what each part contributes).
struct AlgebraOptions {
    double smallRel = tol::kGroebnerSmallRel;  // the Groebner small-value rule's threshold
    bool polish = true;  // Newton on (F1, F2) from each algebraic root (polishRoot)
};

struct PlaneEquations {
    Bivariate f1, f2;
};
PlaneEquations planeEquations(const BezierPatch& patch, const Vec3& o, const Vec3& d);

// A univariate polynomial of degree <= Bivariate::kMaxDegreeU, ascending coefficients.
struct WidePolynomial {
    std::array<double, Bivariate::kMaxDegreeU + 1> c{};
    int degree = 0;  // nominal: trimmed by unitParameterRoots
};

// The real roots of p in [-kPatchParamSlack, 1 + kPatchParamSlack], ascending, each once
// (a double root may appear twice; finishCrossings merges the points). Degree <= 16 goes to
// the root-solver issue's solve() (Solver::Auto); above, Bernstein subdivision on a local
// wider array (the same rule as solvers/Bernstein.h: 0 sign changes, no root; 1, one root).
// roots holds p.degree entries. A zero polynomial has no isolated roots: returns 0.
int unitParameterRoots(const WidePolynomial& p, double* roots);

// True when (u, v) lies in the closed unit square widened by kPatchParamSlack and both
// plane equations vanish there to within kPatchResidualRel of their terms' size.
bool isCommonRoot(const PlaneEquations& planes, double u, double v);

// The roots v in [0, 1] (widened by tol::kPatchParamSlack) of F1(u, .) and of F2(u, .), each
// at its degree in v under the small-value rule (smallRel): candidates for v at a root u when
// the method's own v is lost (two crossings at nearly the same u make the basis element or
// the Bezout null vector ill-conditioned). vs holds 2 * Bivariate::kMaxDegreeV entries.
int planeRootsInV(const PlaneEquations& planes, double u, double smallRel, double* vs);

// True when roots[i] has a neighbour in roots[0..count) (ascending) within
// tol::kPatchRootDriftParam: a near-double root, where v from the method is ill-conditioned.
bool hasCloseNeighbour(const double* roots, int count, int i);

// The crossing at a root (u, v) the method found: checked as found (isCommonRoot), then
// polished (when options.polish) and appended to out[n..).
void acceptMethodRoot(const BezierPatch& patch, const PlaneEquations& planes, const Vec3& o,
                      const Vec3& d, double u, double v, const AlgebraOptions& options,
                      PatchCrossings& out, int& n);

// The crossings at a root u whose v the method lost: each root of planeRootsInV, polished
// (when options.polish) as long as u moves by at most tol::kPatchRootDriftParam, kept when it
// is a common root; appended to out[n..).
void crossingsFromPlaneRoots(const BezierPatch& patch, const PlaneEquations& planes, const Vec3& o,
                             const Vec3& d, double u, const AlgebraOptions& options,
                             PatchCrossings& out, int& n);

// Up to kPolishSteps Newton steps on (F1, F2) = 0 from the algebraic root (u, v), each kept
// only while it lowers max |F_k|. Why: where two crossings share nearly the same u, the
// eliminant (or resultant) has a near-double root, found only to ~sqrt(ulp) in u; Newton in
// both parameters at once is well conditioned there and recovers full precision.
void polishRoot(const PlaneEquations& planes, double& u, double& v);

// Appends the crossing at (u, v), clamped to [0, 1]^2, with its t. n < kMaxPatchCrossings.
void appendCrossing(const BezierPatch& patch, const Vec3& o, const Vec3& d, double u, double v,
                    PatchCrossings& out, int& n);

// Sorts out[0..n) by t and merges points closer than kPatchSamePointParam in (u, v) (double
// roots, a root found from two basis elements); returns the new count.
int finishCrossings(PatchCrossings& out, int n);

}  // namespace csg
