// The exact boundary of a part whose leaves are all polyhedra: boxes, OpenSCAD's faceted
// cylinders and spheres (ConvexPolytope), polyhedron() and imported meshes. Such a part is a
// polyhedron itself, so its mesh can be the part, not an approximation of it: this is what
// OpenSCAD and Manifold write for it, and what a uniform grid can only approach at the cost of
// millions of triangles.
//
// Boundary evaluation by classification (Requicha's method, with the ray caster as the
// classifier):
//   1. Every face of every leaf is cut, as a convex polygon in its plane, where the other leaves'
//      boundaries cross it. A convex leaf (a box, a polytope) cuts by its section, the convex
//      polygon its face planes leave in that plane: a piece the section's interior meets is split
//      into the part inside and one part outside each of the section's edges. A mesh leaf cuts by
//      the lines where its faces meet the plane (a face that crosses or touches it gives one line;
//      a coplanar face gives the lines of its edges). Only leaves with a face whose box overlaps
//      are looked at.
//   2. A piece is kept when the line through its middle along the face's normal has a span end
//      on that very face (leaf and face id): the CSG merge then says that the piece bounds the
//      part and which way it faces (a span's entry faces back along the line, its exit forward),
//      and where faces of two leaves coincide it keeps exactly one of them: a span end on any
//      coincident face facing the same way counts (the merge names one of them, by a rounding
//      that may change from line to line), and the lowest of those leaves keeps the piece. A
//      face keeps nothing outside its leaf's reach (Scene::leafReach), and a coincident face
//      counts only within its own: outside it, the face was not cut by what lies there.
//   3. Vertices closer than tol::kPolyBoundaryWeldRel of the part's size are welded, and a vertex
//      that lies on another piece's edge is inserted into that edge (no T-junctions).
//   4. The pieces of each face are merged back into one polygon with holes, vertices on straight
//      edges dropped, and triangulated by ear clipping (CoplanarMerge.h). Where a face's outline
//      touches itself, the pieces are triangulated one by one and merged by the simplifier
//      instead, moving no vertex off its plane by more than the weld distance.
// The result must be a closed, consistently oriented manifold (MeshCheck.h); a part where it is
// not (faces meeting in a way the cuts did not resolve) gets no mesh here and the caller falls
// back to the grid.
#pragma once

#include <cstdint>
#include <optional>

#include "csg/Scene.h"
#include "csg/mesh/Distribute.h"
#include "csg/mesh/TriangleMesh.h"

namespace csg {

struct PolyhedralBoundaryStats {
    uint64_t faces = 0;       // leaf faces
    uint64_t pieces = 0;      // after the cuts
    uint64_t kept = 0;        // pieces on the boundary
    uint64_t tJunctions = 0;  // vertices inserted into edges
    uint64_t trianglesBeforeMerge = 0;
    // Wall seconds: cutting and classifying the faces; welding, closing T-junctions and
    // triangulating; merging the pieces of each face (the simplifier) and checking the result.
    double classifySeconds = 0.0, assembleSeconds = 0.0, mergeSeconds = 0.0;
    // Wall seconds of measuring the result both ways (set by tessellate(), not here).
    double measureSeconds = 0.0;
    // What merged the pieces of each face: "faces" (CoplanarMerge.h), "the simplifier" where a
    // face's outline touches itself, or "nothing".
    const char* mergedBy = "nothing";
    // Why no mesh was made (nullptr when one was): a leaf that is not a polyhedron, or a result
    // that is not a closed manifold.
    const char* declined = nullptr;
};

// Whether this method takes the leaf: a box, a polytope or a polygon mesh.
bool polyhedralLeaf(const Primitive& p);
// Whether every leaf of the scene is a polyhedron this method takes.
bool allLeavesPolyhedral(const Scene& scene);

// The part's exact boundary as a closed, outward-oriented triangle mesh (no normals; materials
// per triangle from the leaves' tags), or nothing when the part is not all polyhedra or the
// result would not be a closed manifold. threads: 0 for all cores. With `distribute`, the faces
// are cut and classified on the processes of a job (csg/mesh/Distribute.h: the same mesh on
// every one).
std::optional<TriangleMesh> polyhedralBoundary(const Scene& scene, int threads,
                                               PolyhedralBoundaryStats* stats = nullptr,
                                               const ItemDistributor* distribute = nullptr);

}  // namespace csg
