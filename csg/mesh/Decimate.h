// One piece of a mesh decimated by halfedge collapses, cheapest first, under the rules of
// Simplify.h: the decimation loop of simplify(), which cuts a big mesh into pieces and calls
// this on each, then on the whole.
#pragma once

#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
// QuadricT.hh uses vector_traits without including it: after the mesh header.
#include <OpenMesh/Core/Geometry/QuadricT.hh>

#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "primitives/base/Math.h"

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

// What a collapse may do besides the deviation rules.
struct CollapseLimits {
    double maxDeviation = 0.0;  // world units (Simplify.h)
    // Refuse a collapse that makes a triangle of its new fan cross or overlap another triangle
    // of the piece (MeshCheck.h triangleContact with these tolerances, world units). Off when
    // contactTol <= 0.
    double contactTol = 0.0, flatTol = 0.0;
    // Triangles outside the piece that do not change while it is decimated and that its new
    // triangles must not cross or overlap either (when contactTol > 0): the near triangles of
    // the neighbouring slabs (Simplify.cpp).
    std::vector<std::array<Vec3, 3>> obstacles;
};

struct DecimateStats {
    uint64_t collapses = 0;
    uint64_t refusedCrossing = 0;  // collapses refused because their fan would cross a triangle
};

// Decimates a piece in place: the kept vertices (in their order, with their merged quadrics)
// and the triangles left. False when OpenMesh refuses a face (a piece that is not a 2-manifold
// with boundary); the piece is then unchanged. stats, when given, is added to.
bool decimate(Piece& piece, const CollapseLimits& limits, DecimateStats* stats = nullptr);

}  // namespace csg
