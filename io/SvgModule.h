// import("drawing.svg", center = false, dpi = 72): an SVG drawing (io/SvgFile.h reads it) as a
// 2-D shape, one even-odd Plane leaf per SVG shape, united as OpenSCAD 2021 unites them. Its
// curves are exact unless the curve mode is `openscad`, which makes OpenSCAD's chords
// ($fn, $fa and $fs are ignored, as OpenSCAD ignores them for SVG). The file is found as
// import() finds meshes; a missing or malformed file is an error at the call naming the SVG's
// line; what OpenSCAD reads other than the file means is a warning at the call.
#pragma once

#include <string_view>

#include "io/BoundArgs.h"

namespace io {

// Whether a file name is an SVG file's (by its extension, case-insensitively, as OpenSCAD).
bool isSvgFile(std::string_view name);

// b is bound as import() binds it: file 0, center 5, dpi 6 (layer, origin and scale are the
// caller's to warn about).
Instance importSvg(Evaluator& e, const BoundArgs& b, const GeomState& state);

}  // namespace io
