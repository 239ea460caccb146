// Solids that touch along an edge or at a point without sharing volume (a disc's corner against
// a flat wall, two cubes meeting at an edge) have an exact boundary whose edge there bounds four
// triangles, or whose vertex is the apex of two cones: no mesh that keeps one vertex per position
// is a 2-manifold there. The sheets are told apart instead, as Manifold's and CGAL's meshes do:
// around such an edge each solid wedge is closed by its own pair of triangles, and a vertex gets
// one copy per fan of triangles that those pairs and the ordinary edges connect. The sheets then
// meet only in contact (coincident edges and vertices), which is no self-intersection
// (MeshCheck.h), and every edge bounds two triangles.
#pragma once

#include <cstdint>

#include "csg/mesh/TriangleMesh.h"

namespace csg {

// Separates the touching sheets of a closed, outward-oriented triangle mesh in place: each edge
// used by 2k > 2 triangles is split into k edges, pairing the triangles by their order around it
// (the triangle at which the ray turning about the edge enters solid with the one where it
// leaves); each vertex whose triangles fall into several fans is copied once per further fan
// (positions and normals copied, triangles re-indexed). An edge whose triangles do not alternate
// between entering and leaving (an odd count, a hole, a misoriented neighbour, a face folded onto
// another) is left as it is, and so is a mesh with a triangle that repeats a corner, for
// checkTopology to report. Returns the number of vertices added.
uint64_t separateTouchingSheets(TriangleMesh& mesh);

// Whether the mesh is a closed, consistently oriented 2-manifold (checkTopology), its touching
// sheets separated first where it is not.
bool closedOnceSheetsSeparated(TriangleMesh& mesh);

}  // namespace csg
