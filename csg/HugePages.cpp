#include "csg/HugePages.h"

#include <sys/mman.h>

#include <cstdint>

namespace csg {

namespace {

size_t roundUpToHugePage(size_t bytes) {
    return (bytes + kHugePageBytes - 1) / kHugePageBytes * kHugePageBytes;
}

}  // namespace

void* mapHugePages(size_t bytes) {
    // mmap aligns to 4 KiB only: map one huge page more than needed and give back the
    // unaligned head and the tail, so that every 2 MiB of the block can be one huge page.
    const size_t size = roundUpToHugePage(bytes);
    if (size < bytes || size + kHugePageBytes < size) throw std::bad_alloc();
    const size_t mapped = size + kHugePageBytes;
    void* raw = mmap(nullptr, mapped, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
    if (raw == MAP_FAILED) throw std::bad_alloc();
    const uintptr_t start = uintptr_t(raw);
    const uintptr_t aligned = (start + kHugePageBytes - 1) / kHugePageBytes * kHugePageBytes;
    if (aligned > start) munmap(raw, aligned - start);
    const uintptr_t end = start + mapped;
    if (end > aligned + size) munmap(reinterpret_cast<void*>(aligned + size), end - aligned - size);
    // Only advice: a kernel without transparent huge pages answers EINVAL and keeps 4 KiB pages.
    madvise(reinterpret_cast<void*>(aligned), size, MADV_HUGEPAGE);
    return reinterpret_cast<void*>(aligned);
}

void unmapHugePages(void* block, size_t bytes) noexcept {
    munmap(block, roundUpToHugePage(bytes));
}

}  // namespace csg
