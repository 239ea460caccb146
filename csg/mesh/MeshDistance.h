// Sampled one-sided distances between a mesh and the exact surface of a scene. Mesh to surface
// is measured by casting lines (the surface is known only through its spans): the distance
// along any line from a point to a surface bounds the Euclidean distance from above, so each
// figure is an upper bound at its sample. Surface to mesh is the Euclidean distance from exact
// surface points to the nearest triangle. Either maximum is a lower bound of the true one-sided
// Hausdorff distance only in that it is sampled.
#pragma once

#include <cstdint>

#include "csg/Scene.h"
#include "csg/mesh/Distribute.h"
#include "csg/mesh/TriangleBvh.h"
#include "csg/mesh/TriangleMesh.h"

namespace csg {

struct DistanceStats {
    uint64_t samples = 0;
    double max = 0.0;  // world units; +inf when some sample found nothing within reach
    double mean = 0.0;
    Vec3 worst{0.0};  // the sample point of max
    // Samples with nothing within reach: mesh to surface, no crossing along any direction;
    // surface to mesh, no triangle.
    uint64_t unresolved = 0;
};

struct DistanceOptions {
    // Lines reach this far on each side of a sample (world units); surface to mesh, the
    // nearest triangle is searched this far. Farther surfaces count as unresolved (distance
    // +inf).
    double reach = 1.0;
    // Mesh to surface only: the tolerance the figures will be judged against (world units).
    // Within tol::kDistanceFirstLineFraction of it, the first line's answer is taken; above, the
    // three axes and four body diagonals are tried as well and the smallest answer kept (a sample
    // near a crease whose normal line runs almost along the surface), and a sample whose answer
    // could still be the maximum is tightened (lines along the surface normal where its best
    // line met the surface, then a fan of 64 lines): the maximum is as tight as if every such
    // sample had been, the mean is not.
    double goodEnough = 0.0;
    int threads = 0;
    // The processes of a job that share the samples (csg/mesh/Distribute.h); null: this one.
    const ItemDistributor* distribute = nullptr;
};

// Mesh to surface: every triangle's centroid, every vertex (from the first triangle that has it)
// and every edge's midpoint (once, from the triangle that runs the edge from its lower vertex
// index; a boundary edge run the other way is not sampled), measured first along that
// triangle's normal. Vertices and midpoints are sampled tol::kDistanceSampleInset of the way
// towards the triangle's centroid: on the mesh, but off the part's edges the mesh may follow.
DistanceStats meshToSurface(const Scene& scene, const TriangleMesh& mesh,
                            const DistanceOptions& options);

// Surface to mesh: exact surface points from a grid of raysPerAxis^2 lines along each axis
// through the scene's bounds, each at its Euclidean distance from the mesh (the BVH's nearest
// triangle within options.reach).
DistanceStats surfaceToMesh(const Scene& scene, const TriangleBvh& bvh, int raysPerAxis,
                            const DistanceOptions& options);

}  // namespace csg
