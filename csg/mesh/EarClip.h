// Triangulation of a polygon with holes in the plane by ear clipping, with no new vertices: a
// polygon of V corners and H holes becomes V + 2H - 2 triangles, the fewest its corners allow.
// Each hole is first joined to the outer loop by a bridge to a corner it can see (Eberly,
// "Triangulation by Ear Clipping", 2002: the hole's rightmost corner, a ray to the right, the
// nearest edge it meets and the reflex corners in the triangle that ray leaves), which makes one
// weakly simple loop; then ears are cut from that loop. O(n^2) in the corners: meant for the
// faces of a mesh, tens to a few thousand corners each.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "primitives/base/Math.h"

namespace csg {

// The signed area of the loop of points (indices into points): positive counter-clockwise.
double signedArea(std::span<const Vec2> points, const std::vector<uint32_t>& loop);

// Triangulates the region inside `outer` (indices into points, counter-clockwise) and outside
// every hole (clockwise loops inside it). An ear is cut only where its tip stands more than
// minHeight off the line through its neighbours, so corners that lie on a straight edge (within
// minHeight) stay corners and make no sliver. Appends counter-clockwise triangles of indices
// into points to out; false (out unchanged) when the loop cannot be cut to the end, as for
// loops that cross or a hole that is not inside.
bool earClip(std::span<const Vec2> points, const std::vector<uint32_t>& outer,
             const std::vector<std::vector<uint32_t>>& holes, double minHeight,
             std::vector<std::array<uint32_t, 3>>& out);

}  // namespace csg
