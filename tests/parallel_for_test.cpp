// parallelFor (primitives/base/ParallelFor.h): every item once, a stop honoured, and an item's
// exception brought back to the caller from whichever thread threw it.
#include "primitives/base/ParallelFor.h"

#include <gtest/gtest.h>

#include <atomic>
#include <new>
#include <stdexcept>
#include <vector>

namespace csg {
namespace {

TEST(ParallelFor, EveryItemOnceOnAWorkerInRange) {
    for (int threads : {1, 2, 5}) {
        std::vector<std::atomic<int>> runs(1000);
        std::atomic<bool> badWorker{false};
        parallelFor(runs.size(), threads, [&](int worker, uint64_t item) {
            if (worker < 0 || worker >= threads) badWorker = true;
            ++runs[item];
        });
        EXPECT_FALSE(badWorker) << threads << " threads";
        for (size_t i = 0; i < runs.size(); ++i)
            ASSERT_EQ(runs[i].load(), 1) << "item " << i << ", " << threads << " threads";
    }
}

// No item starts once a worker has seen the stop: on one thread, the items after the one that
// set it do not run.
TEST(ParallelFor, NoItemStartsAfterTheStop) {
    std::atomic<bool> stop{false};
    std::vector<int> ran;
    parallelFor(
        100, 1,
        [&](int, uint64_t item) {
            ran.push_back(int(item));
            if (item == 9) stop = true;
        },
        &stop);
    EXPECT_EQ(ran.size(), 10u);
}

// An item that throws, on any thread, ends the run and the exception reaches the caller; the
// other workers finish the items they started and start no more. Before, an exception on a
// worker's thread called std::terminate, which would end this test program.
TEST(ParallelFor, AnItemsExceptionReachesTheCaller) {
    for (int threads : {1, 2, 3}) {
        std::atomic<uint64_t> started{0};
        EXPECT_THROW(parallelFor(100000, threads,
                                 [&](int, uint64_t item) {
                                     ++started;
                                     if (item >= 50) throw std::bad_alloc();
                                 }),
                     std::bad_alloc)
            << threads << " threads";
        // Each worker starts at most one item after the first throw is seen.
        EXPECT_LT(started.load(), 50u + 2u * uint64_t(threads)) << threads << " threads";
    }
    // The exception thrown on the caller's own thread (worker 0) while others run.
    EXPECT_THROW(parallelFor(1000, 3,
                             [](int worker, uint64_t) {
                                 if (worker == 0) throw std::runtime_error("on the caller");
                             }),
                 std::runtime_error);
}

}  // namespace
}  // namespace csg
