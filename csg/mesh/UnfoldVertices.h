// Local repair of a mesh's self-intersections by moving vertices toward safe points.
//
// Dual contouring's triangles around the sheet vertices of one cell (their stars) lie in that
// cell and its neighbours, and the crossings found on csg_grid, csg_grid3 and random CSG were
// all between two of them (DualContour.h): a vertex
// clamped into the cell a hair from a face, with its fan flattened onto that face and folded
// over itself there, or two sheets of one cell (a wall thinner than the cell, whose edges carry
// only the first of their two crossings) whose QEF vertices both land on the line where the
// two sheets' planes meet. The mass point of a sheet's crossings is the safe point: its fan is
// the Marching Cubes polygon fanned from its centroid, which lies well inside the polygon.
// Moving the vertex only part of the way keeps as much of the QEF's sharp feature as the fold
// allows.
#pragma once

#include <cstdint>
#include <vector>

#include "csg/mesh/TriangleMesh.h"

namespace csg {

// Steps of bisection between a folded group's positions (t = 0) and its safe points (t = 1): the
// group ends at a clean t within 2^-kUnfoldBisections of a folded one.
inline constexpr int kUnfoldBisections = 5;
// Rounds of checking the groups around moved vertices again (a move changes the triangles a
// neighbouring group's vertices share with the moved one).
inline constexpr int kUnfoldRounds = 4;

// Vertices first .. first + count - 1 of a mesh that move together (the sheet vertices of one
// cell: their stars share triangles).
struct UnfoldGroup {
    uint32_t first = 0;
    uint32_t count = 0;
};

struct UnfoldStats {
    uint64_t checkedGroups = 0;   // group checks, all rounds
    uint64_t pairwiseGroups = 0;  // of these, tested pair by pair (no quick certificate)
    uint64_t foldedGroups = 0;    // groups whose stars crossed (a group folded twice counts twice)
    uint64_t movedGroups = 0;     // of these, moved to a clean position
    uint64_t unresolvedGroups = 0;     // of these, still crossing at their safe points (left there)
    std::vector<uint32_t> unresolved;  // those groups (indices into the groups given), ascending
    uint64_t leftFoldedGroups = 0;     // found folded by the last round's checks, left as they are
};

// For each group, whether two triangles of the stars of its vertices (every triangle using one
// of them) cross or overlap (triangleContact, MeshCheck.h, for contact tolerance tol made
// stricter by tol::kUnfoldCheckMargin both ways, so the mesh passes findSelfIntersections with
// tol also after rounding to float). A group that does moves each vertex v from p to
// p + t (safe[v] - p), t in (0, 1] found by kUnfoldBisections steps of bisection between t = 0
// (folded) and t = 1 (clean); after a move, clean also means that no triangle of its stars
// crosses or overlaps one sharing a corner with them (a move may fold onto a neighbour's
// triangle that holds none of the group's vertices). If not clean at t = 1, the group stays at
// its safe points (counted unresolved, and not moved again). Then the groups sharing a triangle
// with a moved vertex are checked again, up to kUnfoldRounds rounds (those still folded after
// the last are not moved: leftFoldedGroups). The first round's checks
// run on `threads` threads (0: all cores); moves are serial, in group order, so the mesh is the
// same for any thread count. safe is indexed by vertex (only groups' vertices are read).
UnfoldStats unfoldVertices(TriangleMesh& mesh, const std::vector<UnfoldGroup>& groups,
                           const std::vector<Vec3>& safe, double tol, int threads = 0);

// The groups (indices into groups, ascending) whose stars cross or overlap, as unfoldVertices
// checks them, without moving anything: for vertices that may not move (the octree's merged
// blocks, whose folds are undone by splitting the block).
std::vector<uint32_t> findFoldedGroups(const TriangleMesh& mesh,
                                       const std::vector<UnfoldGroup>& groups, double tol,
                                       int threads = 0);

}  // namespace csg
