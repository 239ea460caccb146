// surface(f = "x^4 + y^4 + z^4 - 1", bbox = [[x0,y0,z0],[x1,y1,z1]], solver = "auto"): the
// algebraic solid { p in bbox : F(p) <= 0 } of issue 5 (primitives/AlgebraicSurface.h).
// OpenSCAD's heightmap surface(file = ...) shares the name: a call in that form goes to
// io/HeightmapModule.h (isHeightmapCall() tells the two apart by their arguments).
#pragma once

#include "io/Evaluator.h"

namespace io {

// The built-in module; every bad argument is a file:line:col error with the expected form,
// and a problem inside f is located at its character in the string literal when f is one.
Instance surfaceModule(Evaluator& e, const InstantiationStmt& s, const ContextPtr& ctx,
                       const GeomState& state);

}  // namespace io
