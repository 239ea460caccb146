// Shading normals for a mesh with sharp edges: a vertex on a crease (a box edge, a hole's rim)
// is split into one vertex per smooth group of the triangles around it, each with that group's
// normal, so viewers shade box faces flat and spheres smooth (what "auto smooth" does in most
// tools). Positions are copied bit for bit, so welding by position gives back the closed mesh.
#pragma once

#include "csg/mesh/TriangleMesh.h"
#include "primitives/base/Tolerances.h"

namespace csg {

// Triangles around a vertex that are joined through edges whose dihedral angle is at most
// creaseDegrees (callers pass tol::kShadingCreaseDegrees) share one output vertex. Its normal is
// the input normal when the vertex has a single group and one was given (the exact surface
// normal for crossing vertices), else the angle-weighted mean of the group's triangle normals.
// Triangle order and materials are kept.
TriangleMesh splitAtCreases(const TriangleMesh& mesh, double creaseDegrees);

}  // namespace csg
