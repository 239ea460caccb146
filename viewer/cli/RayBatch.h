// `csgray probe --rays FILE`: many rays through one compiled scene. Input is one ray per line,
// "ox oy oz dx dy dz" (spaces, tabs or commas between numbers; blank lines and lines starting
// with '#' are skipped); output is one ProbeJson line per ray on stdout, in input order.
//
// Rays are read in blocks; each block is split into at most one contiguous part per thread
// (csg::parallelFor), each part with its own output buffer and each thread its own
// QueryContext, reused from block to block: no allocation per ray once the buffers have grown. A
// bad line stops the run after the rays before it have been printed.
#pragma once

#include <cstdint>
#include <cstdio>
#include <string>

#include "viewer/cli/ProbeJson.h"
#include "viewer/cli/Report.h"
#include "viewer/cli/dist/Ranks.h"

namespace viewer {

struct RayBatchResult {
    int exitCode = 0;   // kExitOk, kExitBadModel (a bad input line) or kExitIo
    uint64_t rays = 0;  // rays probed and printed
};

// inputName labels diagnostics ("<stdin>" for -). threads >= 1.
RayBatchResult probeRayBatch(std::FILE* input, const std::string& inputName, const ProbeJson& probe,
                             int threads, Report& report);

// The same on every rank of an MPI job: rank 0 reads input (others pass null) and hands out
// blocks of rays dynamically; it prints every ray's line in input order, as probeRayBatch does.
// The result counts only on rank 0.
RayBatchResult probeRayBatchOnRanks(const dist::Ranks& ranks, std::FILE* input,
                                    const std::string& inputName, const ProbeJson& probe,
                                    int threads, Report& report);

}  // namespace viewer
