// Coarsening a dual-contoured mesh where the surface is flat or gently curved: the uniform grid
// puts a fan of triangles on every crossed grid edge, so a box face of n x n cells carries
// ~4 n^2 triangles that all lie in one plane.
//
// Halfedge collapses on an OpenMesh mesh, in the order OpenMesh's decimater makes them
// (Decimate.h): a collapse moves one vertex onto a neighbour, so every kept vertex is one of the
// input's (exact crossings and QEF feature points stay where dual contouring put them). A
// collapse is allowed only when
//   - OpenMesh's link condition holds (the mesh stays a closed 2-manifold),
//   - the kept vertex is within maxDeviation of every plane of the input triangles merged into
//     it (Garland-Heckbert quadrics, unweighted: a sum of squared plane distances bounds each
//     one, so a crease or corner cannot be cut),
//   - the removed vertex is within maxDeviation of the triangles that replace its fan,
//   - no triangle of the fan turns by more than tol::kSimplifyMaxFanTurnCos (no fold-overs),
//   - the removed vertex touches triangles of one material only (material borders stay).
// Collapses go cheapest first (quadric error, then edge length, so flat regions coarsen
// evenly). A mesh of a few hundred thousand triangles or more is first cut into slabs
// (how many depends on the mesh only) decimated in parallel, each with the vertices on and next to
// its borders locked (so every collapse a slab makes sees the whole mesh's fans, rings and
// quadrics), and then decimated as a whole, which coarsens the border strips: the same rules hold,
// the collapse order differs from one piece's. The result is checked by the caller against the
// exact surface (Tessellate.cpp): these rules bound the deviation from the *input mesh* locally,
// not the distance to the part.
#pragma once

#include <cstdint>

#include "csg/mesh/TriangleMesh.h"

namespace csg {

struct SimplifyStats {
    uint64_t trianglesBefore = 0;
    uint64_t trianglesAfter = 0;
    bool built = false;  // false: OpenMesh refused a face (the input is not manifold); unchanged
    // Wall seconds of the phases: building the mesh structure, collapsing, extracting the result.
    double buildSeconds = 0.0, decimateSeconds = 0.0, extractSeconds = 0.0;
    // A big mesh is decimated in blocks first: how many, the wall seconds that took (part of
    // decimateSeconds) and the triangles left for the pass over the whole mesh. 0: one piece.
    int blocks = 0;
    double blocksSeconds = 0.0;
    uint64_t trianglesAfterBlocks = 0;
};

// The simplified mesh; normals and materials of kept vertices and triangles are carried over.
// maxDeviation <= 0 or an empty mesh returns the input unchanged. threads: workers for the
// slabs (0: all cores); the result does not depend on it.
TriangleMesh simplify(const TriangleMesh& mesh, double maxDeviation, SimplifyStats* stats = nullptr,
                      int threads = 0);

}  // namespace csg
