// Work spread over the ranks of a job and the threads of each rank, handed out dynamically by
// rank 0 (a task farm): image tiles, animation frames, blocks of probe rays. Rank 0 makes the
// tasks and receives every result, so it alone writes the output, in whatever order it likes
// (the pixels of a tile, the lines of a ray block, do not depend on where they were made).
//
// Rank 0's threads take one task at a time; every other rank asks for batches (two tasks per
// thread) before its threads run out of work and sends its results back with its next request.
// The main thread of each rank does all the MPI calls (MPI_THREAD_FUNNELED), polling and
// sleeping in between, while the rank's worker threads compute. Alone (no mpirun) the farm is only
// rank 0's threads: no MPI call is made.
#pragma once

#include <cstdint>
#include <functional>
#include <string>

#include "viewer/cli/dist/Ranks.h"

namespace viewer::dist {

struct Task {
    uint64_t id = 0;
    std::string input;  // what the worker needs beyond what every rank already has
};

// Rank 0's end of the farm. The farm calls it from one thread at a time (under one lock), so it
// may keep a progress meter, a journal or an output stream without locks of its own.
class TaskSource {
public:
    virtual ~TaskSource() = default;
    // The next task; false when there is none left (all handed out, a failure, Ctrl-C).
    virtual bool next(Task& task) = 0;
    // The result of task id, one of those next() handed out; each arrives exactly once.
    virtual void finished(uint64_t id, std::string&& result) = 0;
};

// Does one task on worker thread `worker` (in [0, threads)) of this rank; result is what is
// sent back to rank 0.
using TaskWork = std::function<void(int worker, const Task& task, std::string& result)>;

// Runs the farm on every rank: source is rank 0's (ignored elsewhere), threads >= 1. Returns
// once every task handed out has finished and every rank has been told there is no more.
void runFarm(const Ranks& ranks, TaskSource* source, int threads, const TaskWork& work);

}  // namespace viewer::dist
