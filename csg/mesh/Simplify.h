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
//   - the removed vertex touches triangles of one material only (material borders stay),
//   - no triangle of the new fan crosses or overlaps another triangle of the mesh as it is when
//     the collapse is made (MeshCheck.h triangleContact, the pair test of findSelfIntersections,
//     made stricter by tol::kUnfoldCheckMargin both ways so the result passes it also as
//     floats): the rules above look at the fan only, and a chord they allow may still cut
//     through the other side of a wall or gap thinner than the budget. The triangles near the
//     fan come from a grid of boxes kept up to date (BoxGrid.h); a refused collapse leaves the
//     vertex to its next best one.
// Collapses go cheapest first (quadric error, then edge length, so flat regions coarsen
// evenly). A mesh of a few hundred thousand triangles or more is first cut into slabs
// (how many depends on the mesh only) decimated in parallel, each with the vertices on and next to
// its borders locked (so every collapse a slab makes sees the whole mesh's fans, rings and
// quadrics; slabs that could come near each other run one after the other, each seeing the
// other's triangles), and then decimated as a whole, which coarsens the border strips: the same
// rules hold, the collapse order differs from one piece's. The result is checked by the caller
// against the exact surface (Tessellate.cpp): these rules bound the deviation from the *input
// mesh* locally, not the distance to the part.
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
    uint64_t collapses = 0;        // collapses made, blocks and whole pass
    uint64_t refusedCrossing = 0;  // collapses refused: a new triangle would cross another
};

// The simplified mesh; normals and materials of kept vertices and triangles are carried over.
// maxDeviation <= 0 or an empty mesh returns the input unchanged. threads: workers for the
// slabs (0: all cores); the result does not depend on it. refuseCrossings = false drops the
// crossing rule (for tests and benchmarks of what it costs and prevents; the collapses are then
// exactly those made before it existed).
TriangleMesh simplify(const TriangleMesh& mesh, double maxDeviation, SimplifyStats* stats = nullptr,
                      int threads = 0, bool refuseCrossings = true);

}  // namespace csg
