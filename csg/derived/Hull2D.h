// hull() of 2-D shapes: the convex hull of points and circular arcs, exactly. Where a shape is
// exact (circle() without faceting) its hull is bounded by arcs of its circles and by the
// lines tangent to them; where it is OpenSCAD's polygon, by the polygon's vertices, as
// OpenSCAD's applyHull2D takes them.
//
// How: the hull's support function h(phi) = max over the sites of x . u(phi), u(phi) =
// (cos phi, sin phi), is traced once round: a point's is p . u, an arc's is c . u + rho for phi
// within the arc's directions seen from its centre (outside them the arc's ends, which are
// points too, carry it). Where another site overtakes the current one the hull passes from one
// to the other along a line: p to q, a tangent from a point to a circle, or a bitangent of two
// circles. While a circle is the maximum the hull follows it.
#pragma once

#include <vector>

#include "csg/Tree.h"
#include "csg/derived/Boundary2D.h"

namespace csg {

// Points and arcs whose hull is a shape's hull: every point they stand for lies in the shape
// (or on its boundary), and every vertex and convex arc of the shape's boundary is among them.
struct HullSites {
    std::vector<Vec2> points;
    std::vector<BoundaryPiece> arcs;  // Arc pieces only
    bool approximated = false;        // elliptic arcs or Beziers became chords
};

// Adds the sites of a 2-D shape (io/Shapes2D.h). A union of leaves gives every point and arc of
// its outlines (all lie in the union); a shape with an intersection or difference gives its
// boundary's (csg/derived/Boundary2D.h), since a leaf's vertex outside the result would grow the
// hull.
void addHullSites(const Node& shape, HullSites& sites);

// The convex hull as one closed counter-clockwise outline of lines and circular arcs; no
// segments when it has no area (fewer than 3 points not on one line, and no circle).
Outline convexHull2D(const HullSites& sites);

}  // namespace csg
