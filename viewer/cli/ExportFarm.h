// The mesh pipeline's loops (csg/mesh/Distribute.h) on the ranks of an MPI job: `csgray export`
// under mpirun. Each loop's items go through the task farm (dist/TaskFarm.h: handed out by
// rank 0, computed on every rank's threads), rank 0 joins their results in item order and
// broadcasts them, and every rank takes them in that order: all ranks then hold the same grid
// and the same figures, make the same mesh, and rank 0 writes it, the bytes a single process
// writes. What the loops do not cover (contouring, the exact boundary's welding and merging,
// simplification) runs on every rank alike.
#pragma once

#include "csg/mesh/Distribute.h"
#include "viewer/cli/dist/Ranks.h"

namespace viewer {

// Loops on ranks (which must outlive the result), `threads` (>= 1) workers on each rank.
csg::ItemDistributor itemsOnRanks(const dist::Ranks& ranks, int threads);

}  // namespace viewer
