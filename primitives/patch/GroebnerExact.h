// The Groebner-basis method in exact arithmetic (issue 23): every double of the patch and the
// ray is a rational, so the basis of {F1, F2} is computed over Q (GMP rationals) and no
// threshold decides what is zero. The basis is read off the Bezout resultant and proved
// equal to the ideal's (the shape basis {g0(u), e(u) v - c(u)}: F1, F2 vanish modulo it and
// deg g0 reaches the Bezout bound); where that proof fails (crossings at infinity, as on
// patches with a pole) Buchberger's algorithm runs over Z. Then the eliminant's real roots in
// [0, 1] (widened by tol::kPatchParamSlack) are isolated exactly (Descartes' rule on exact
// Bernstein coefficients of its square-free part), refined by exact bisection until u is known
// to 110 bits and v(u) to double precision, v is read from the basis element Kalkbrener's
// theorem names at that root, and t from the patch point. Exact means: the crossings reported
// are those of the double ray with the double patch, each once (a tangent crossing too),
// (u, v) rounded to double.
//
// Plane choice: F_k = n_k . (S(u, v) - o) with n_1 = e_a x d, n_2 = e_b x d (a, b the axes
// other than d's largest component): their components are d's own doubles, so the planes meet
// exactly in the line o + t d (RayPlanes' unit normals would be rounded).
// Cost: heap and GMP per ray, 2-10 ms with the shape basis, 0.1-0.5 s with Buchberger
// (bench/reports/patches.md): a reference and the fallback of the certified method
// (GroebnerCertified.h), not a per-pixel method.
#pragma once

#include "primitives/patch/BezierPatch.h"

namespace csg {

// What one exact Groebner intersection did, for tests and the benchmark.
struct ExactGroebnerStats {
    int rawBasisSize = 0;       // elements Buchberger's loop produced (the input pair included)
    int basisSize = 0;          // elements of the reduced basis
    int uDegree = -1;           // degree of the eliminant (-1: none)
    int squareFreeDegree = -1;  // degree of its square-free part
    bool empty = false;         // 1 in the basis: the planes never meet on the complex patch
    bool notZeroDimensional = false;  // no eliminant: F1, F2 share a curve (no isolated point)
    bool swapped = false;     // solved as the transpose (v is the parameter of lower degree)
    bool shapeBasis = false;  // the basis came from the resultant, proved (no Buchberger run)
};

// The crossings of the line o + t d with patch by the exact Groebner method; contract as in
// BezierPatch.h. stats may be null.
int intersectByExactGroebner(const BezierPatch& patch, const Vec3& o, const Vec3& d,
                             PatchCrossings& out, ExactGroebnerStats* stats = nullptr);

}  // namespace csg
