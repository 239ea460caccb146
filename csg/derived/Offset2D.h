// offset() of a 2-D shape, exactly: the shape R grown or shrunk by what lies within a distance
// of its boundary (csg/derived/Boundary2D.h), on one side:
//   r > 0       R  u  band        band = points within r of the boundary, outside R
//   r < 0       R  -  band        band = points within |r| of the boundary, inside R
// The band is a union of simple pieces, each a closed counter-clockwise curve, so outlines
// with the nonzero rule hold their union exactly and no two of them need be intersected:
//   a straight piece    the rectangle it sweeps along its normal (on the band's side)
//   a circular piece    the annular sector it sweeps radially (a sector and its mirror through
//                       the centre where the band reaches past the centre)
//   a vertex (round)    the disc about it
//   a corner (delta)    Clipper's miter: the kite between the two normals and the point where
//                       the two moved edges meet, only at corners the band turns round
//                       (convex ones growing, reflex ones shrinking); with chamfer, the kite cut
//                       by the line perpendicular to the corner's bisector at the distance.
// A point of the band is within the distance of the boundary and every such point on the
// band's side is in some piece: its nearest boundary point is a vertex or lies on a piece
// along its normal. So the result is exact where the boundary is (lines and circles).
#pragma once

#include <cstdint>
#include <vector>

#include "csg/derived/Boundary2D.h"

namespace csg {

enum class OffsetJoin : uint8_t { Round, Miter, Chamfer };

// The band of the offset by `distance` (> 0 outward, < 0 inward, see above) as the union of
// nonzero outlines of a few dozen segments each (a BVH culls them for a ray); none when the
// boundary has none or the distance is 0.
std::vector<Outline> offsetBand(const Boundary2D& boundary, double distance, OffsetJoin join);

}  // namespace csg
