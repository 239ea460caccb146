// bezier_patch(points = [16 points], method = "clip", solid = false) and
// bezier_patches(points = [...], patches = [[16 indices], ...], method, solid) (the Utah teapot
// layout: each patch lists 16 indices into points, row by row along u). A set with
// solid=false is a surface (primitives/PatchSet.h): a top-level object only.
#pragma once

#include "io/Evaluator.h"

namespace io {

// The built-in modules; every bad argument is a file:line:col error at that argument with the
// expected form (wrong counts, an index out of range or not whole, a non-finite coordinate,
// an unknown method with the valid names).
Instance bezierPatchModule(Evaluator& e, const InstantiationStmt& s, const ContextPtr& ctx,
                           const GeomState& state);
Instance bezierPatchesModule(Evaluator& e, const InstantiationStmt& s, const ContextPtr& ctx,
                             const GeomState& state);

}  // namespace io
