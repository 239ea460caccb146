// The point of a triangle nearest a point: the mesh distance of export (csg/mesh) and the
// choice among a mesh primitive's candidate faces (primitives/Polyhedron.cpp).
#pragma once

#include "primitives/base/Math.h"

namespace csg {

// The point of triangle (a, b, c) nearest p (of a triangle of zero area: of its edges).
Vec3 closestPointOnTriangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c);

}  // namespace csg
