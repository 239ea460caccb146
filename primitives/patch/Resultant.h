// Kajiya's method ("Ray tracing parametric patches", SIGGRAPH 1982): the ray is the meet of
// two planes, and each plane's equation on the patch is a cubic in v with coefficients cubic
// in u (PatchAlgebra.h). Their Sylvester resultant with respect to v is a polynomial in u of
// degree <= 18 whose roots in [0, 1] are the u of the crossings; v is the common root of
// F1(u, .) and F2(u, .), and t is read from the patch point.
//
// The resultant is computed through its Bezout form: for two cubics the 3x3 Bezout matrix
// B(u), entries of degree <= 6 in u, has det B = -Res_v(F1, F2) (the 6x6 Sylvester
// determinant; tests check the identity numerically). Multiplying out a 3x3 determinant of
// polynomials is exact polynomial arithmetic, with no division. The common root in v is read
// from the null vector (1, v, v^2) of B(u), the gcd's root when it is simple.
#pragma once

#include "primitives/patch/PatchAlgebra.h"

namespace csg {

// What one resultant intersection did, for tests and the benchmark.
struct ResultantStats {
    int uDegree = -1;  // degree of the resultant in u after trimming (-1: identically zero)
};

// The resultant Res_v(F1, F2) as a polynomial in u, coefficients ascending, degree <= 18
// (nominal; trailing zeros are trimmed by the caller). For tests: det of the Bezout matrix.
std::array<double, 19> resultantInU(const Bivariate& f1, const Bivariate& f2);

// The crossings of the line o + t d with patch, by Kajiya's resultant; contract as in
// BezierPatch.h.
int intersectByResultant(const BezierPatch& patch, const Vec3& o, const Vec3& d,
                         PatchCrossings& out);
// The same, also reporting the resultant's degree in *stats (may be null), with options
// (options.smallRel decides which v-coefficients are zero, hence the Bezout matrix's size).
int intersectByResultant(const BezierPatch& patch, const Vec3& o, const Vec3& d,
                         PatchCrossings& out, ResultantStats* stats,
                         const AlgebraOptions& options = {});

}  // namespace csg
