// An extrusion as the closed polyhedron it is once its curves are replaced by chords:
//   - a straight linear_extrude (no twist, one scale for both axes) is the prism, or the
//     frustum, of a polygon with holes: the chords' side quads (planar: a scale about the axis
//     keeps each side's top edge parallel to its bottom edge) and the two caps, ear-clipped;
//   - a rotate_extrude is the profile revolved in equal steps: each chord sweeps a band of
//     quads (isosceles trapezoids, so planar), and a wedge has the profile as its two ends;
//   - a twisted or unevenly scaled linear_extrude, whose sides are curved, is sliced as
//     OpenSCAD slices it (slicedExtrusionMesh), its contours' edges cut into equal pieces: of
//     the slices and pieces that keep every side triangle within its share of the deviation,
//     those that make the fewest triangles (ExtrusionMesh.cpp derives the bound).
// With straight lines only, a linear_extrude's polyhedron is the extrusion itself. With curves,
// every chord's ends lie on the curve and no point of the curve is farther than the deviation
// from its chord, at the top as at the bottom; a revolution gives half the deviation to the
// profile's chords and half to the steps at its largest radius, or all of it to the steps when
// the profile has no curve.
//
// The region is the outline's by its fill rule, whatever the segments' order and however its
// contours overlap or touch (glyphs, projections, imported drawings): Clipper's union of the
// chords with that rule gives outer contours with their holes (under the even-odd rule a
// segment may be walked either way). It works on integers, on a grid of 2^-50 of the
// outline's size, and cleans what it returns of corners within about 2^-22 of the size of
// their neighbours or of the line through them (ExtrusionMesh.cpp says why): the outline moves
// by less than that.
//
// Declined (nullopt, the caller keeps the exact leaf): a straight linear_extrude with a top
// scale of 0 (the apex would join the contours' sides in one vertex), an unbounded height, a
// 2-D shape; an outline whose segments do not chain into closed walks; more than
// kMaxExtrusionMeshCorners chord (or cut) corners, kMaxRevolutionPoints points, or a sliced
// mesh of more points than a polyhedron may have; a cap that ear clipping cannot cut; a mesh
// that is not closed, or for a prism or a revolution not a manifold (contours that touch at a
// corner).
#pragma once

#include <cstddef>
#include <optional>
#include <vector>

#include "csg/mesh/Tessellate.h"
#include "primitives/Extrusion.h"
#include "primitives/Polyhedron.h"

namespace io {

// Chord corners of an outline beyond which no mesh is built (caps are ear-clipped in O(n^2)).
inline constexpr size_t kMaxExtrusionMeshCorners = 1 << 16;
// Points of a revolution (corners times steps) beyond which none is built.
inline constexpr size_t kMaxRevolutionPoints = 1 << 22;

// A polygon of an outline's region: its outer contour (counter-clockwise) and its holes
// (clockwise), each a list of corners.
struct RegionPolygon {
    std::vector<csg::Vec2> outer;
    std::vector<std::vector<csg::Vec2>> holes;
};

// The outline's region by its fill rule as polygons, its curves replaced by chords within
// `deviation` (> 0), on Clipper's grid as described above; nullopt when its segments do not
// chain into closed walks, when the chords would have more than kMaxExtrusionMeshCorners
// corners, or when Clipper refuses them.
std::optional<std::vector<RegionPolygon>> chordRegion(const csg::Outline& outline,
                                                      const csg::Bounds2& box, double deviation);

// OpenSCAD 2021's linear_extrude of the region from z0 to z1 turning by `twist` degrees and
// scaling to `scale` at the top, in `slices` layers (OPENSCAD.md section 3; its
// GeometryEvaluator's extrudePolygon and add_slice): layer j, at z0 + (z1 - z0) j / slices, is
// the region turned by -twist j / slices (OpenSCAD's degree trigonometry) and then scaled by
// 1 - (1 - scale) j / slices per axis. Between two layers each contour edge p -> c (p1, c1
// below, p2, c2 above) becomes two triangles split along the shorter diagonal; when the two
// are equal within 10 ppm, along p1 c2 unless the contour is a hole or the slice does not turn
// forward (twist <= 0), not both. A zero top scale inverts the choice and leaves out the
// triangle that would have no area. The caps are the region (ear-clipped) at the bottom and its
// last layer at the top when both top scales are above 0. The solid is the mesh's by crossing
// parity; nullopt when it is not closed (a top scale of 0 on one axis can fold it), larger than
// a polyhedron may be, or a cap cannot be ear-clipped. capStraight: a cap corner within that
// distance of the line through its neighbours is not cut as an ear (csg/mesh/EarClip.h); 0, as
// OpenSCAD, cuts at any corner that is not exactly on that line.
std::optional<csg::Polyhedron> slicedExtrusionMesh(const std::vector<RegionPolygon>& region,
                                                   double z0, double z1, double twist,
                                                   csg::Vec2 scale, int64_t slices,
                                                   double capStraight = 0.0);

// OpenSCAD 2021's faceted rotate_extrude of a region in x >= 0 (OPENSCAD.md section 4): the
// ring of each profile corner has `sections` equal steps through `degrees` (in (0, 360]) from
// azimuth `start`, its corners at start + degrees k / sections by OpenSCAD's degree
// trigonometry (io/Degrees.h cosDegrees, sinDegrees). nullopt as for extrusionMesh.
std::optional<csg::Polyhedron> facetedRevolutionMesh(const std::vector<RegionPolygon>& region,
                                                     double start, double degrees,
                                                     int64_t sections);

// The extrusion as a closed polyhedron in its own frame, its curves within `deviation` (local
// units, > 0) of their chords, or nullopt (see above). A balanced fit (csg::FacetFit) scales a
// revolution's rings out about the axis, so its steps stand as far outside their circles as
// inside: about 1 / sqrt(2) of the steps; chords of a profile stay inscribed.
std::optional<csg::Polyhedron> extrusionMesh(const csg::Extrusion& extrusion, double deviation,
                                             csg::FacetFit fit = csg::FacetFit::Inscribed);

}  // namespace io
