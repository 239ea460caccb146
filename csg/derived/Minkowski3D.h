// minkowski() of solids, the geometry; io/Minkowski.cpp decides what each operand is. Three
// constructions, each the exact Minkowski sum of what it is given:
//   convex ⊕ convex   the convex hull of all pairwise sums of their vertices (OpenSCAD 2021's
//                     CGALUtils::applyMinkowski, for every pair of convex pieces);
//   P ⊕ K, K convex   (P + k) ∪ ⋃_T hull(T ⊕ K) over the triangles T of P's boundary, for
//                     any point k of K and any solid P, convex or not. Why: x is in P ⊕ K
//                     exactly when the convex set x - K meets P; either it lies inside P, and
//                     then x - k does, or, being connected, it meets P's boundary, some T;
//                     and T ⊕ K is convex, the hull of its vertices' sums. So no convex
//                     decomposition of P is needed, which OpenSCAD gets from CGAL;
//   P ⊕ Q, neither    (P + q_j) ∪ (Q + p_i) ∪ ⋃_{T,S} hull(T ⊕ S) over the triangles T of P's
//     convex          boundary and S of Q's, with p_i a vertex of each connected sheet of P's
//                     boundary and q_j of Q's. Why: for x in P ⊕ Q take a connected piece Q_j
//                     of Q with x - Q_j meeting P: either x - Q_j lies in P (x is in P + q_j)
//                     or some q of Q_j has x - q on a triangle T of P's boundary, so x is in
//                     T ⊕ Q_j = (Q_j + t) ∪ ⋃_S hull(T ⊕ S) by the construction above (K = T,
//                     t in T). Along the connected sheet C that holds t, either x - C lies in
//                     Q_j (x is in Q_j + p_C) or some c of C has x - c on Q's boundary, in a
//                     hull T' ⊕ S. Again no convex decomposition, at |∂P| |∂Q| hulls;
//   P ⊕ ball(c, r)    the exact rounded solid, no faceting of the ball: by the same argument
//                     (P + c) ∪ ⋃_T (T ⊕ ball), and T ⊕ ball is the prism T ± r n with a
//                     cylinder of radius r along each edge and a ball at each corner. Edges
//                     between coplanar triangles need no cylinder (both prisms cover it).
#pragma once

#include <optional>
#include <span>
#include <string>
#include <vector>

#include "csg/Tree.h"
#include "csg/mesh/TriangleMesh.h"

namespace csg {

// The convex hull of every a + b, nullopt with why set when it has no volume.
std::optional<ConvexPolytope> hullOfSums(std::span<const Vec3> a, std::span<const Vec3> b,
                                         std::string& why);

// The leaves of ⋃_T hull(T ⊕ K) over boundary's triangles, for the convex K given by its
// vertices (flat hulls, of a flat K along a triangle's plane, are left out: they bound no
// volume and lie in the others' closure). The caller adds P + k.
std::vector<NodePtr> sumsOfBoundaryWithConvex(const TriangleMesh& boundary,
                                              std::span<const Vec3> convex, Tags tags);

// The leaves of ⋃_{T,S} hull(T ⊕ S) over the triangles T of a and S of b (flat hulls left
// out, as above). The caller adds the translates (sheetVertices).
std::vector<NodePtr> sumsOfBoundaries(const TriangleMesh& a, const TriangleMesh& b, Tags tags);

// One vertex of each connected sheet of the mesh (triangles joined at shared vertices), in the
// order of their first triangles.
std::vector<Vec3> sheetVertices(const TriangleMesh& mesh);

// The leaves of ⋃_T (T ⊕ ball(c, r)) over boundary's triangles, in boundary's frame: a prism
// per face (coplanar triangles joined across flat edges, one prism when the face is convex,
// else one per triangle), edge cylinders and corner balls. The caller adds P + c.
std::vector<NodePtr> sumsOfBoundaryWithBall(const TriangleMesh& boundary, const Vec3& center,
                                            double radius, Tags tags);

}  // namespace csg
