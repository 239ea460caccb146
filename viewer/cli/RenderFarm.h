// `csgray render` on the ranks of an MPI job, or alone with --resume: the image's tiles, or an
// animation's frames, handed out by rank 0 through dist::TaskFarm and recorded in a journal
// beside the output as they finish.
#pragma once

#include <atomic>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "viewer/cli/Report.h"
#include "viewer/cli/dist/Journal.h"
#include "viewer/cli/dist/Ranks.h"
#include "viewer/render/TileRenderer.h"

namespace viewer {

// --resume: the journal of finished tasks beside the output (rank 0 only). Opened by the
// functions below, which read back what it holds; removed by the caller once the output is
// committed.
struct ResumeJournal {
    std::filesystem::path path;
    std::string key;  // the job's identity (RenderCommand's jobKey)
    dist::Journal journal;
};

// Renders every tile of one image on every rank. On rank 0, result gets the whole image, the
// tiles of the journal (when given: rank 0 only) included, and each newly finished tile is
// appended to the journal. Returns kExitOk, kExitIo (the journal cannot be written) or
// render::kExitInterrupted; result.interrupted is then set on rank 0. Counts are summed over the
// ranks into rank 0's result.
int renderTilesOnRanks(const dist::Ranks& ranks, const csg::Scene& scene,
                       const render::EffectsPlan& plan, const render::RenderCamera& camera,
                       const render::ImageSettings& settings, ResumeJournal* resume,
                       render::ProgressMeter* progress, const std::atomic<bool>* cancel,
                       render::RenderResult& result, Report& report);

// Runs renderFrame(frame) (which writes its own file) for each frame of `frames` on some rank,
// one frame per rank at a time; rank 0 records finished frames in the journal (when given) and
// skips those it holds whose file is still there (written(frame)). Returns kExitOk or the first
// failing frame's exit code.
int renderFramesOnRanks(const dist::Ranks& ranks, const std::vector<int>& frames,
                        const std::function<int(int frame)>& renderFrame,
                        const std::function<bool(int frame)>& written, ResumeJournal* resume,
                        render::ProgressMeter* progress, Report& report);

}  // namespace viewer
