// Topological and integral checks of a triangle mesh: is it a closed, consistently oriented
// 2-manifold, and what volume and area does it enclose.
#pragma once

#include <cstdint>

#include "csg/mesh/TriangleMesh.h"

namespace csg {

class TriangleBvh;

struct MeshTopology {
    uint64_t edges = 0;                // distinct undirected edges
    uint64_t boundaryEdges = 0;        // used by one triangle: a hole
    uint64_t nonManifoldEdges = 0;     // used by three or more triangles
    uint64_t misorientedEdges = 0;     // used twice in the same direction (neighbours disagree)
    uint64_t nonManifoldVertices = 0;  // triangles around the vertex form more than one fan
    uint64_t degenerateTriangles = 0;  // a repeated corner index

    // Every edge shared by exactly two triangles in opposite directions, every vertex a disk.
    bool closedManifold() const {
        return boundaryEdges == 0 && nonManifoldEdges == 0 && misorientedEdges == 0 &&
               nonManifoldVertices == 0 && degenerateTriangles == 0;
    }
};

// Edges are compared by vertex index, so a mesh whose seams repeat positions under different
// indices (an STL soup before welding) shows those seams as boundary edges.
MeshTopology checkTopology(const TriangleMesh& mesh);

// Signed volume by the divergence theorem, sum over triangles of p0 . (p1 x p2) / 6: positive
// for a closed mesh oriented outward, meaningful only when the mesh is closed.
struct SelfIntersections {
    uint64_t pairs = 0;           // triangle pairs that cross or overlap
    uint64_t coplanarPairs = 0;   // of these, coplanar pairs whose interiors overlap
    uint64_t skippedSlivers = 0;  // triangles thinner than the contact tolerance, not tested
    // On the crossing of the first pair in triangle order (deterministic), when pairs > 0.
    Vec3 example{0.0};
    uint32_t exampleA = 0, exampleB = 0;  // that pair's triangle indices
};

// Pairs of triangles that intersect other than where they share vertices (bit-identical
// positions count as shared, so an unwelded soup works too), with a contact tolerance tol =
// contactRel times the largest coordinate magnitude (primitives/base/Tolerances.h,
// kSelfIntersectionContactRel). Counted: crossings, where each triangle has corners more than
// tol beyond the other's plane on both sides and their segments on the line where the planes
// meet overlap by more than tol (also through a shared vertex); coplanar pairs (one triangle
// within tol of the other's plane) whose interiors overlap by more than tol (duplicates, faces
// folded flat onto a neighbour). Not counted: contacts (a vertex on a face, an edge along a
// face or an edge, a corner through the other's plane by tol or less) and pairs sharing an edge
// that are not coplanar (they meet only along it). Triangles whose height is within tol are
// slivers without a reliable plane, skipped and counted. Uses `threads` threads (0: all cores).
SelfIntersections findSelfIntersections(const TriangleMesh& mesh, double contactRel,
                                        int threads = 0);
SelfIntersections findSelfIntersections(const TriangleMesh& mesh);
// The same, reusing a BVH over mesh: its build is a fair share of the check on big meshes, and
// compare needs the same BVH for surface->mesh (bench/README.md, 4a2606e).
SelfIntersections findSelfIntersections(const TriangleMesh& mesh, const TriangleBvh& bvh,
                                        double contactRel, int threads = 0);

// findSelfIntersections' contact tolerance for mesh: contactRel times its largest coordinate
// magnitude (world units).
double selfIntersectionTolerance(const TriangleMesh& mesh, double contactRel);

// A triangle as findSelfIntersections tests it: corners in winding order and unit normal, zero
// for a sliver (height over its longest edge within the contact tolerance), which is not tested.
struct ContactTriangle {
    Vec3 p[3];
    Vec3 n;
};
ContactTriangle contactTriangle(const Vec3& p0, const Vec3& p1, const Vec3& p2, double tol);

// How two triangles meet, by findSelfIntersections' rules with contact tolerance tol (world
// units): crossing, overlapping coplanar, or neither (apart, a contact, sharing an edge without
// being coplanar, or one of them a sliver). A triangle within flatTol (world units) of the
// other's plane counts as coplanar; findSelfIntersections uses flatTol = tol, and a larger one
// makes a stricter test, for a pair that must also pass findSelfIntersections after rounding
// (see kUnfoldCheckMargin).
enum class TriangleContact { None, Crossing, Coplanar };
TriangleContact triangleContact(const ContactTriangle& a, const ContactTriangle& b, double tol,
                                double flatTol);

double signedVolume(const TriangleMesh& mesh);
double surfaceArea(const TriangleMesh& mesh);

// Merges vertices with bit-identical positions (what STL and per-material glTF primitives need
// before their topology can be checked). Normals and materials are kept per triangle/vertex.
TriangleMesh weldExactDuplicates(const TriangleMesh& mesh);

}  // namespace csg
