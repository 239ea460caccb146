// Subdivision to a flatness bound, then 2-D Newton from each flat piece the ray's box test
// keeps (the `newton` method of bezier_patch()).
#pragma once

#include "primitives/patch/BezierPatch.h"

namespace csg {

// The crossings of the line o + t d with patch; contract as in BezierPatch.h. Fixed-size
// stack, no heap. Pieces are halved until flat within tol::kPatchFlatRel; each flat piece
// whose box meets the line runs Newton from its centre and keeps a root inside itself. A line
// meeting one flat piece twice (grazing it within ~0.1 degrees) may lose one crossing.
int intersectByNewton(const BezierPatch& patch, const Vec3& o, const Vec3& d, PatchCrossings& out);

}  // namespace csg
