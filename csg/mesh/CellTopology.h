// The combinatorics of one grid cell for manifold dual contouring, computed from the signs
// of its 8 corners alone.
//
// Corner c of a cell sits at offset (c & 1, (c >> 1) & 1, (c >> 2) & 1). Edge 4a + ob + 2oc
// runs along axis a from the corner with offsets ob on axis b = a+1 and oc on axis c = a+2
// (mod 3). A face carries 0, 2 or 4 sign-changing edges. Two edges on a face are *paired*
// when one surface curve on that face joins them: the only two, or, on an ambiguous face
// (4 edges, inside corners diagonal), the two edges meeting at the same inside corner
// ("inside corners are separated", one rule for both cells sharing the face). Every
// sign-changing edge lies on two faces of the cell and so has two partners: the pairs form
// disjoint cycles, one per surface sheet in the cell. Each cycle becomes one mesh vertex, so a
// cell crossed by two sheets gets two vertices and the mesh stays manifold.
#pragma once

#include <array>
#include <cstdint>

namespace csg {

struct CellCycles {
    int count = 0;  // sheets through the cell
    // Cycle of each edge, -1 when the edge has no sign change.
    std::array<int8_t, 12> edgeCycle{};
    bool ambiguousFace = false;  // a face whose inside corners are only diagonal
};

// The cycles of a cell whose corners' inside bits are mask (bit c = corner c inside).
// Table lookup, built once on first use.
const CellCycles& cellCycles(uint8_t mask);

// Whether a face's inside corners are exactly one diagonal pair (cornerInside as for
// faceSegment below): the face then carries two curves, one around each inside corner.
bool faceIsAmbiguous(const std::array<bool, 4>& cornerInside);

// The partner of a sign-changing edge on one face, in face-local terms. A face perpendicular
// to axis f has in-plane axes u = f+1 and v = f+2 (mod 3) and corners (du, dv) in {0,1}^2;
// cornerInside[du + 2 dv]. A face edge is named by its axis (0 = along u, 1 = along v) and its
// offset on the other in-plane axis. Returns the segment index on the face (0 or 1; 1 only on
// ambiguous faces, for the curve around the inside corner with du = 1), the same whichever
// cell asks.
int faceSegment(const std::array<bool, 4>& cornerInside, int edgeAxis, int edgeOffset);

}  // namespace csg
