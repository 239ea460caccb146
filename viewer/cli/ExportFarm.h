// The mesh pipeline's loops (csg/mesh/Distribute.h) on the ranks of an MPI job: `csgray export`
// under mpirun, or alone with --resume or progress shown. Each loop's items go through the task
// farm (dist/TaskFarm.h: handed out by rank 0, computed on every rank's threads), rank 0 joins
// their results in item order and broadcasts them, and every rank takes them in that order: all
// ranks then hold the same grid and the same figures, make the same mesh, and rank 0 writes it, the
// bytes a single process writes. What the loops do not cover (contouring, the exact boundary's
// welding and merging, simplification) runs on every rank alike.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <unordered_map>

#include "csg/mesh/Distribute.h"
#include "viewer/cli/Report.h"
#include "viewer/cli/dist/Journal.h"
#include "viewer/cli/dist/Ranks.h"
#include "viewer/render/Progress.h"

namespace viewer {

// --resume for an export (rank 0 only): every finished item of every loop is a record of the
// journal beside the output. The loops of one job run in the same order with the same item
// counts each time (they depend on the part and the options of the job's key alone), so a
// record is named by the loop's place in the job and the item's place in the loop, and a
// restarted job takes what the journal holds instead of computing it again.
class ExportJournal {
public:
    // Opens path for the job key, reading back what a killed run of it left. "" or why not.
    std::string open(const std::filesystem::path& path, std::string_view key);
    // The result of (loop, item) that the journal held, moved out (each is taken once), or
    // false.
    bool take(uint64_t loop, uint64_t item, std::string& bytes);
    // Records a finished item; "" or why it could not.
    std::string append(uint64_t loop, uint64_t item, std::string_view bytes);
    // Deletes the journal: the output is committed.
    void remove() { journal_.remove(); }
    const std::filesystem::path& path() const { return journal_.path(); }
    // How many results were taken from the journal so far.
    uint64_t reused() const { return reused_; }

private:
    dist::Journal journal_;
    std::unordered_map<uint64_t, std::string> held_;
    uint64_t reused_ = 0;
};

// Loops on ranks (which must outlive the result), `threads` (>= 1) workers on each rank; with a
// journal (rank 0's; null elsewhere), items it holds are not computed again and finished items
// are appended to it; with a meter (rank 0's), each loop shows its progress, labelled by what
// its items are. A journal that cannot be written ends the job (exit kExitIo) after an error in
// report, leaving no output. journal, progress and report must outlive the result.
csg::ItemDistributor itemsOnRanks(const dist::Ranks& ranks, int threads, Report& report,
                                  ExportJournal* journal = nullptr,
                                  render::ProgressMeter* progress = nullptr);

}  // namespace viewer
