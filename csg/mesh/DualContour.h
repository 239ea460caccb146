// Manifold dual contouring of tri-dexel Hermite data on a rectilinear grid (HermiteGrid.h).
//
// Vertices are of three kinds: one per sheet (cycle, see CellTopology.h) of each cell, placed
// by a QEF clamped to the cell (sharp corners and creases inside cells); one per crossed grid
// edge, the exact crossing point with its exact normal; and, where a surface curve on a cell
// face bends over a crease (or the face is ambiguous), one on that face where the crossings'
// tangent lines meet. Each crossed edge gets a fan of triangles around its crossing through the
// sheet vertices of its four cells and the face vertices between them. So the mesh is Marching
// Cubes' surface with each polygon fanned from its QEF vertex and each face curve bent at its
// crease: a closed 2-manifold (the polygons of MC with one face rule are), oriented outward,
// and every triangle lies inside one cell, so triangles of different cells never cross.
#pragma once

#include <cstdint>

#include "csg/mesh/HermiteGrid.h"
#include "csg/mesh/TriangleMesh.h"

namespace csg {

struct DualContourStats {
    uint64_t cells = 0;             // cells of the grid
    uint64_t activeCells = 0;       // cells with corners of both signs
    uint64_t sheetVertices = 0;     // QEF vertices (cells crossed by two sheets count twice)
    uint64_t faceVertices = 0;      // crease points on cell faces
    uint64_t missingCrossings = 0;  // sign changes whose ray saw no crossing (midpoint used)
    uint64_t thinEdges = 0;  // edges crossed more than once: thinner than a cell (HermiteGrid)
    Vec3 thinAt{0.0};        // one of them
};

// The mesh of the grid's surface; empty when no node is inside. Active cells are found and
// their sheet vertices placed on `threads` threads (0: all cores); the mesh is the same for any
// thread count.
TriangleMesh dualContour(const HermiteGrid& grid, DualContourStats* stats = nullptr,
                         int threads = 0);

}  // namespace csg
