// OpenSCAD's 2-D shapes as the language keeps them: a CSG tree whose leaves are Plane
// extrusions (primitives/Extrusion.h), infinite prisms over outlines, so that 2-D union,
// difference and intersection are the ordinary tree operators. Transforms are baked into the
// outlines (a 2-D node never carries a matrix), and extruding lifts every leaf in place.
#pragma once

#include <functional>
#include <memory>
#include <optional>

#include "csg/Tree.h"

namespace io {

// 2 for a 2-D shape, 3 for a solid, 0 for the empty shape (a null node).
int dimensionOf(const csg::NodePtr& node);

// The shape under the x-y part of m, as OpenSCAD applies a transform to 2-D geometry (its
// z rows and columns are dropped).
csg::NodePtr transformed2D(const csg::Mat4& m, const csg::NodePtr& shape);

// The boundary of a shape's booleans (csg::boundaryOf) chained into closed contours
// (csg::contoursOf) as one outline: outer contours counter-clockwise, holes clockwise, never
// crossing, filled by the nonzero rule; nullopt when the boundary does not chain. approximated:
// elliptic arcs or Beziers became chords within tol::kFlattenRel of the shape's size.
struct BoundaryOutline {
    std::shared_ptr<csg::Outline> outline;
    bool approximated = false;
};
std::optional<BoundaryOutline> boundaryOutline(const csg::Node& shape);

// The shape as one leaf whose outline is the boundary of its booleans (csg::contoursOf), as
// OpenSCAD unions an extrusion's children before extruding them: the twisted extrusion then
// finds a line's pieces once, not once per leaf. The shape itself when it is one leaf already,
// or when its boundary would have to replace elliptic arcs or Beziers by chords; nullptr when
// it has no area.
csg::NodePtr unitedShape(const csg::NodePtr& shape);

// The shape with every leaf replaced by lift(leaf); the tree's operators and tags stay.
csg::NodePtr liftLeaves(const csg::NodePtr& shape,
                        const std::function<csg::Extrusion(const csg::Extrusion&)>& lift);

}  // namespace io
