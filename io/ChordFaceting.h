// A part's exact spheres and cylinders (cones too) replaced by polytopes whose faces stand at most
// a given distance off the exact surface in world units: the faceting an export to a tolerance
// needs, sized by each curve's own radius, not by OpenSCAD's $fa and $fs. A sphere or cylinder gets
// OpenSCAD's vertex layout, inscribed or balanced (csg::FacetFit: scaled out so that its vertices
// stand as far outside the curve as its faces stand inside, half the inscribed polytope's distance
// for the same fragments). linear_extrudes and rotate_extrudes become prisms, slices and
// revolutions of their outlines' chords within the same distance (io/ExtrusionMesh.h; the chords
// inscribed, a twisted or unevenly scaled extrusion's slices too, a revolution's steps balanced
// with the fit), and a torus the revolution of its tube's circle. The result is all polyhedra when
// nothing else is curved, so it has an exact boundary (csg/mesh/PolyhedralBoundary.h) that is the
// part to within that distance.
#pragma once

#include <functional>
#include <optional>

#include "csg/Scene.h"
#include "csg/Tree.h"
#include "csg/mesh/Tessellate.h"

namespace io {

// The tree with every sphere, cylinder, torus, linear_extrude and rotate_extrude leaf faceted so
// that no face stands more than `deviation` (world units, > 0) off the exact surface, or nullptr
// when a leaf stays curved (a surface, Bezier patches, an extrusion extrusionMesh declines) or a
// curve would need more faces than a polytope may have. Spheres and cylinders get OpenSCAD's
// vertices (io/Faceting.h), inscribed, or balanced: scaled out by 2 / (1 + c), c the nearest face's
// distance over the radius. Each gets the fewest fragments whose faces stand within the deviation
// at the leaf's largest world scale. When the tree is mixedCurvature, the leaves curved one way
// only are faceted to oneWayShare times the deviation.
csg::NodePtr facetToDeviation(const csg::NodePtr& root, double deviation, csg::FacetFit fit,
                              double oneWayShare = 1.0);

// Whether the tree has leaves curved both ways (spheres, tori, twisted extrusions, revolutions of
// outlines with curves) and leaves curved one way only (cylinders and cones, untwisted
// extrusions of outlines with curves, revolutions of straight-edged ones):
// CurveFaceter::mixedCurvature.
bool mixedCurvature(const csg::NodePtr& root);

// TessellateOptions::facetCurves for the part whose tree is root: facetToDeviation, compiled,
// and whether the tree is mixedCurvature.
csg::CurveFaceter curveFaceter(csg::NodePtr root);

}  // namespace io
