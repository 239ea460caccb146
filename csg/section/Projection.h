// OpenSCAD's projection() of a CSG tree onto the plane z = 0, as a 2-D region (an Outline of
// straight segments), and the tight bounds resize() needs. Each leaf becomes a closed triangle
// mesh in the tree's frame (csg/section/LeafMesh.h: exact for polyhedral leaves, within a
// tolerance for the others); polygons are combined by Clipper on an integer grid of 2^-50 of
// the part's extent (so a snapped coordinate moves by about a double's rounding).
//
// Notation: the section of a mesh by a plane n . x = c on side + is its section by the plane
// pushed by an infinitesimal toward +n: a vertex with n . v - c = 0 counts as below it. Its
// crossing segments chain into loops through the crossed edges (each crossing point computed
// once per edge, from the edge's lower-index end, so loops close bit for bit); the region is
// the loops' even-odd interior, which is the mesh's solid by crossing parity at that plane.
//
// Why these are exact for polyhedral leaves:
//   Section (cut = true). OpenSCAD 2021 intersects its (unregularised) Nef polyhedron with
//     the plane: a leaf is a closed set, a difference removes the closed subtrahend, and the
//     2-D faces left in the plane are the answer (checked with the binary: cube(10) and
//     translate([0, 0, -10]) cube(10) give the square, their intersection too, and
//     cube(10, center = true) minus translate([0, 0, -10]) cube(10) an L, cube(10) minus
//     that cube nothing). Pointwise booleans commute with the plane section, so the answer is
//     the 2-D CSG of each leaf's closed section: its section just above the plane united
//     with its section just below (the face lying in the plane is both's limit).
//   Shadow (cut = false). A shadow commutes with union only. The shadow of an intersection or
//     difference S is the union over the leaves' non-vertical faces F of the projection of
//     F n S (the top point of S over any shadow point lies on some face), and F n S is F cut
//     by S's section in F's plane; for csgray's regularised solid that is the CSG of the
//     leaves' sections just above the plane united with the CSG just below. So every piece
//     is a polygon computed from the leaves' own faces; no new surface is invented. A face is
//     a planar polygon (LeafMesh.h's faceStarts: a prism's wall or cap is one), cut once. Its
//     cost is faces x leaf triangles; past kMaxFaceWork the subtree is meshed as a whole
//     instead (and the result says so).
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "csg/Tree.h"
#include "primitives/Outline.h"
#include "primitives/base/Tolerances.h"

namespace csg {

// Most triangle-plane tests the face method may spend on one intersection or difference of
// a shadow (faces x triangles of the leaves near each face) before that subtree is meshed as
// a whole: a few seconds at most.
inline constexpr uint64_t kMaxFaceWork = uint64_t(200) << 20;

// Leaves that are not polyhedral are made meshes within tol::kLeafMeshToleranceRel of their
// bounds' diagonal first (primitives/base/Tolerances.h says why that value).

struct ProjectionResult {
    Outline outline;              // straight segments, even-odd; empty when nothing is there
    bool exact = true;            // false when a leaf or a subtree was meshed
    uint32_t meshedLeaves = 0;    // leaves meshed (not polyhedral)
    uint32_t meshedSubtrees = 0;  // shadows of intersections/differences meshed as a whole
    double meshError = 0.0;       // largest measured mesh-to-surface distance of those meshes
};

// The closed section of the tree's solid by z = 0 (OpenSCAD's projection(cut = true)).
// Throws std::invalid_argument for a tree with an unbounded or 2-D leaf.
ProjectionResult sectionAtZ0(const NodePtr& root);

// The shadow of the tree's solid along z on z = 0 (OpenSCAD's projection(cut = false)).
// Throws std::invalid_argument as sectionAtZ0.
ProjectionResult shadowAlongZ(const NodePtr& root);

// The shadow along z, exactly and with its curves, when every leaf is a linear_extrude with no
// twist and scale 1 whose axis the tree's transforms keep along z: each leaf's shadow is its
// outline under the leaf's map to x, y, and a union's shadow their union. An intersection or
// difference is the 2-D one only where its leaves have no shear into z and span one z
// interval (a linear_extrude of a 2-D boolean): the solid is then the region times that
// interval. Returns the 2-D tree (Plane leaves tagged `tags`, shape "projection"), or nullopt
// when the tree is not of that form (an empty tree's shadow is nullptr).
std::optional<NodePtr> axialShadow(const NodePtr& root, Tags tags);

// The solid's bounding box: exact for trees of unions of leaves (from their vertices, or the
// primitive's tight bounds); for trees with an intersection or difference, from the shadows
// along z and along x (so exact for polyhedral leaves, as shadowAlongZ). Empty for an empty
// tree. Throws std::invalid_argument as sectionAtZ0.
Bounds3 solidBounds(const NodePtr& root);

}  // namespace csg
