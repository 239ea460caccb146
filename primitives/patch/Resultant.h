// Kajiya's method ("Ray tracing parametric patches", 1982): the ray is the meet of two
// planes; the Sylvester resultant of the two bicubics F1, F2 with respect to v is a polynomial
// in u of degree <= 18 whose roots in [0, 1] are the u of the hits; v is the common root of
// F1(u, .) and F2(u, .), and t is read from the patch point.
#pragma once

#include "primitives/patch/BezierPatch.h"

namespace csg {

// What one resultant intersection did, for tests and the benchmark.
struct ResultantStats {
    int uDegree = -1;  // degree of the resultant in u after trimming (-1: identically zero)
};

// The crossings of the line o + t d with patch, by Kajiya's resultant; contract as in
// BezierPatch.h.
int intersectByResultant(const BezierPatch& patch, const Vec3& o, const Vec3& d,
                         PatchCrossings& out);
// The same, also reporting the resultant's degree in *stats.
int intersectByResultant(const BezierPatch& patch, const Vec3& o, const Vec3& d,
                         PatchCrossings& out, ResultantStats* stats);

}  // namespace csg
