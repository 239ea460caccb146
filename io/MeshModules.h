// polyhedron(points, faces, convexity) (and 2021's deprecated triangles=) and import(file,
// convexity) of STL, OFF and OBJ files: both a primitives/Polyhedron.h mesh, a solid by
// crossing parity. import() of a DXF file hands over to io/DxfModules.h (a 2-D shape).
#pragma once

#include "io/Evaluator.h"

namespace io {

// The built-in modules. polyhedron(): faces are OpenSCAD's (clockwise seen from outside, though
// the solid does not depend on it); an out-of-range index is skipped with OpenSCAD's warning; a
// point that is not [x, y, z] (or [x, y]) of finite numbers is an error at the argument.
// import(): the file is found as io/DataFiles.h says (beside the .scad file that contains the
// call, else next to the main file, with OpenSCAD's deprecation warning); a missing, unreadable
// or malformed file is an error at the call naming the file's line and column. Both warn at the
// call when the mesh is open, non-manifold or inconsistently wound, and say what csgray does.
Instance polyhedronModule(Evaluator& e, const InstantiationStmt& s, const ContextPtr& ctx,
                          const GeomState& state);
Instance importModule(Evaluator& e, const InstantiationStmt& s, const ContextPtr& ctx,
                      const GeomState& state);

}  // namespace io
