// Notation: a request goes from a worker rank to rank 0 (tag kRequest) and carries the results
// of a finished batch; the answer (tag kBatch) is the next batch, empty when there is no more
// work; the worker's last request (kFinal) carries its last results and gets no answer. Both
// are one MPI_BYTE message: a u32 header, a u32 count, then per item a u64 id, a u64 size and
// the bytes.
#include "viewer/cli/dist/TaskFarm.h"

#include <chrono>
#include <condition_variable>
#include <csignal>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <deque>
#include <mutex>
#include <thread>
#include <vector>

#include "primitives/base/ParallelFor.h"

namespace viewer::dist {

namespace {

constexpr int kRequest = 1, kBatch = 2;
// A request's header is the asking rank's thread count (it gets two tasks per thread), or this.
constexpr uint32_t kFinal = UINT32_MAX;
// Rank 0's serving thread polls for requests this often when there are none: a blocking
// receive would spin a core of Open MPI's progress engine that the workers need.
constexpr std::chrono::microseconds kPollInterval{200};

struct Item {
    uint64_t id;
    std::string bytes;
};

void put(std::string& out, const void* p, size_t n) {
    out.append(static_cast<const char*>(p), n);
}

std::string pack(uint32_t header, const std::vector<Item>& items) {
    std::string out;
    put(out, &header, sizeof header);
    const uint32_t count = uint32_t(items.size());
    put(out, &count, sizeof count);
    for (const Item& item : items) {
        const uint64_t size = item.bytes.size();
        put(out, &item.id, sizeof item.id);
        put(out, &size, sizeof size);
        out += item.bytes;
    }
    return out;
}

// The inverse of pack (messages come from this program on another rank, so they are trusted).
std::vector<Item> unpack(const std::string& in, uint32_t& header) {
    size_t at = 0;
    auto get = [&](void* p, size_t n) {
        std::memcpy(p, in.data() + at, n);
        at += n;
    };
    uint32_t count = 0;
    get(&header, sizeof header);
    get(&count, sizeof count);
    std::vector<Item> items(count);
    for (Item& item : items) {
        uint64_t size = 0;
        get(&item.id, sizeof item.id);
        get(&size, sizeof size);
        item.bytes.assign(in.data() + at, size);
        at += size;
    }
    return items;
}

// Receives a message that poll or probe found.
std::string receive(const CsgrayMpiCalls& mpi, const CsgrayMpiMessage& message) {
    std::string bytes(size_t(message.bytes), '\0');
    mpi.receive(&message, bytes.data());
    return bytes;
}

// Rank 0: `threads` workers taking one task at a time, and (with other ranks) the main thread
// serving their requests from the same source.
void runRoot(const Ranks& ranks, TaskSource& source, int threads, const TaskWork& work) {
    std::mutex lock;
    auto workLocally = [&](int worker) {
        Task task;
        std::string result;
        for (;;) {
            {
                std::lock_guard<std::mutex> hold(lock);
                if (!source.next(task)) return;
            }
            result.clear();
            work(worker, task, result);
            std::lock_guard<std::mutex> hold(lock);
            source.finished(task.id, std::move(result));
        }
    };
    if (ranks.size() == 1) {
        csg::parallelFor(uint64_t(threads), threads,
                         [&](int worker, uint64_t) { workLocally(worker); });
        return;
    }
    std::vector<std::thread> pool;
    for (int w = 0; w < threads; ++w) pool.emplace_back(workLocally, w);

    const CsgrayMpiCalls& mpi = ranks.calls();
    int serving = ranks.size() - 1;  // worker ranks whose final request has not come yet
    while (serving > 0) {
        CsgrayMpiMessage message;
        if (!mpi.poll(-1, kRequest, &message)) {
            std::this_thread::sleep_for(kPollInterval);
            continue;
        }
        uint32_t header = 0;
        std::vector<Item> results = unpack(receive(mpi, message), header);
        std::vector<Item> batch;
        {
            std::lock_guard<std::mutex> hold(lock);
            for (Item& r : results) source.finished(r.id, std::move(r.bytes));
            Task task;
            for (uint32_t i = 0; header != kFinal && i < 2 * header && source.next(task); ++i)
                batch.push_back({task.id, std::move(task.input)});
        }
        if (header == kFinal) {
            --serving;
        } else {
            const std::string reply = pack(0, batch);
            mpi.send(reply.data(), int(reply.size()), message.source, kBatch);
        }
    }
    for (std::thread& t : pool) t.join();
}

// The fault the tests inject (tests/cli_mpi_test.cpp): CSGRAY_TEST_KILL_AFTER_TASKS=K makes the
// job's last rank kill itself with SIGKILL once it has finished K tasks (or, if it gets fewer,
// when it is told there are no more), as a node that dies midway would; it does so in the
// process's first farm, or in farm F (counted from 0) when CSGRAY_TEST_KILL_IN_FARM=F (an
// export runs one farm per loop). Never set outside the tests; costs two getenv per farm.
uint64_t tasksBeforeKill(const Ranks& ranks) {
    static uint64_t farms = 0;  // farms this process has worked in (main thread only)
    const uint64_t farm = farms++;
    const char* value = std::getenv("CSGRAY_TEST_KILL_AFTER_TASKS");
    if (!value || ranks.rank() != ranks.size() - 1) return UINT64_MAX;
    const char* in = std::getenv("CSGRAY_TEST_KILL_IN_FARM");
    if (farm != (in ? std::strtoull(in, nullptr, 10) : 0)) return UINT64_MAX;
    return std::strtoull(value, nullptr, 10);
}

// Any other rank: `threads` workers take tasks from a local queue while the main thread keeps
// the queue fed. It asks rank 0 for a batch as soon as fewer tasks than threads are waiting (so
// the round trip hides behind the work), sends the results finished so far with each request,
// and otherwise polls and sleeps, which also keeps MPI's transfers moving. The last request
// (kFinal) carries the last results and wants no answer.
void runWorker(const Ranks& ranks, int threads, const TaskWork& work) {
    std::mutex lock;
    std::condition_variable ready;
    std::deque<Item> queue;
    std::vector<Item> results;
    int working = 0;  // tasks taken from the queue and not yet finished
    uint64_t finished = 0;
    bool over = false;

    auto workLocally = [&](int worker) {
        std::unique_lock<std::mutex> hold(lock);
        for (;;) {
            ready.wait(hold, [&] { return over || !queue.empty(); });
            if (queue.empty()) return;
            const Task task{queue.front().id, std::move(queue.front().bytes)};
            queue.pop_front();
            ++working;
            hold.unlock();
            Item result{task.id, {}};
            work(worker, task, result.bytes);
            hold.lock();
            results.push_back(std::move(result));
            --working;
            ++finished;
        }
    };
    std::vector<std::thread> pool;
    for (int w = 0; w < threads; ++w) pool.emplace_back(workLocally, w);

    const uint64_t killAfter = tasksBeforeKill(ranks);
    const CsgrayMpiCalls& mpi = ranks.calls();
    std::string outgoing;  // the request in flight; MPI reads it until the send completes
    void* sending = nullptr;
    auto request = [&](uint32_t header, std::vector<Item>&& done) {
        mpi.wait(sending);
        outgoing = pack(header, done);
        sending = mpi.startSend(outgoing.data(), int(outgoing.size()), 0, kRequest);
    };
    bool asked = false, noMore = false;
    for (;;) {
        bool idle = true;
        {
            std::unique_lock<std::mutex> hold(lock);
            // (A rank that got fewer tasks dies when told there are no more: the job fails.)
            if (finished >= killAfter || (noMore && killAfter != UINT64_MAX)) std::raise(SIGKILL);
            if (noMore && queue.empty() && working == 0) break;
            if (!asked && !noMore && queue.size() < size_t(threads)) {
                std::vector<Item> done = std::move(results);
                results.clear();
                hold.unlock();
                request(uint32_t(threads), std::move(done));
                asked = true;
                idle = false;
            }
        }
        CsgrayMpiMessage message;
        if (asked && mpi.poll(0, kBatch, &message)) {
            uint32_t unused = 0;
            std::vector<Item> batch = unpack(receive(mpi, message), unused);
            asked = false;
            idle = false;
            std::lock_guard<std::mutex> hold(lock);
            noMore = batch.empty();
            for (Item& item : batch) queue.push_back(std::move(item));
            ready.notify_all();
        }
        if (idle) std::this_thread::sleep_for(kPollInterval);
    }
    {
        std::lock_guard<std::mutex> hold(lock);
        over = true;
        ready.notify_all();
    }
    for (std::thread& t : pool) t.join();
    request(kFinal, std::move(results));
    mpi.wait(sending);
}

}  // namespace

void runFarm(const Ranks& ranks, TaskSource* source, int threads, const TaskWork& work) {
    if (ranks.root())
        runRoot(ranks, *source, threads, work);
    else
        runWorker(ranks, threads, work);
}

}  // namespace viewer::dist
