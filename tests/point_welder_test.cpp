// PointWelder against a std::map of the same positions: indices in order of first appearance,
// -0 and +0 one position that keeps the value it first came with, and the table's growth from
// its smallest size through tens of thousands of positions.
#include <gtest/gtest.h>

#include <array>
#include <bit>
#include <map>
#include <vector>

#include "primitives/base/PointWelder.h"
#include "tests/SeededRng.h"

namespace csg {
namespace {

TEST(PointWelder, NumbersPositionsInOrderOfFirstAppearance) {
    testing::Rng rng(5);
    // Points of a small lattice, so most repeat; a zero coordinate comes as +0 or -0.
    std::vector<Vec3> points(200000);
    for (Vec3& p : points)
        for (int a = 0; a < 3; ++a) {
            const int k = rng.integer(-20, 20);
            p[a] = k == 0 ? (rng.chance(0.5) ? 0.0 : -0.0) : 0.25 * k;
        }
    PointWelder welder;  // the smallest table: it grows all the way
    std::vector<uint32_t> got(points.size());
    for (size_t i = 0; i < points.size(); ++i) got[i] = welder.add(points[i]);
    const std::vector<Vec3> distinct = welder.take();

    std::map<std::array<double, 3>, uint32_t> firstIndex;  // -0 < +0 is false: one key
    std::vector<Vec3> expected;
    for (size_t i = 0; i < points.size(); ++i) {
        const Vec3& p = points[i];
        const auto [at, added] =
            firstIndex.emplace(std::array<double, 3>{p.x, p.y, p.z}, uint32_t(expected.size()));
        if (added) expected.push_back(p);
        ASSERT_EQ(got[i], at->second) << "point " << i;
    }
    ASSERT_GT(expected.size(), 30000u);
    ASSERT_EQ(distinct.size(), expected.size());
    for (size_t v = 0; v < expected.size(); ++v)
        for (int a = 0; a < 3; ++a)  // bit for bit: the first zero's sign is kept
            ASSERT_EQ(std::bit_cast<uint64_t>(distinct[v][a]),
                      std::bit_cast<uint64_t>(expected[v][a]))
                << "position " << v;
    EXPECT_EQ(welder.size(), 0u);
    EXPECT_EQ(welder.add(points[0]), 0u);  // emptied by take(), it starts again
}

}  // namespace
}  // namespace csg
