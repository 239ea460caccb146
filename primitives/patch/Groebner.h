// The thesis' method ("Ray tracing polynomial patches using Groebner bases"): the ray is the
// meet of two planes, and each plane's equation on the patch is a bicubic F_k(u, v)
// (PatchAlgebra.h). A Buchberger reduction of {F1, F2} in lex order v > u (Bivariate.h) turns
// the pair into a Groebner basis whose v-free element is a polynomial in u; its roots in
// [0, 1] are back-substituted into the basis element of lowest v-degree for v, and t is read
// from the patch point. Coefficients are doubles with the article's small-value rule
// (tol::kGroebnerSmallRel). No heap: every polynomial is a fixed-capacity Bivariate.
//
// Variable order: lex v > u with v the parameter of lower degree in F1, F2 (a patch cubic in v
// and linear in u is solved as its transpose and (u, v) swapped back), so the eliminant is in
// the parameter of higher degree and the easy variable is the one eliminated.
//
// The steps, as in the article: R2, the mutual reduction of the pair (each reduced by the
// other until neither changes); the S-polynomial loop (Buchberger; pairs whose leading terms
// are coprime are skipped by Buchberger's first criterion, which cannot change the result);
// the emptiness test (a nonzero constant in G: the planes never meet on the patch's complex
// extension, a miss); then the reduced basis (elements whose leading term another's divides
// are dropped, the rest reduced by each other), whose v-free element is the eliminant.
// Beyond the article (AlgebraOptions::polish, on by default): each (u, v) is polished by
// Newton on (F1, F2), and at a near-double root u, where the basis element's v is
// ill-conditioned, v comes from the plane equations instead (PatchAlgebra.h).
//
// Cost: no heap, but ~100 KB of stack per call (the basis under construction and the reduced
// one: 2 x kCapacity Bivariates of 1 KB each); bench/reports/patches.md has the times and where
// the method breaks down (general bicubic patches: on every ray).
#pragma once

#include "primitives/base/Tolerances.h"
#include "primitives/patch/PatchAlgebra.h"

namespace csg {

// What one Groebner intersection did, for tests and the benchmark.
struct GroebnerStats {
    int rawBasisSize = 0;    // elements Buchberger's loop produced (R2 pair + added remainders)
    int basisSize = 0;       // elements of the reduced basis
    int uDegree = -1;        // degree of the v-free element (-1: none, e.g. a breakdown)
    bool empty = false;      // a nonzero constant in the basis: no common root at all
    bool breakdown = false;  // capacity exceeded or an eliminant of degree > 18: no answer
};

// The Groebner basis computation alone, for tests. smallRel is the small-value rule's
// threshold (tol::kGroebnerSmallRel in the method). basis[0..stats.basisSize) is the reduced
// basis, each element monic, ordered by leading term ascending (the eliminant first).
struct GroebnerBasis {
    static constexpr int kCapacity = 40;
    std::array<Bivariate, kCapacity> basis;
    GroebnerStats stats;
};
void groebnerBasis(const Bivariate& f1, const Bivariate& f2, double smallRel,
                   GroebnerBasis& result);

// The crossings of the line o + t d with patch, by the Groebner-basis method; contract as in
// BezierPatch.h. Returns 0 (a miss) on a breakdown; stats, when given, says which.
int intersectByGroebner(const BezierPatch& patch, const Vec3& o, const Vec3& d,
                        PatchCrossings& out);
// The same, also reporting what the reduction did in *stats (may be null), with options.
int intersectByGroebner(const BezierPatch& patch, const Vec3& o, const Vec3& d, PatchCrossings& out,
                        GroebnerStats* stats, const AlgebraOptions& options = {});

}  // namespace csg
