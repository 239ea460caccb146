// offset() and hull(): shapes derived from their children (io/Offset.cpp, io/Hull.cpp; the
// geometry is csg/derived/'s).
#pragma once

#include "io/Evaluator.h"

namespace io {

// offset(r | delta, chamfer = false) of 2-D children (../shared/OPENSCAD.md section 2): exact
// (lines and arcs of the result's boundary grown or shrunk, csg/derived/Offset2D.h), or, where
// the curve mode facets a circle of radius |r| with the call's $fn, $fa, $fs, OpenSCAD 2021's
// Clipper offset of the polygons (csg/derived/ClipperOffset2D.h).
Instance offsetModule(Evaluator& e, const InstantiationStmt& s, const ContextPtr& ctx,
                      const GeomState& state);

// hull() of 2-D children (exact: tangents to arcs) or 3-D children (qhull over the vertices
// of the children's result, curved solids faceted as OpenSCAD's).
Instance hullModule(Evaluator& e, const InstantiationStmt& s, const ContextPtr& ctx,
                    const GeomState& state);

}  // namespace io
