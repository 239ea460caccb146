// One piece of a mesh decimated by halfedge collapses, cheapest first, under the rules of
// Simplify.h: the decimation loop of simplify(), which cuts a big mesh into pieces and calls
// this on each, then on the whole.
#pragma once

#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
// QuadricT.hh uses vector_traits without including it: after the mesh header.
#include <OpenMesh/Core/Geometry/QuadricT.hh>

#include <array>
#include <cstdint>
#include <vector>

#include "csg/Math.h"

namespace csg {

using Quadric = OpenMesh::Geometry::Quadricd;

// A part of the mesh to decimate: its vertices (positions, quadrics, locks, where each came from)
// and triangles (local vertex indices, materials).
struct Piece {
    std::vector<Vec3> positions;
    std::vector<Quadric> quadrics;
    std::vector<uint8_t> locked;
    std::vector<uint32_t> source;  // the input's vertex index
    std::vector<std::array<uint32_t, 3>> triangles;
    std::vector<uint32_t> materials;
};

// Decimates a piece in place: the kept vertices (in their order, with their merged quadrics)
// and the triangles left. False when OpenMesh refuses a face (a piece that is not a 2-manifold
// with boundary); the piece is then unchanged. maxDeviation: world units (Simplify.h).
bool decimate(Piece& piece, double maxDeviation);

}  // namespace csg
