// DXF drawings in the language (io/DxfFile.h reads them): import() of a .dxf file, the legacy
// file= of linear_extrude() and rotate_extrude(), and the functions dxf_dim() and dxf_cross().
// A drawing is one 2-D leaf (an even-odd outline); its arcs are exact unless the curve mode
// facets them ($fn, $fa, $fs of the call, as for circle()); --curves openscad also reads only
// what OpenSCAD 2021 reads (LWPOLYLINE bulges straight, no POLYLINE). The file is found as
// import() finds meshes; a missing or malformed file is an error at the call naming the DXF's
// line; entities csgray does not read get OpenSCAD's "Unsupported DXF Entity" warning.
#pragma once

#include <string_view>

#include "io/BoundArgs.h"

namespace io {

// Whether a file name is a DXF file's (by its extension, case-insensitively, as OpenSCAD).
bool isDxfFile(std::string_view name);

// Where the DXF arguments of a call are in its bound arguments, and the scale to apply (each
// module reads its own: import() and rotate_extrude() take a number <= 0 as 1, linear_extrude
// takes its top scale).
struct DxfArgs {
    size_t file;    // a string (the caller checked)
    size_t layer;   // a name, or a number OpenSCAD turns into one; undef: every layer
    size_t origin;  // [x, y]; undef: [0, 0]
    double scale;
};

// The drawing as a 2-D shape (one Plane leaf tagged with the call, named "import"); the empty
// shape when it has no paths.
Instance dxfShape(Evaluator& e, const BoundArgs& b, const ContextPtr& ctx, const GeomState& state,
                  const DxfArgs& args);

// import("drawing.dxf", layer, convexity, origin, scale): b is bound as import() binds it.
Instance importDxf(Evaluator& e, const BoundArgs& b, const ContextPtr& ctx, const GeomState& state);

// dxf_dim(file, name, layer, origin, scale): the dimension named `name` (the first DIMENSION
// when no name is given) measured as OpenSCAD 2021 measures it (src/dxfdim.cc): linear (the
// distance projected on its angle), aligned, angular, radius or diameter, or ordinate. undef
// with OpenSCAD's warning when the file or the dimension is missing or of a type it does not
// measure.
Value dxfDimFunction(Evaluator& e, const ArgValues& args, Loc loc);
// dxf_cross(file, layer, origin, scale): [x, y] where the lines of the first two one-edge
// paths of the drawing cross (undef with OpenSCAD's warning when there are no such two, or
// they are parallel). Arcs are OpenSCAD's 36-fragment chords, as there.
Value dxfCrossFunction(Evaluator& e, const ArgValues& args, Loc loc);

}  // namespace io
