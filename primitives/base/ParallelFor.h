// The one thread helper: runs fn(worker, item) for item in [0, count) on `threads` threads that
// take items from one atomic counter (items of uneven cost balance themselves). worker is in
// [0, threads); the calling thread is worker 0, so per-worker state (a query context, an
// output buffer, a progress meter only the caller may touch) is indexed by worker.
#pragma once

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <exception>
#include <thread>
#include <utility>
#include <vector>

namespace csg {

// The thread count an option asks for: threads itself when > 0, else one per core (>= 1).
inline int resolveThreads(int threads) {
    return threads > 0 ? threads : int(std::max(1u, std::thread::hardware_concurrency()));
}

// Returns once every item has run, or, when stop is given and *stop turns true, once the items
// already started have finished: no item starts after a worker sees *stop (checked before
// each item), so a caller that counts its finished items can tell a stopped run.
// An exception from fn (std::bad_alloc while a large mesh's BVH is built) stops the run the
// same way and is rethrown here, once every worker has returned: thrown on a worker's own
// thread it would end the process (std::terminate) instead of reaching the caller's handler.
// Of several, the first caught is rethrown.
template <class Fn>
void parallelFor(uint64_t count, int threads, Fn&& fn, const std::atomic<bool>* stop = nullptr) {
    const int n =
        int(std::min<uint64_t>(uint64_t(resolveThreads(threads)), std::max<uint64_t>(count, 1)));
    std::atomic<uint64_t> next{0};
    std::atomic<bool> failed{false};
    std::exception_ptr error;  // written only by the worker that set `failed`
    auto work = [&](int worker) {
        try {
            for (uint64_t item = next++; item < count; item = next++) {
                if (failed.load(std::memory_order_relaxed)) return;
                if (stop && stop->load(std::memory_order_relaxed)) return;
                fn(worker, item);
            }
        } catch (...) {
            if (!failed.exchange(true)) error = std::current_exception();
        }
    };
    std::vector<std::thread> pool;
    pool.reserve(size_t(n - 1));  // before any thread runs, so that only starting one can fail
    for (int w = 1; w < n; ++w) {
        try {
            pool.emplace_back(work, w);
        } catch (const std::exception&) {
            break;  // no more threads to be had: the items are shared by those started
        }
    }
    work(0);
    for (std::thread& t : pool) t.join();
    if (error) std::rethrow_exception(error);
}

// One worker's state in a std::vector indexed by worker, alone on its cache lines: state written
// on every item (a query context's counters) would otherwise slow the neighbouring workers.
template <class T>
struct alignas(64) WorkerSlot {
    template <class... Args>
    explicit WorkerSlot(Args&&... args) : value(std::forward<Args>(args)...) {}
    T value;
};

}  // namespace csg
