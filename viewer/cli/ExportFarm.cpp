#include "viewer/cli/ExportFarm.h"

#include <algorithm>
#include <cstring>
#include <string>
#include <vector>

#include "viewer/cli/dist/TaskFarm.h"

namespace viewer {

namespace {

// Rank 0's end: items 0 .. count - 1, each result kept at its index.
class ItemSource : public dist::TaskSource {
public:
    ItemSource(uint64_t count, std::vector<std::string>& results)
        : count_(count), results_(results) {}
    bool next(dist::Task& task) override {
        if (next_ >= count_) return false;
        task.id = next_++;
        task.input.clear();
        return true;
    }
    void finished(uint64_t id, std::string&& result) override {
        results_[size_t(id)] = std::move(result);
    }

private:
    uint64_t count_, next_ = 0;
    std::vector<std::string>& results_;
};

}  // namespace

csg::ItemDistributor itemsOnRanks(const dist::Ranks& ranks, int threads) {
    csg::ItemDistributor items;
    items.threads = threads;
    items.run = [&ranks, threads](uint64_t count, const csg::ItemWork& work,
                                  const csg::ItemTake& take) {
        std::vector<std::string> results(ranks.root() ? size_t(count) : 0);
        ItemSource source(count, results);
        dist::runFarm(ranks, ranks.root() ? &source : nullptr, threads,
                      [&](int worker, const dist::Task& task, std::string& result) {
                          work(worker, task.id, result);
                      });
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
