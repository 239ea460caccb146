// Buffers of many megabytes (a rendered image, its 8-bit encoding, the PNG rows) on transparent
// huge pages. Touching fresh memory costs a page fault per page; on 4 KiB pages a 1600x1600
// float image is 7,500 faults, and on a virtual machine each costs ~7 us of kernel time: 5-10 %
// of that render's CPU (bench/README.md). Blocks of at least kHugePageMinBytes are mapped by
// the kernel directly, aligned to 2 MiB and advised onto huge pages (MADV_HUGEPAGE, which the
// kernel honours in its "always" and "madvise" modes), so the same image takes 15 faults.
// Smaller blocks come from std::allocator. Where the kernel has no huge pages the advice is ignored
// and the block is plain anonymous memory. Elements a vector makes without a value (resize(n),
// vector(n)) are default-initialized, as by std::make_unique_for_overwrite: numbers are left
// unset, for buffers that are written before they are read; pass a value to fill them.
#pragma once

#include <cstddef>
#include <memory>
#include <new>
#include <utility>
#include <vector>

namespace csg {

inline constexpr size_t kHugePageBytes = size_t(2) << 20;  // x86-64's transparent huge page
// Below two huge pages a mapping's rounding and its system calls cost more than they save.
inline constexpr size_t kHugePageMinBytes = 2 * kHugePageBytes;

// A block of at least `bytes` (>= kHugePageMinBytes), aligned to kHugePageBytes and advised
// onto huge pages; throws std::bad_alloc when the kernel refuses the mapping.
void* mapHugePages(size_t bytes);
// Returns a block of mapHugePages(bytes) with the same `bytes`.
void unmapHugePages(void* block, size_t bytes) noexcept;

template <class T>
struct HugePageAllocator {
    using value_type = T;

    HugePageAllocator() = default;
    template <class U>
    HugePageAllocator(const HugePageAllocator<U>&) noexcept {}

    T* allocate(size_t n) {
        if (n > size_t(-1) / sizeof(T)) throw std::bad_array_new_length();
        const size_t bytes = n * sizeof(T);
        if (bytes >= kHugePageMinBytes) return static_cast<T*>(mapHugePages(bytes));
        return std::allocator<T>().allocate(n);
    }

    void deallocate(T* p, size_t n) noexcept {
        const size_t bytes = n * sizeof(T);
        if (bytes >= kHugePageMinBytes)
            unmapHugePages(p, bytes);
        else
            std::allocator<T>().deallocate(p, n);
    }

    // Default-initialization instead of value-initialization (see the header comment).
    template <class U>
    void construct(U* p) noexcept(noexcept(::new (static_cast<void*>(p)) U)) {
        ::new (static_cast<void*>(p)) U;
    }
    template <class U, class... Args>
    void construct(U* p, Args&&... args) {
        ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
    }

    template <class U>
    bool operator==(const HugePageAllocator<U>&) const noexcept {
        return true;  // stateless: any instance frees what another allocated
    }
};

template <class T>
using HugePageVector = std::vector<T, HugePageAllocator<T>>;

}  // namespace csg
