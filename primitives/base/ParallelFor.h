// Runs fn(worker, item) for item in [0, count) on `threads` threads that take items from one
// atomic counter (items of uneven cost balance themselves). worker is in [0, threads).
#pragma once

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <thread>
#include <vector>

namespace csg {

inline int resolveThreads(int threads) {
    return threads > 0 ? threads : int(std::max(1u, std::thread::hardware_concurrency()));
}

template <class Fn>
void parallelFor(uint64_t count, int threads, Fn&& fn) {
    const int n =
        int(std::min<uint64_t>(uint64_t(resolveThreads(threads)), std::max<uint64_t>(count, 1)));
    std::atomic<uint64_t> next{0};
    auto work = [&](int worker) {
        for (uint64_t item = next++; item < count; item = next++) fn(worker, item);
    };
    std::vector<std::thread> pool;
    for (int w = 1; w < n; ++w) pool.emplace_back(work, w);
    work(0);
    for (std::thread& t : pool) t.join();
}

}  // namespace csg
