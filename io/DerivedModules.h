// offset(), hull() and minkowski(): shapes derived from their children (io/Offset.cpp,
// io/Hull.cpp, io/Minkowski.cpp; the geometry is csg/derived/'s).
#pragma once

#include "csg/derived/Offset2D.h"
#include "io/Evaluator.h"
#include "io/Faceting.h"

namespace io {

// offset(r | delta, chamfer = false) of 2-D children (../shared/OPENSCAD.md section 2): exact
// (lines and arcs of the result's boundary grown or shrunk, csg/derived/Offset2D.h), or, where
// the curve mode facets a circle of radius |r| with the call's $fn, $fa, $fs, OpenSCAD 2021's
// Clipper offset of the polygons (csg/derived/Clipper2D.h).
Instance offsetModule(Evaluator& e, const InstantiationStmt& s, const ContextPtr& ctx,
                      const GeomState& state);

// The exact offset of a 2-D shape: the shape with the band its boundary sweeps (lines and arcs,
// csg/derived/Offset2D.h) added (distance > 0) or cut away (< 0).
csg::NodePtr exactOffset(Evaluator& e, Loc loc, const csg::NodePtr& shape, double distance,
                         csg::OffsetJoin join, const csg::Tags& tags);

// hull() of 2-D children (exact: tangents to arcs) or 3-D children (qhull over the vertices
// of the children's result, curved solids faceted as OpenSCAD's).
Instance hullModule(Evaluator& e, const InstantiationStmt& s, const ContextPtr& ctx,
                    const GeomState& state);

// minkowski() of solids (io/Minkowski.cpp): exact with an exact sphere, else OpenSCAD's sum
// of the faceted children.
Instance minkowskiModule(Evaluator& e, const InstantiationStmt& s, const ContextPtr& ctx,
                         const GeomState& state);

// The points a leaf stands for in a 3-D hull or Minkowski sum, in its own frame: a polyhedral
// leaf's vertices; a sphere, cylinder, torus or extrusion faceted as OpenSCAD facets it with
// settings; false (nothing appended) for a leaf that has none (a twisted extrusion, a patch).
bool facetedLeafPoints(const csg::Primitive& p, const FragmentSettings& settings,
                       std::vector<csg::Vec3>& out);

}  // namespace io
