// A leaf of a CSG tree as a closed triangle mesh in a given frame, for the plane sections and
// shadows of csg/section/Projection.h. Polyhedral leaves give their own boundary, exactly (up
// to the rounding of mapping each vertex): a box's 12 triangles, a convex polytope's faces
// (OpenSCAD's faceted cylinders and spheres), a polyhedron's triangles (polyhedron(), import(),
// surface(file)), and a linear_extrude of straight segments by the even-odd rule with no twist
// and one scale for both axes (extruded polygon()s, and offset()s with --curves openscad) as
// its walls and fans over its caps. Built directly too, within the tolerance: an exact
// sphere, cylinder or torus as an inscribed polyhedron with the segment count that keeps every
// point of it within the tolerance of the surface, and such a linear_extrude of curved
// segments as the prism over their chords (the mesher's grid would give tens of times the
// triangles for the same bound). Every other leaf (a twisted or rotate_extrude, a nonzero
// outline, an algebraic surface, Bezier patches) is meshed by csgray's own mesher
// (csg/mesh/Tessellate.h) within the tolerance. Both say so (exact = false).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "primitives/Primitives.h"
#include "primitives/base/Bounds.h"

namespace csg {

struct WorldMesh {
    std::vector<Vec3> vertices;
    // Corner indices; winding is not used (sections and shadows go by crossing parity and by
    // covered area).
    std::vector<std::array<uint32_t, 3>> triangles;
    // Planar faces: face k is triangles [faceStarts[k], faceStarts[k + 1]), and it is the
    // even-odd sum of those (a fan over a concave cap overlaps itself). Empty: every triangle
    // is a face of its own.
    std::vector<uint32_t> faceStarts;
    Bounds3 box;         // of the vertices
    bool exact = true;   // the leaf's own boundary, not a mesh of it
    double error = 0.0;  // when not exact: the bound (inscribed) or the mesher's measurement
};

// The leaf's boundary in the frame where worldFromLocal puts it. A leaf that is not polyhedral
// is meshed within `tolerance` (world units, > 0). Throws std::invalid_argument for a leaf that
// has no bounded solid to mesh (a half-space, a 2-D shape's infinite prism).
WorldMesh leafMesh(const Primitive& shape, const Mat4& worldFromLocal, double tolerance);

// Whether leafMesh() gives the leaf's own boundary (no meshing).
bool isPolyhedral(const Primitive& shape);

}  // namespace csg
