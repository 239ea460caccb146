// Loops of the mesh pipeline whose items other processes may compute: `csgray export` under
// mpirun hands them to the ranks of the job (viewer/cli/ExportFarm.h), so that every rank ends
// up with the same results and makes the same mesh, and rank 0 writes it. csg/ knows nothing of
// MPI: a loop gives run() its item count, what its items are (for progress: "the grid's rows"),
// and two functions,
//   work(worker, item, bytes)  computes item on worker thread `worker` (in [0, threads)) of
//                              whichever process runs it, and writes its result to bytes;
//   take(item, bytes)          is then called on every process, for every item, in ascending
//                              order, with the bytes work wrote,
// so a loop that merges its items in item order makes the same result as alone. With no
// distributor (the default) a loop runs on this process's threads and skips the bytes.
#pragma once

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <functional>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include "primitives/base/ParallelFor.h"

namespace csg {

using ItemWork = std::function<void(int worker, uint64_t item, std::string& bytes)>;
using ItemTake = std::function<void(uint64_t item, std::string_view bytes)>;

struct ItemDistributor {
    int threads = 1;  // worker indices of work() run in [0, threads)
    std::function<void(uint64_t count, std::string_view what, const ItemWork& work,
                       const ItemTake& take)>
        run;
};

// The worker indices a loop's work() may see: the distributor's threads, or this process's
// (threads 0: all cores) when it runs alone.
inline int workersFor(const ItemDistributor* distribute, int threads) {
    return distribute ? distribute->threads : resolveThreads(threads);
}

// Results to bytes and back: trivially copyable values and vectors of them, in the order
// written. The processes of one job run the same binary on the same architecture (as MPI
// jobs do), so the bytes are the values' own.
class ByteWriter {
public:
    explicit ByteWriter(std::string& out) : out_(out) {}
    template <class T>
    void value(const T& v) {
        static_assert(std::is_trivially_copyable_v<T>);
        out_.append(reinterpret_cast<const char*>(&v), sizeof v);
    }
    template <class T>
    void values(const std::vector<T>& v) {
        value(uint64_t(v.size()));
        static_assert(std::is_trivially_copyable_v<T>);
        out_.append(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(T));
    }

private:
    std::string& out_;
};

class ByteReader {
public:
    explicit ByteReader(std::string_view in) : in_(in) {}
    template <class T>
    T value() {
        static_assert(std::is_trivially_copyable_v<T>);
        T v{};
        if (in_.size() >= sizeof v) std::memcpy(&v, in_.data(), sizeof v);
        in_.remove_prefix(std::min(in_.size(), sizeof v));
        return v;
    }
    template <class T>
    std::vector<T> values() {
        const uint64_t n = std::min<uint64_t>(value<uint64_t>(), in_.size() / sizeof(T));
        std::vector<T> v(n);
        if (n) std::memcpy(v.data(), in_.data(), n * sizeof(T));
        in_.remove_prefix(n * sizeof(T));
        return v;
    }

private:
    std::string_view in_;
};

}  // namespace csg
