#include "viewer/cli/ExportFarm.h"

#include <algorithm>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include "viewer/cli/Cli.h"
#include "viewer/cli/dist/TaskFarm.h"

namespace viewer {

namespace {

// A record's id: the loop in the high bits, the item in the low kItemBits (2^40 items: far more
// than any loop's grid rows, faces or blocks of samples).
constexpr int kItemBits = 40;
uint64_t recordId(uint64_t loop, uint64_t item) {
    return loop << kItemBits | item;
}

// Rank 0's end: items 0 .. count - 1, each result kept at its index; items the journal holds
// are taken from it instead of handed out, and finished ones are appended to it and counted on
// the meter.
class ItemSource : public dist::TaskSource {
public:
    ItemSource(uint64_t count, std::vector<std::string>& results, ExportJournal* journal,
               uint64_t loop, render::ProgressMeter* progress)
        : count_(count), results_(results), journal_(journal), loop_(loop), progress_(progress) {}
    bool next(dist::Task& task) override {
        if (!error_.empty()) return false;
        while (next_ < count_ && journal_ && journal_->take(loop_, next_, results_[next_]))
            ++next_, ++done_;
        if (next_ >= count_) return false;
        task.id = next_++;
        task.input.clear();
        return true;
    }
    void finished(uint64_t id, std::string&& result) override {
        if (journal_ && error_.empty()) error_ = journal_->append(loop_, id, result);
        results_[size_t(id)] = std::move(result);
        if (progress_) progress_->update(++done_, count_);
    }
    const std::string& error() const { return error_; }
    uint64_t done() const { return done_; }

private:
    uint64_t count_, next_ = 0, done_ = 0;
    std::vector<std::string>& results_;
    ExportJournal* journal_;
    uint64_t loop_;
    render::ProgressMeter* progress_;
    std::string error_;
};

}  // namespace

std::string ExportJournal::open(const std::filesystem::path& path, std::string_view key) {
    return journal_.open(
        path, key, [&](uint64_t id, std::string_view bytes) { held_[id] = std::string(bytes); });
}

bool ExportJournal::take(uint64_t loop, uint64_t item, std::string& bytes) {
    const auto found = held_.find(recordId(loop, item));
    if (found == held_.end()) return false;
    bytes = std::move(found->second);
    held_.erase(found);
    ++reused_;
    return true;
}

std::string ExportJournal::append(uint64_t loop, uint64_t item, std::string_view bytes) {
    return journal_.append(recordId(loop, item), bytes);
}

csg::ItemDistributor itemsOnRanks(const dist::Ranks& ranks, int threads, Report& report,
                                  ExportJournal* journal, render::ProgressMeter* progress) {
    csg::ItemDistributor items;
    items.threads = threads;
    // Loops are numbered in the order they run, the same on every rank.
    auto loops = std::make_shared<uint64_t>(0);
    items.run = [&ranks, threads, &report, journal, progress, loops](
                    uint64_t count, std::string_view what, const csg::ItemWork& work,
                    const csg::ItemTake& take) {
        const uint64_t loop = (*loops)++;
        std::vector<std::string> results(ranks.root() ? size_t(count) : 0);
        render::ProgressMeter* meter = ranks.root() ? progress : nullptr;
        if (meter) meter->restart("export: " + std::string(what));
        ItemSource source(count, results, ranks.root() ? journal : nullptr, loop, meter);
        dist::runFarm(ranks, ranks.root() ? &source : nullptr, threads,
                      [&](int worker, const dist::Task& task, std::string& result) {
                          work(worker, task.id, result);
                      });
        if (!source.error().empty()) {
            if (meter) meter->finish(source.done(), count, true);
            report.error(journal->path().string(), source.error());
            report.finish();
            ranks.abort(kExitIo);
        }
        if (meter) meter->finish(count, count, false);
        // Rank 0 joins the results in item order, each after its size; the broadcast also
        // keeps the next loop's farm from starting before every rank has left this one.
        std::string all;
        if (ranks.root()) {
            size_t total = 0;
            for (const std::string& r : results) total += sizeof(uint64_t) + r.size();
            all.reserve(total);
            for (std::string& r : results) {
                const uint64_t size = r.size();
                all.append(reinterpret_cast<const char*>(&size), sizeof size);
                all += r;
                std::string().swap(r);
            }
        }
        ranks.broadcast(all);
        std::string_view rest(all);
        for (uint64_t item = 0; item < count; ++item) {
            uint64_t size = 0;
            if (rest.size() >= sizeof size) std::memcpy(&size, rest.data(), sizeof size);
            rest.remove_prefix(std::min(rest.size(), sizeof size));
            const std::string_view bytes = rest.substr(0, size_t(size));
            rest.remove_prefix(bytes.size());
            take(item, bytes);
        }
    };
    return items;
}

}  // namespace viewer
