// The faces of a closed polygon mesh whose polygons are pieces of larger faces (the pieces the
// exact polyhedral boundary keeps, PolyhedralBoundary.h), merged back into those faces and
// triangulated with the fewest triangles their corners allow.
//   1. Pieces that share an edge, lie in one plane and carry one material are one face
//      (union-find over the shared edges).
//   2. A face's outline is its pieces' edges whose reverse lies in another face, chained into
//      loops: one outer loop and its holes.
//   3. A vertex that lies on a straight stretch of every outline it is on (within `straight` of
//      the segment between the corners around it) is dropped from all of them at once, so the
//      faces on both sides of an edge keep the same vertices and the mesh stays closed.
//   4. Each face is triangulated by ear clipping with holes (EarClip.h): V + 2H - 2 triangles for
//      V corners and H holes, with no vertex off the face's plane.
// This is what the general simplifier (Simplify.h) reached by collapsing edges, in a fraction of
// the time, and with fewer triangles: that one stops where a collapse would move the surface.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "csg/mesh/TriangleMesh.h"

namespace csg {

// polygons: corner loops (indices into positions), counter-clockwise seen from outside, every
// edge met by exactly one reversed edge (closed, no T-junctions); normals: one unit normal and
// materials: one material per polygon. straight: how far a vertex may stand off the segment
// between its neighbours and still be dropped. Returns the triangles, with only the positions
// they use (no normals), or nothing when the polygons are not closed, an outline does not chain
// into loops (a face that touches itself at a vertex), a face does not triangulate, or a face
// has more than a few thousand corners (ear clipping is quadratic in them).
std::optional<TriangleMesh> mergeCoplanar(const std::vector<Vec3>& positions,
                                          const std::vector<std::vector<uint32_t>>& polygons,
                                          const std::vector<Vec3>& normals,
                                          const std::vector<uint32_t>& materials, double straight);

}  // namespace csg
