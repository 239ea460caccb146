// csg/HugePages.h: big blocks are 2 MiB-aligned mappings the kernel may back with transparent
// huge pages; small ones come from std::allocator; vectors of either behave as vectors.
#include "csg/HugePages.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <fstream>
#include <sstream>
#include <string>

namespace csg {
namespace {

// The kernel's transparent huge page mode: "always", "madvise", "never", or "" when unknown.
std::string hugePageMode() {
    std::ifstream in("/sys/kernel/mm/transparent_hugepage/enabled");
    std::string line;
    std::getline(in, line);
    const size_t open = line.find('['), close = line.find(']');
    if (open == std::string::npos || close == std::string::npos) return {};
    return line.substr(open + 1, close - open - 1);
}

// The "THPeligible" field of the mapping in /proc/self/smaps that contains address, or -1.
int hugePageEligible(const void* address) {
    std::ifstream smaps("/proc/self/smaps");
    const uintptr_t at = uintptr_t(address);
    bool inside = false;
    for (std::string line; std::getline(smaps, line);) {
        uintptr_t begin = 0, end = 0;
        char dash = 0;
        std::istringstream range(line);
        if (range >> std::hex >> begin >> dash >> end && dash == '-') {
            inside = begin <= at && at < end;
            continue;
        }
        if (inside && line.rfind("THPeligible:", 0) == 0)
            return std::stoi(line.substr(line.find(':') + 1));
    }
    return -1;
}

TEST(HugePages, BigBlocksAreAlignedAndAdvisedOntoHugePages) {
    HugePageVector<float> image;
    image.resize(8 << 20);  // 32 MiB
    ASSERT_EQ(uintptr_t(image.data()) % kHugePageBytes, 0u);
    for (size_t i = 0; i < image.size(); ++i) image[i] = float(i % 1000);
    EXPECT_EQ(image[image.size() - 1], float((image.size() - 1) % 1000));

    const std::string mode = hugePageMode();
    if (mode != "always" && mode != "madvise")
        GTEST_SKIP() << "this kernel offers no transparent huge pages (mode '" << mode << "')";
    // In madvise mode only the advice makes the mapping eligible.
    EXPECT_EQ(hugePageEligible(image.data()), 1);
    EXPECT_EQ(hugePageEligible(image.data() + image.size() - 1), 1);
}

TEST(HugePages, VectorsFillWhenGivenAValueAndCopyAndCompare) {
    const size_t big = kHugePageMinBytes / sizeof(double) + 3;  // not a whole number of pages
    for (const size_t n : {size_t(0), size_t(1), size_t(1000), big}) {
        const HugePageVector<double> filled(n, 2.5);
        ASSERT_EQ(filled.size(), n);
        for (const double x : filled) ASSERT_EQ(x, 2.5);
        HugePageVector<double> copy = filled;
        EXPECT_EQ(copy, filled);
        if (n > 0) copy[n - 1] = 0.0;
        EXPECT_EQ(copy == filled, n == 0);
        copy.push_back(7.0);  // may move a small block into a mapping and back
        EXPECT_EQ(copy.back(), 7.0);
        copy.shrink_to_fit();
        EXPECT_EQ(copy.size(), n + 1);
    }
}

TEST(HugePages, ImpossibleSizesThrowBadAlloc) {
    HugePageAllocator<double> allocator;
    EXPECT_THROW((void)allocator.allocate(size_t(-1) / 4), std::bad_alloc);
    EXPECT_THROW((void)allocator.allocate(size_t(1) << 60), std::bad_alloc);
}

}  // namespace
}  // namespace csg
