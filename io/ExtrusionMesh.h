// An extrusion as the closed polyhedron it is once its curves are replaced by chords:
//   - a straight linear_extrude (no twist, one scale for both axes) is the prism, or the
//     frustum, of a polygon with holes: the chords' side quads (planar: a scale about the axis
//     keeps each side's top edge parallel to its bottom edge) and the two caps, ear-clipped;
//   - a rotate_extrude is the profile revolved in equal steps: each chord sweeps a band of
//     quads (isosceles trapezoids, so planar), and a wedge has the profile as its two ends.
// With straight lines only, a linear_extrude's polyhedron is the extrusion itself. With curves,
// every chord's ends lie on the curve and no point of the curve is farther than the deviation
// from its chord, at the top as at the bottom; a revolution gives half the deviation to the
// profile's chords and half to the steps at its largest radius.
//
// The region is the outline's by its fill rule, whatever the segments' order and however its
// contours overlap or touch (glyphs, projections, imported drawings): Clipper's union of the
// chords with that rule gives outer contours with their holes. It works on integers, on a grid
// of 2^-28 of the outline's size, and cleans what it returns of corners closer than that
// (ExtrusionMesh.cpp says why): the corners move by 2e-9 of the size at most.
//
// Declined (nullopt, the caller keeps the exact leaf): a twist or two scales (curved sides), a
// scale of 0 (the apex would join the contours' sides in one vertex), an unbounded height, a
// 2-D shape; an outline whose segments do not chain into closed walks; more than
// kMaxExtrusionMeshCorners chord corners or kMaxRevolutionPoints points; a cap that ear
// clipping cannot cut; a mesh that is not a closed manifold (contours that touch at a corner).
#pragma once

#include <cstddef>
#include <optional>

#include "primitives/Extrusion.h"
#include "primitives/Polyhedron.h"

namespace io {

// Chord corners of an outline beyond which no mesh is built (caps are ear-clipped in O(n^2)).
inline constexpr size_t kMaxExtrusionMeshCorners = 1 << 16;
// Points of a revolution (corners times steps) beyond which none is built.
inline constexpr size_t kMaxRevolutionPoints = 1 << 22;

// The extrusion as a closed polyhedron in its own frame, its curves within `deviation` (local
// units, > 0) of their chords, or nullopt (see above).
std::optional<csg::Polyhedron> extrusionMesh(const csg::Extrusion& extrusion, double deviation);

}  // namespace io
