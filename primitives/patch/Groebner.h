// The thesis' method (Sweeney-style "Ray tracing polynomial patches using Groebner bases"):
// the ray is the meet of two planes, each plane equation on the patch is a bicubic F_k(u, v);
// a Buchberger reduction of {F1, F2} in lex order v > u yields a basis whose v-free element
// is a polynomial in u; its roots in [0, 1] are back-substituted into the basis element of
// lowest v-degree for v, and t is read from the patch point.
#pragma once

#include "primitives/patch/BezierPatch.h"

namespace csg {

// What one Groebner intersection did, for tests and the benchmark.
struct GroebnerStats {
    int basisSize = 0;        // elements of the reduced basis (0 when the reduction broke down)
    int uDegree = -1;         // degree of the v-free element (-1: none found)
    bool empty = false;       // a nonzero constant in the basis: the planes never meet on S
    bool breakdown = false;   // capacity or degree exceeded (see Groebner.cpp): no answer
};

// The crossings of the line o + t d with patch, by the Groebner-basis method; contract as in
// BezierPatch.h. Returns 0 (a miss) on a breakdown; stats, when given, says which.
int intersectByGroebner(const BezierPatch& patch, const Vec3& o, const Vec3& d,
                        PatchCrossings& out);
// The same, also reporting what the reduction did in *stats.
int intersectByGroebner(const BezierPatch& patch, const Vec3& o, const Vec3& d,
                        PatchCrossings& out, GroebnerStats* stats);

}  // namespace csg
