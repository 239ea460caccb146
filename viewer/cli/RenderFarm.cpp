#include "viewer/cli/RenderFarm.h"

#include <memory>
#include <set>

#include "viewer/cli/Cli.h"
#include "viewer/cli/dist/TaskFarm.h"
#include "viewer/render/Interrupt.h"

namespace viewer {

namespace {

// Rank 0's tiles: the ones the journal does not hold yet, in image order.
class TileSource : public dist::TaskSource {
public:
    TileSource(const render::TileSet& tiles, render::RenderResult& image, dist::Journal* journal,
               render::ProgressMeter* progress, const std::atomic<bool>* cancel)
        : tiles_(tiles), image_(image), journal_(journal), progress_(progress), cancel_(cancel) {}

    // Takes the journal's tiles into the image; the rest become the tasks.
    void resume(const std::set<int>& done) {
        done_ = done.size();
        for (int t = 0; t < tiles_.count(); ++t)
            if (!done.count(t)) pending_.push_back(t);
    }

    bool next(dist::Task& task) override {
        if (next_ >= pending_.size() || !error_.empty() || (cancel_ && cancel_->load()))
            return false;
        task.id = uint64_t(pending_[next_++]);
        task.input.clear();
        return true;
    }

    void finished(uint64_t id, std::string&& pixels) override {
        tiles_.place(int(id), pixels, image_);
        if (journal_ && error_.empty()) error_ = journal_->append(id, pixels);
        ++done_;
        if (progress_) progress_->update(done_, uint64_t(tiles_.count()));
    }

    uint64_t done() const { return done_; }
    const std::string& error() const { return error_; }

private:
    const render::TileSet& tiles_;
    render::RenderResult& image_;
    dist::Journal* journal_;
    render::ProgressMeter* progress_;
    const std::atomic<bool>* cancel_;
    std::vector<int> pending_;
    size_t next_ = 0;
    uint64_t done_ = 0;
    std::string error_;
};

}  // namespace

int renderTilesOnRanks(const dist::Ranks& ranks, const csg::Scene& scene,
                       const render::EffectsPlan& plan, const render::RenderCamera& camera,
                       const render::ImageSettings& settings, ResumeJournal* resume,
                       render::ProgressMeter* progress, const std::atomic<bool>* cancel,
                       render::RenderResult& result, Report& report) {
    render::TileSet tiles(scene, plan, camera, settings);
    std::unique_ptr<TileSource> source;
    if (ranks.root()) {
        result = tiles.blankResult();
        std::set<int> done;
        if (resume) {
            const std::string error = resume->journal.open(
                resume->path, resume->key, [&](uint64_t id, std::string_view pixels) {
                    if (id < uint64_t(tiles.count()) && tiles.place(int(id), pixels, result))
                        done.insert(int(id));
                });
            if (!error.empty()) {
                report.error(resume->path.string(), error);
                ranks.abort(kExitIo);
            }
        }
        source = std::make_unique<TileSource>(tiles, result, resume ? &resume->journal : nullptr,
                                              progress, cancel);
        source->resume(done);
    }
    dist::runFarm(ranks, source.get(), settings.threads,
                  [&](int worker, const dist::Task& task, std::string& pixels) {
                      tiles.render(worker, int(task.id), pixels);
                  });

    render::RenderResult counts;
    tiles.addCounts(counts);
    unsigned long long sums[] = {counts.rays.primary,           counts.rays.shadow,
                                 counts.rays.reflection,        counts.rays.refraction,
                                 counts.queries.rays,           counts.queries.nodeVisits,
                                 counts.queries.primitiveTests, counts.queries.slabCulls};
    ranks.sumToRoot(sums, int(std::size(sums)));
    if (!ranks.root()) return kExitOk;
    result.rays = {sums[0], sums[1], sums[2], sums[3]};
    result.queries.rays = sums[4];
    result.queries.nodeVisits = sums[5];
    result.queries.primitiveTests = sums[6];
    result.queries.slabCulls = sums[7];

    const uint64_t total = uint64_t(tiles.count());
    result.interrupted = source->done() < total;
    if (!source->error().empty()) {
        if (progress) progress->finish(source->done(), total, true);
        report.error(resume ? resume->path.string() : "render", source->error());
        return kExitIo;
    }
    if (progress) progress->finish(source->done(), total, result.interrupted);
    return result.interrupted ? render::kExitInterrupted : kExitOk;
}

namespace {

// Rank 0's frames: those the journal does not hold, each one task whose result is the exit
// code of its render (one byte).
class FrameSource : public dist::TaskSource {
public:
    FrameSource(std::vector<int> pending, size_t total, dist::Journal* journal,
                render::ProgressMeter* progress)
        : pending_(std::move(pending)),
          total_(total),
          done_(total - pending_.size()),
          journal_(journal),
          progress_(progress) {}

    bool next(dist::Task& task) override {
        if (next_ >= pending_.size() || code_ != kExitOk || render::interruptRequested().load())
            return false;
        task.id = uint64_t(pending_[next_++]);
        task.input.clear();
        return true;
    }

    void finished(uint64_t id, std::string&& result) override {
        const int code = result.empty() ? kExitBadModel : int(uint8_t(result[0]));
        if (code != kExitOk) {
            if (code_ == kExitOk) code_ = code;
            return;
        }
        if (journal_ && code_ == kExitOk && !(error_ = journal_->append(id, {})).empty())
            code_ = kExitIo;
        ++done_;
        if (progress_) progress_->update(done_, total_);
    }

    int code() const { return code_; }
    uint64_t done() const { return done_; }
    const std::string& error() const { return error_; }

private:
    std::vector<int> pending_;
    size_t next_ = 0;
    uint64_t total_, done_;
    dist::Journal* journal_;
    render::ProgressMeter* progress_;
    int code_ = kExitOk;
    std::string error_;
};

}  // namespace

int renderFramesOnRanks(const dist::Ranks& ranks, const std::vector<int>& frames,
                        const std::function<int(int frame)>& renderFrame,
                        const std::function<bool(int frame)>& written, ResumeJournal* resume,
                        render::ProgressMeter* progress, Report& report) {
    std::unique_ptr<FrameSource> source;
    if (ranks.root()) {
        std::set<int> done;
        if (resume) {
            const std::string error =
                resume->journal.open(resume->path, resume->key, [&](uint64_t id, std::string_view) {
                    if (written(int(id))) done.insert(int(id));
                });
            if (!error.empty()) {
                report.error(resume->path.string(), error);
                ranks.abort(kExitIo);
            }
        }
        std::vector<int> pending;
        for (int f : frames)
            if (!done.count(f)) pending.push_back(f);
        source = std::make_unique<FrameSource>(std::move(pending), frames.size(),
                                               resume ? &resume->journal : nullptr, progress);
    }
    // One frame at a time per rank: each frame's render uses all the rank's threads.
    dist::runFarm(ranks, source.get(), 1, [&](int, const dist::Task& task, std::string& result) {
        result.assign(1, char(uint8_t(renderFrame(int(task.id)))));
    });
    if (!ranks.root()) return kExitOk;
    const bool complete = source->done() == frames.size();
    if (progress) progress->finish(source->done(), frames.size(), !complete);
    if (!source->error().empty()) report.error(resume->path.string(), source->error());
    if (source->code() != kExitOk) return source->code();
    return complete ? kExitOk : render::kExitInterrupted;
}

}  // namespace viewer
