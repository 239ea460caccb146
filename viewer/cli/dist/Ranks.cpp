#include "viewer/cli/dist/Ranks.h"

#include <mpi.h>

#include <cstdlib>
#include <initializer_list>

namespace viewer::dist {

namespace {

bool launchedByMpi() {
    for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_RANK"})
        if (std::getenv(name)) return true;
    return false;
}

void finalizeAtExit() {
    int finalized = 0;
    MPI_Finalized(&finalized);
    if (!finalized) MPI_Finalize();
}

}  // namespace

Ranks::Ranks() {
    if (!launchedByMpi()) return;
    // Only the main thread calls MPI (TaskFarm's serving loop and the collectives), while
    // worker threads render: FUNNELED is all csgray needs.
    int provided = 0;
    if (MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided) != MPI_SUCCESS) return;
    mpi_ = true;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
    MPI_Comm_size(MPI_COMM_WORLD, &size_);
    std::atexit(finalizeAtExit);
}

Ranks& Ranks::job() {
    static Ranks ranks;
    return ranks;
}

bool Ranks::allOk(bool ok) const {
    if (!mpi_) return ok;
    int mine = ok ? 1 : 0, all = 0;
    MPI_Allreduce(&mine, &all, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD);
    return all == 1;
}

void Ranks::sumToRoot(unsigned long long* values, int n) const {
    if (!mpi_ || size_ == 1) return;
    if (root())
        MPI_Reduce(MPI_IN_PLACE, values, n, MPI_UNSIGNED_LONG_LONG, MPI_SUM, 0, MPI_COMM_WORLD);
    else
        MPI_Reduce(values, nullptr, n, MPI_UNSIGNED_LONG_LONG, MPI_SUM, 0, MPI_COMM_WORLD);
}

void Ranks::abort(int code) const {
    if (mpi_) MPI_Abort(MPI_COMM_WORLD, code);
    std::exit(code);
}

}  // namespace viewer::dist
