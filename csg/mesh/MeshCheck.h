// Topological and integral checks of a triangle mesh: is it a closed, consistently oriented
// 2-manifold, and what volume and area does it enclose.
#pragma once

#include <cstdint>

#include "csg/mesh/TriangleMesh.h"

namespace csg {

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
double signedVolume(const TriangleMesh& mesh);
double surfaceArea(const TriangleMesh& mesh);

// Merges vertices with bit-identical positions (what STL and per-material glTF primitives need
// before their topology can be checked). Normals and materials are kept per triangle/vertex.
TriangleMesh weldExactDuplicates(const TriangleMesh& mesh);

}  // namespace csg
