// text(...): OpenSCAD's text as a 2-D shape. The glyphs come from io/TextLayout.h (OpenSCAD
// 2021's placement, 1.024e5 advance bug included); each becomes one Plane leaf whose outline
// keeps the font's contours, with the non-zero rule, and the leaves are united, as OpenSCAD
// unites its glyph polygons. See ../shared/OPENSCAD.md section 2, "text(...)".
#pragma once

#include <cstdint>
#include <vector>

#include "io/Evaluator.h"
#include "io/TextLayout.h"
#include "primitives/Outline.h"

namespace io {

// text(text, size = 10, font, halign = "left", valign = "baseline", spacing = 1,
// direction = "ltr", language = "en", script = "latin"): exact quadratic and cubic Beziers, or
// OpenSCAD's chords where the curve mode facets (the fragment radius is size). An empty or
// all-space text is the empty shape.
Instance textModule(Evaluator& e, const InstantiationStmt& s, const ContextPtr& ctx,
                    const GeomState& state);

// OpenSCAD 2021's chords per Bezier piece (src/text.cc): max(floor(fragments / 8) + 1, 2),
// for the fragment count of a circle of radius size.
int64_t textChordCount(int64_t fragments);

// One outline per glyph that has contours (spaces have none), in the text's coordinates: the
// font's pieces as lines and exact Beziers when chords is 0, else each Bezier piece replaced by
// `chords` chords at uniform parameter steps, at the points OpenSCAD's
// DrawingCallback::curve_to computes. Consecutive segments share their end points bit for bit
// (see primitives/Outline.h); zero-length pieces are left out.
std::vector<csg::Outline> glyphOutlines(const TextLayout& layout, double size, int64_t chords);

// How many segments glyphOutlines would make, before it makes any (for the work budget).
uint64_t glyphSegmentCount(const TextLayout& layout, int64_t chords);

}  // namespace io
