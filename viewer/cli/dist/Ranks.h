// The processes of one csgray job. Started by mpirun or srun, csgray is one MPI rank of several;
// started alone, it is the only one and never calls MPI. Everything csgray knows of MPI is in
// this folder (Ranks, TaskFarm): the commands see ranks, and the renderer sees tiles.
//
// Whether MPI is started is decided from the launcher's environment (OMPI_COMM_WORLD_SIZE from
// Open MPI's mpirun, PMI_SIZE or PMIX_RANK from srun and other process managers). Only then is
// the module csgray_mpi.so (MpiCalls.h) loaded, with libmpi, and MPI initialized: a plain run
// starts as fast as a csgray without MPI and needs no mpirun (bench/README.md, MPI start-up).
#pragma once

#include <string>

#include "viewer/cli/dist/MpiCalls.h"

namespace viewer::dist {

class Ranks {
public:
    // The job this process belongs to: MPI is initialized on the first call when a launcher
    // started the process, and finalized at exit. A process that a launcher started but that
    // cannot load csgray_mpi.so stops there (exit 1), rather than run the whole job alone.
    static Ranks& job();

    int rank() const { return rank_; }
    int size() const { return size_; }
    bool root() const { return rank_ == 0; }
    // True when MPI is initialized (even for a job of one rank: mpirun -np 1).
    bool mpi() const { return calls_ != nullptr; }
    // The MPI calls; only when mpi().
    const CsgrayMpiCalls& calls() const { return *calls_; }

    // Whether every rank passed ok: a collective call, so every rank must make it (after
    // loading the part, so that no rank waits for work from a rank that failed).
    bool allOk(bool ok) const;
    // Sums values[0, n) over the ranks into rank 0's values (a collective; others keep theirs).
    void sumToRoot(unsigned long long* values, int n) const;
    // Rank 0's bytes to every rank (a collective): the others' are replaced.
    void broadcast(std::string& bytes) const;
    // Ends the whole job at once with code (an error on one rank that the others cannot see).
    [[noreturn]] void abort(int code) const;

private:
    Ranks();
    int rank_ = 0, size_ = 1;
    const CsgrayMpiCalls* calls_ = nullptr;
};

}  // namespace viewer::dist
