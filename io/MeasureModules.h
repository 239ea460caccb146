// The modules whose result depends on their children's evaluated solid, not only on their
// tree: projection() and resize(). Both measure the children through csg/section/Projection.h.
//
// projection(cut = false | true, convexity): the 2-D shape (one Plane extrusion leaf, shape
// "projection") of the 3-D children's shadow on z = 0 (cut = false) or of their closed section
// by z = 0 (cut = true: a face lying in z = 0 counts, as in OpenSCAD). What is exact:
//   - cut = true of any tree whose leaves are polyhedral (cube, OpenSCAD's faceted spheres and
//     cylinders, polyhedron(), import(), surface(file)): the leaves' own faces cut by the plane,
//     combined by the tree's booleans on Clipper's integer grid of 2^-50 of the part's extent;
//   - cut = false of such a tree: unions of leaf shadows (projected triangles), and for an
//     intersection or difference the projections of the leaves' faces cut by the subtree's
//     section in each face's plane, unless that costs more than csg::kMaxFaceWork (then the
//     subtree is meshed as a whole, as below).
// What is approximate: a leaf that is not polyhedral is first made a closed mesh within
// csg::tol::kLeafMeshToleranceRel (5e-4) of its bounds' diagonal: an exact sphere, cylinder or
// torus an inscribed polyhedron of enough segments, any other (an extrusion, an algebraic surface,
// patches) csgray's mesher's grid mesh; the outline is then within that distance of the true
// section or shadow. info shows "accuracy" on such a leaf.
//
// resize(newsize, auto = false, convexity): OpenSCAD's scaling about the origin that takes the
// child's bounding box to newsize (0 or less keeps an axis; auto = true or [bx, by, bz] scales
// such an axis by the factor of the largest newsize). The box is the evaluated solid's: exact
// for unions of leaves, and for trees with an intersection or difference the bounds of their
// shadows along z and x (exact for polyhedral leaves). 2-D children: the bounds of their
// outlines, bottom-up (an intersection's overlap, a difference's first operand: an upper bound
// where a difference trims the box, where OpenSCAD would measure the trimmed shape).
#pragma once

#include "io/Evaluator.h"

namespace io {

Instance projectionModule(Evaluator& e, const InstantiationStmt& s, const ContextPtr& ctx,
                          const GeomState& state);
Instance resizeModule(Evaluator& e, const InstantiationStmt& s, const ContextPtr& ctx,
                      const GeomState& state);

}  // namespace io
