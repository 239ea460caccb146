// BoxIndex (csg/mesh/BoxIndex.h) against brute force: every query reports exactly the boxes that
// overlap it (touching counts), each once, over seeded sets of small, long and flat boxes.
#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include "csg/mesh/BoxIndex.h"
#include "tests/SeededRng.h"

namespace csg {
namespace {

// The reference: every box tested, by the coordinates themselves.
bool overlaps(const Bounds3& a, const Bounds3& b) {
    for (int k = 0; k < 3; ++k)
        if (a.lo[k] > b.hi[k] || a.hi[k] < b.lo[k]) return false;
    return true;
}

// A box at a random place with random sides: mostly small, some long along one axis (a
// cylinder's side face), some flat (a box's face).
Bounds3 randomBox(testing::Rng& rng) {
    const Vec3 lo = rng.inBox(Vec3(0.0), Vec3(20.0));
    Vec3 size = rng.inBox(Vec3(0.0), Vec3(2.0));
    if (rng.chance(0.1)) size[rng.index(3)] = rng.uniform(5.0, 20.0);
    if (rng.chance(0.2)) size[rng.index(3)] = 0.0;
    return {lo, lo + size};
}

TEST(BoxIndex, ReportsExactlyTheOverlappingBoxesOnce) {
    testing::Rng rng(31);
    for (const int count : {1, 2, 5, 100, 5000}) {
        std::vector<Bounds3> boxes;
        for (int i = 0; i < count; ++i) boxes.push_back(randomBox(rng));
        const BoxIndex index(boxes);
        size_t found = 0;
        for (int q = 0; q < 300; ++q) {
            // Some queries are the set's own boxes, which they touch.
            const Bounds3 query = q % 3 == 0 ? boxes[size_t(rng.index(count))] : randomBox(rng);
            std::vector<uint32_t> got;
            index.forEachOverlapping(query, [&](uint32_t id) { got.push_back(id); });
            std::sort(got.begin(), got.end());
            std::vector<uint32_t> want;
            for (uint32_t i = 0; i < boxes.size(); ++i)
                if (overlaps(boxes[i], query)) want.push_back(i);
            ASSERT_EQ(got, want) << count << " boxes, query " << q;
            found += got.size();
        }
        // Queries met boxes: their own at least, and in the crowded set many more.
        EXPECT_GE(found, 100u) << count;
        if (count == 5000) {
            EXPECT_GT(found, 1000u);
        }
    }
}

TEST(BoxIndex, AnEmptySetReportsNothing) {
    const BoxIndex index(std::vector<Bounds3>{});
    int calls = 0;
    index.forEachOverlapping(Bounds3{Vec3(0.0), Vec3(1.0)}, [&](uint32_t) { ++calls; });
    EXPECT_EQ(calls, 0);
}

}  // namespace
}  // namespace csg
