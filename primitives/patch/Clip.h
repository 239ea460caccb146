// Bezier clipping (Nishita, Sederberg and Kakimoto 1990) with Newton polish: the practical
// default method of bezier_patch().
#pragma once

#include "primitives/patch/BezierPatch.h"

namespace csg {

// The crossings of the line o + t d with patch; contract as in BezierPatch.h. Fixed-size
// stack, no heap. A ray lying in the patch (infinitely many crossings) gives some of them.
int intersectByClip(const BezierPatch& patch, const Vec3& o, const Vec3& d, PatchCrossings& out);

}  // namespace csg
