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
// and each triangle lies within the cells around its crossed edge.
//
// Fans can still cross where a cell's vertex sits badly, and the crossings found (MeshCheck.h's
// findSelfIntersections on csg_grid, csg_grid3 and random CSG) were all between triangles
// around the sheet vertices of one cell: a vertex clamped a hair inside a face whose fan folds
// flat onto that face, or two sheets of one cell (a wall thinner than the cell) whose QEF
// vertices meet where the two sheets' planes do. So, last, each cell whose vertices' triangles
// cross or overlap moves its vertices toward the mass points of their crossings, just far
// enough (UnfoldVertices.h; DualContourStats::unfoldedCells). On an ambiguous face the two
// curves' crease points are kept on their own corners' sides of the curves' chords, so they
// cannot cross each other. Vertices of merged blocks (below) are not moved: a block whose
// vertex's triangles cross or overlap, or next to a cell still folded at its mass points, is
// not merged in the next round instead.
//
// Adaptive (DualContourOptions::flatTolerance > 0): an octree over the cells in index space
// (Ju et al. 2002, "Dual contouring of Hermite data") merges blocks of 2^k x 2^k x 2^k cells,
// k <= kOctreeMaxLevel, that the surface crosses flat (one sheet, every sample's tangent plane
// within the tolerance of the block's one QEF vertex, normals in a narrow cone, every sample
// measured) and whose corner signs keep the topology (Ju's test: one sign change per block
// edge, face and block centres agreeing with a corner, no ambiguous face). Every cell of such
// a block uses the block's vertex. The fans are the same per crossed edge with that mapping,
// with no face vertex between two cells of one block; a ring with two distinct vertices or
// fewer (an edge inside a block, or inside a face between two blocks) gets no fan: it would be
// a pair of opposite triangles. The mesh is the image of the uniform one under merging
// vertices, so it stays closed and oriented as a chain. A ring may be fanned from one of its
// vertices instead of its crossing (same boundary; a ring of three becomes Ju's triangle)
// where the crossing's fan would fold. Where no fan fits, a vertex's triangles are not one
// disk, or they cross (above), the blocks there are forbidden and the contour is made again (at
// most kOctreeMaxRounds rounds, then the uniform contour: DualContourStats::octreeFallback).
// Triangles then span up to four blocks, so "one cell" above holds per block.
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
    uint64_t thinEdges = 0;       // edges crossed more than once: thinner than a cell (HermiteGrid)
    Vec3 thinAt{0.0};             // one of them
    uint64_t octreeLeaves = 0;    // merged blocks (each one vertex), see the header
    uint64_t octreeCells = 0;     // active cells inside them
    int octreeRounds = 0;         // contours made (each after one that folded at a block)
    bool octreeFallback = false;  // the merged mesh folded or was not a manifold: uniform used
    uint64_t unfoldedCells = 0;   // cells whose vertices moved off a fold (UnfoldVertices.h)
    uint64_t unfoldFailures = 0;  // cells left folded: at their crossings' mass points, or
                                  // found folded again after the last round of unfolding
};

// A merged block spans at most 2^kOctreeMaxLevel cells per axis (16): a block never reaches
// far past the surface it was measured on, and a top block's cells fit one worker's pass.
inline constexpr int kOctreeMaxLevel = 4;

// Rounds of merging before the uniform contour is used instead (DualContour.cpp's run()).
inline constexpr int kOctreeMaxRounds = 8;

struct DualContourOptions {
    int threads = 0;  // 0: all cores; the mesh is the same for any count
    // Largest distance of a merged block's vertex from any tangent plane in it (world units);
    // <= 0: no octree, every cell keeps its own vertices.
    double flatTolerance = 0.0;
};

// The mesh of the grid's surface; empty when no node is inside. Active cells are found and
// their sheet vertices placed on `threads` threads (0: all cores); the mesh is the same for any
// thread count.
TriangleMesh dualContour(const HermiteGrid& grid, DualContourStats* stats = nullptr,
                         int threads = 0);
TriangleMesh dualContour(const HermiteGrid& grid, const DualContourOptions& options,
                         DualContourStats* stats = nullptr);

}  // namespace csg
