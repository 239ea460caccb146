// A part's exact spheres and cylinders (cones too) replaced by inscribed polytopes whose faces
// stand at most a given distance off the exact surface in world units: the faceting an export
// to a tolerance needs, sized by each curve's own radius (a chord of a circle of radius R with
// n fragments stands R (1 - cos(pi / n)) off it), not by OpenSCAD's $fa and $fs. Straight
// linear_extrudes and rotate_extrudes become prisms and revolutions of their outlines' chords
// within the same distance (io/ExtrusionMesh.h). The result is all polyhedra when nothing else is
// curved, so it has an exact boundary (csg/mesh/PolyhedralBoundary.h) that is the part to within
// that distance.
#pragma once

#include <functional>
#include <optional>

#include "csg/Scene.h"
#include "csg/Tree.h"

namespace io {

// The tree with every sphere, cylinder, straight linear_extrude and rotate_extrude leaf faceted so
// that no face stands more than `deviation` (world units, > 0) off the exact surface, or nullptr
// when a leaf stays curved (a torus, a surface, a twisted extrusion, an outline extrusionMesh
// declines) or a curve would need more faces than a polytope may have. Spheres and cylinders get
// OpenSCAD's vertices (io/Faceting.h), with the fragment count from the chord rule at the leaf's
// largest world scale.
csg::NodePtr facetToDeviation(const csg::NodePtr& root, double deviation);

// TessellateOptions::facetCurves for the part whose tree is root: facetToDeviation, compiled.
std::function<std::optional<csg::Scene>(double deviation)> curveFaceter(csg::NodePtr root);

}  // namespace io
