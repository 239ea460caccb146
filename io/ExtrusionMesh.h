// A straight linear_extrude (no twist, one scale for both axes) as the closed polyhedron it is
// once its outline's curves are replaced by chords: the prism, or the frustum, of a polygon
// with holes. Its faces are the chords' side quads (planar: a scale about the axis keeps each
// side's top edge parallel to its bottom edge) and the two caps, ear-clipped. With an outline
// of straight lines only the polyhedron is the extrusion itself; with curves, every chord's
// ends lie on the curve and no point of the curve is farther than the deviation from its
// chord, at the top as at the bottom.
//
// The region is the outline's by its fill rule, whatever the segments' order and however its
// contours overlap or touch (glyphs, projections, imported drawings): Clipper's union of the
// chords with that rule gives outer contours with their holes. It works on integers, on a grid
// of 2^-28 of the outline's size, and cleans what it returns of corners closer than that
// (ExtrusionMesh.cpp says why): the corners move by 2e-9 of the size at most.
//
// Declined (nullopt, the caller keeps the exact leaf): another kind of extrusion, a twist or
// two scales (curved sides), a scale of 0 (the apex would join the contours' sides in one
// vertex), an unbounded height, more than kMaxExtrusionMeshCorners chord corners, a cap that
// ear clipping cannot cut, or a mesh that is not a closed manifold.
#pragma once

#include <cstddef>
#include <optional>

#include "primitives/Extrusion.h"
#include "primitives/Polyhedron.h"

namespace io {

// Chord corners beyond which the prism is not built (its caps are ear-clipped in O(n^2)).
inline constexpr size_t kMaxExtrusionMeshCorners = 1 << 16;

// The extrusion as a closed polyhedron in its own frame, its curves within `deviation` (local
// units, > 0) of their chords, or nullopt (see above).
std::optional<csg::Polyhedron> straightExtrusionMesh(const csg::Extrusion& extrusion,
                                                     double deviation);

}  // namespace io
