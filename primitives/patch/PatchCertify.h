// Certifying a patch method's answer (issue 23): interval arithmetic proves that a list of
// crossings is exactly the set of crossings of the line with the patch, each simple.
// Notation: F_k(u, v) = n_k . (S(u, v) - o) with n_k = e_a x d (exact components, as in
// GroebnerExact.h); B_ij their Bernstein coefficients, enclosed by outward-rounded intervals
// (solvers/Interval.h), so every statement below is about the double ray and the double patch.
//
// The proof has two parts. Existence and uniqueness: around each crossing (u_i, v_i) a box X_i
// of radius r (tried from large to small) passes Krawczyk's test, K(X_i) inside X_i: F has
// exactly one zero in X_i, a simple one, and it lies in K(X_i), which must lie in
// [0, 1]^2 widened by tol::kPatchParamSlack; the boxes must be disjoint. Exclusion: [0, 1]^2
// is subdivided (interval de Casteljau) until each piece lies inside some X_i or one F_k's
// Bernstein coefficients all have one strict sign there (no zero of F_k in the piece).
// Either part failing (a tangent ray, a missed or spurious crossing, a crossing within the
// slack of an edge, the piece budget spent) answers false: "not certified", never "wrong".
#pragma once

#include "primitives/patch/BezierPatch.h"

namespace csg {

struct CertifyStats {
    int pieces = 0;            // subdivision pieces examined by the exclusion
    bool rootsProved = false;  // every listed crossing passed Krawczyk's test
};

// True when found[0..n) are proved to be all the crossings of the line o + t d with patch
// ((u, v) in [0, 1]^2 up to the slack), each simple and each inside its Krawczyk box.
bool certifyCrossings(const BezierPatch& patch, const Vec3& o, const Vec3& d,
                      const PatchCrossings& found, int n, CertifyStats* stats = nullptr);

}  // namespace csg
