// hull() of solids: the convex hull of the vertices of the children's result, as OpenSCAD
// 2021 takes it (CGALUtils::applyHull: every vertex of every child, faceted), computed by
// qhull and kept as a ConvexPolytope (an intersection of half-spaces: exact for rays).
//
// The vertices of a CSG result are not its leaves' vertices: a leaf's vertex cut away by a
// difference must not grow the hull, and an intersection makes corners no leaf has. So:
//   a union          the points of its operands (each lies in the union);
//   an intersection, a difference
//                    the points of its operands, and the meeting points of three planes of
//                    its leaves' faces (not all of one leaf), kept when the node's solid is
//                    on some side of them: a point is tried a small step off in the 26
//                    directions of a cube's neighbours and, for every three planes through it,
//                    in the 8 directions between them, against the solid's inside test.
// Every kept point lies in the solid's closure and every vertex of a solid bounded by planes is
// kept, so the hull is exact for polyhedral leaves. Curved leaves (a torus, an exact sphere)
// give the points the caller facets them into, and their curved faces give no planes.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "csg/Tree.h"

namespace csg {

// The points a leaf stands for in a hull, in its own frame, appended to out; false when it
// has none (the caller's faceting of curved primitives, see leafHullPoints).
using LeafPoints = std::function<bool(const Primitive&, std::vector<Vec3>& out)>;

// The vertices of a polyhedral leaf: a box's corners, a convex polyhedron's and a mesh's
// vertices, an extrusion's outline vertices at its bottom and top when its outline is all
// lines. False for anything else (curves, a half-space, 2-D shapes).
bool polyhedralLeafPoints(const Primitive& primitive, std::vector<Vec3>& out);

struct HullPoints {
    std::vector<Vec3> points;
    // Curved faces took part in an intersection or difference: corners where they meet other
    // faces are not among the points.
    bool curvedCut = false;
    // Too many faces met in one intersection or difference (more than kMaxPlaneTriples
    // triples of faces whose boxes overlap): corners past that budget are missing.
    bool tooManyPlanes = false;
};

// Most triples of faces (with overlapping boxes) one intersection or difference may try: a
// budget of time, a few seconds.
inline constexpr uint64_t kMaxPlaneTriples = uint64_t(1) << 25;

// The points of a 3-D tree, in the tree's frame, whose hull is its hull (see above).
HullPoints hullPointsOf(const Node& solid, const LeafPoints& leafPoints);

// The convex hull of the points as a convex polyhedron (faces merged where coplanar, as qhull
// merges them); nullopt with `why` set when the points span no volume (fewer than 4, or all on
// one plane) or qhull fails.
std::optional<ConvexPolytope> convexHull3D(const std::vector<Vec3>& points, std::string& why);

}  // namespace csg
