// OpenSCAD's 2-D shapes and extrusions as built-in modules (io/Modules2D.cpp).
#pragma once

#include "io/Evaluator.h"

namespace io {

// square(size, center), circle(r | d) (exact, or OpenSCAD's polygon where the curve mode
// facets it), polygon(points, paths) (even-odd over all paths): 2-D shapes.
Instance squareModule(Evaluator& e, const InstantiationStmt& s, const ContextPtr& ctx,
                      const GeomState& state);
Instance circleModule(Evaluator& e, const InstantiationStmt& s, const ContextPtr& ctx,
                      const GeomState& state);
Instance polygonModule(Evaluator& e, const InstantiationStmt& s, const ContextPtr& ctx,
                       const GeomState& state);
// linear_extrude(height, center, scale) and rotate_extrude(angle): the 2-D children lifted,
// exactly (primitives/Extrusion.h), or OpenSCAD 2021's legacy file = DXF drawing in their
// place (io/DxfModules.h). twist and a non-uniform scale are errors for now.
Instance linearExtrudeModule(Evaluator& e, const InstantiationStmt& s, const ContextPtr& ctx,
                             const GeomState& state);
Instance rotateExtrudeModule(Evaluator& e, const InstantiationStmt& s, const ContextPtr& ctx,
                             const GeomState& state);

}  // namespace io
