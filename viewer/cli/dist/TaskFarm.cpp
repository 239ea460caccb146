// Notation: a request goes from a worker rank to rank 0 (tag kRequest) and carries the results
// of its last batch; the answer (tag kBatch) is the next batch, empty when the farm is over.
// Both are one MPI_BYTE message: a u32 count, then per item a u64 id, a u64 size and the bytes.
#include "viewer/cli/dist/TaskFarm.h"

#include <mpi.h>

#include <chrono>
#include <csignal>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <mutex>
#include <thread>
#include <vector>

#include "primitives/base/ParallelFor.h"

namespace viewer::dist {

namespace {

constexpr int kRequest = 1, kBatch = 2;
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

void send(const std::string& message, int to, int tag) {
    MPI_Send(message.data(), int(message.size()), MPI_BYTE, to, tag, MPI_COMM_WORLD);
}

std::string receive(const MPI_Status& probed) {
    int size = 0;
    MPI_Get_count(&probed, MPI_BYTE, &size);
    std::string message(size_t(size), '\0');
    MPI_Recv(message.data(), size, MPI_BYTE, probed.MPI_SOURCE, probed.MPI_TAG, MPI_COMM_WORLD,
             MPI_STATUS_IGNORE);
    return message;
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

    int serving = ranks.size() - 1;  // ranks not yet told that the farm is over
    while (serving > 0) {
        int arrived = 0;
        MPI_Status status;
        MPI_Iprobe(MPI_ANY_SOURCE, kRequest, MPI_COMM_WORLD, &arrived, &status);
        if (!arrived) {
            std::this_thread::sleep_for(kPollInterval);
            continue;
        }
        uint32_t theirThreads = 0;
        std::vector<Item> results = unpack(receive(status), theirThreads);
        std::vector<Item> batch;
        {
            std::lock_guard<std::mutex> hold(lock);
            for (Item& r : results) source.finished(r.id, std::move(r.bytes));
            Task task;
            for (uint32_t i = 0; i < 2 * theirThreads && source.next(task); ++i)
                batch.push_back({task.id, std::move(task.input)});
        }
        if (batch.empty()) --serving;
        send(pack(0, batch), status.MPI_SOURCE, kBatch);
    }
    for (std::thread& t : pool) t.join();
}

// The fault the tests inject (tests/cli_mpi_test.cpp): CSGRAY_TEST_KILL_AFTER_TASKS=K makes the
// job's last rank kill itself with SIGKILL once it has finished K tasks, as a node that dies
// midway would. Never set outside the tests; costs one getenv per farm.
uint64_t tasksBeforeKill(const Ranks& ranks) {
    const char* value = std::getenv("CSGRAY_TEST_KILL_AFTER_TASKS");
    if (!value || ranks.rank() != ranks.size() - 1) return UINT64_MAX;
    return std::strtoull(value, nullptr, 10);
}

// Any other rank: ask, work the batch off on the threads, send the results with the next ask.
void runWorker(const Ranks& ranks, int threads, const TaskWork& work) {
    const uint64_t killAfter = tasksBeforeKill(ranks);
    uint64_t finished = 0;
    std::vector<Item> results;
    for (;;) {
        if (finished >= killAfter) std::raise(SIGKILL);
        send(pack(uint32_t(threads), results), 0, kRequest);
        MPI_Status status;
        MPI_Probe(0, kBatch, MPI_COMM_WORLD, &status);
        uint32_t unused = 0;
        std::vector<Item> batch = unpack(receive(status), unused);
        if (batch.empty()) return;
        results.assign(batch.size(), Item{});
        csg::parallelFor(batch.size(), threads, [&](int worker, uint64_t i) {
            const Task task{batch[i].id, std::move(batch[i].bytes)};
            results[i].id = task.id;
            work(worker, task, results[i].bytes);
        });
        finished += batch.size();
    }
}

}  // namespace

void runFarm(const Ranks& ranks, TaskSource* source, int threads, const TaskWork& work) {
    if (ranks.root())
        runRoot(ranks, *source, threads, work);
    else
        runWorker(ranks, threads, work);
}

}  // namespace viewer::dist
