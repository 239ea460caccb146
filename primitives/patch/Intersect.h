// One entry for every ray/patch method: the dispatcher PatchSet and the benchmarks call.
#pragma once

#include "primitives/patch/BezierPatch.h"

namespace csg {

// The crossings of the line o + t d with patch by the given method; contract as in
// BezierPatch.h (ascending t, (u, v) in [0, 1]^2, at most kMaxPatchCrossings).
int intersectPatch(PatchMethod method, const BezierPatch& patch, const Vec3& o, const Vec3& d,
                   PatchCrossings& out);

// The language's name of a method ("groebner", "resultant", "clip", "newton",
// "groebner-exact", "groebner-float"), and every method (for lookups by name).
const char* patchMethodName(PatchMethod method);
inline constexpr PatchMethod kAllPatchMethods[] = {
    PatchMethod::Groebner, PatchMethod::Resultant,     PatchMethod::Clip,
    PatchMethod::Newton,   PatchMethod::GroebnerExact, PatchMethod::GroebnerFloat};

}  // namespace csg
