// offset() and minkowski() of 2-D shapes as OpenSCAD 2021 computes them with Clipper, for
// parts whose curves are faceted as OpenSCAD's (--curves openscad, or $fn): the shapes'
// polygons on Clipper's integer grid of 2^-16, offset by Clipper's ClipperOffset with OpenSCAD's
// join and arc tolerance, or summed as ClipperUtils::applyMinkowski sums them, and cleaned as
// OpenSCAD cleans every Clipper result. csgray keeps a 2-D shape as a tree
// (io/Shapes2D.h); OpenSCAD evaluates each node to polygons at once, so the tree is replayed
// node by node (2021 src/GeometryEvaluator.cc, src/clipper-utils.cc):
//   a leaf          its outlines, each point truncated onto the grid (x * 2^16 to an
//                   integer, as OpenSCAD's IntPoint conversion does), then "sanitized": a
//                   Clipper union with the even-odd rule (a nonzero leaf, a glyph or an exact
//                   offset's band, with the nonzero rule), every contour cleaned by
//                   CleanPolygon (distance 1.415 grid units) and dropped below 3 points;
//   a boolean       Clipper's union, difference or intersection of the two operands with the
//                   nonzero rule, cleaned the same way.
// csgray's trees are binary where OpenSCAD's nodes are n-ary (difference() { a; b; c; } is
// a - (b u c) here, one Clipper call there) and a transformed leaf is snapped once here where
// OpenSCAD snaps it before and after the transform: either moves a vertex by at most a grid
// step. Curves that are not faceted (an exact circle under a faceted offset) are replaced by
// chords within tol::kFlattenRel of the shape's size.
#pragma once

#include <optional>
#include <string>

#include "csg/Tree.h"
#include "csg/derived/Offset2D.h"

namespace csg {

// Clipper's join for each OffsetJoin: round (jtRound), miter (jtMiter, miter limit 1e6 as
// OpenSCAD's OffsetNode sets it) or chamfer (jtSquare).
// arcTolerance: OpenSCAD's |r| (1 - cos(180 deg / fragments(|r|))), in shape units.
struct ClipperOffsetSpec {
    double delta = 1.0;
    OffsetJoin join = OffsetJoin::Round;
    double arcTolerance = 0.0;
};

// The offset shape as one even-odd outline of straight segments (outer curves and holes of
// Clipper's result, at multiples of 2^-16); empty when the result is empty. nullopt and
// `error` set when Clipper refuses the input (coordinates beyond its range, about 7e13).
std::optional<Outline> clipperOffset(const Node& shape, const ClipperOffsetSpec& spec,
                                     std::string& error);

// minkowski() of 2-D shapes as OpenSCAD 2021's ClipperUtils::applyMinkowski: for every pair
// of contours of a and b, Clipper's MinkowskiSum (the quads swept by one contour's edges along
// the other's), plus every contour of each shape moved by the first point of every
// counter-clockwise contour of the other (filling the insides), all united with the nonzero
// rule. One even-odd outline of straight segments as clipperOffset's; nullopt and `error` set
// when Clipper refuses the input.
std::optional<Outline> clipperMinkowski(const Node& a, const Node& b, std::string& error);

}  // namespace csg
