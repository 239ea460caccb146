// Boxes and slab tests: Bounds4 keeps each box inside the floats around it; clipToBoxes (four
// boxes at once, the wide BVH's test) gives clipToBox's answer and entry on the boxes as stored
// bit for bit, on ordinary and on degenerate rays and boxes; overlapBoxes gives overlap()'s
// answer for each of four boxes.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <limits>

#include "primitives/base/Bounds4.h"
#include "tests/SeededRng.h"

namespace csg {
namespace {

// A coordinate that is sometimes exactly 0, +-0, an integer, or infinite: the cases where a
// slab's products are NaN (0 * inf) or its bounds coincide with the origin.
double awkward(testing::Rng& rng) {
    switch (rng.index(8)) {
        case 0:
            return 0.0;
        case 1:
            return -0.0;
        case 2:
            return double(rng.integer(-2, 2));
        case 3:
            return rng.chance(0.5) ? kInfinity : -kInfinity;
        default:
            return rng.uniform(-3.0, 3.0);
    }
}

// A stored box is the tightest box of floats around the given one: each bound is the float on
// its outer side, or the bound itself when it is a float; beyond float's range it goes to
// FLT_MAX or infinity.
TEST(Bounds, FourBoxesAreStoredRoundedOut) {
    constexpr double kFloatMax = std::numeric_limits<float>::max();
    testing::Rng rng(46);
    int inexact = 0;
    for (int trial = 0; trial < 100000; ++trial) {
        const double scale = std::ldexp(1.0, rng.integer(-140, 140));
        Bounds3 box;
        for (int a = 0; a < 3; ++a) {
            box.lo[a] = rng.uniform(-2.0, 1.0) * scale;
            box.hi[a] = box.lo[a] + rng.uniform(0.0, 1.0) * scale;
        }
        Bounds4 wide;
        const int k = rng.integer(0, 3);
        wide.set(k, box);
        const Bounds3 stored = wide.box(k);
        for (int a = 0; a < 3; ++a) {
            const double lo = box.lo[a], hi = box.hi[a];
            ASSERT_LE(stored.lo[a], lo) << trial;
            ASSERT_GE(stored.hi[a], hi) << trial;
            // No float lies strictly between the stored bound and the given one.
            const float lo32 = float(stored.lo[a]), hi32 = float(stored.hi[a]);
            if (lo >= -kFloatMax)
                ASSERT_GT(double(std::nextafter(lo32, float(kInfinity))), lo) << trial;
            else
                ASSERT_EQ(stored.lo[a], -kInfinity) << trial;
            if (hi <= kFloatMax)
                ASSERT_LT(double(std::nextafter(hi32, -float(kInfinity))), hi) << trial;
            else
                ASSERT_EQ(stored.hi[a], kInfinity) << trial;
            inexact += stored.lo[a] != lo;
        }
    }
    EXPECT_GT(inexact, 200000);  // nearly every double is rounded
    // Floats and infinities are kept as they are.
    Bounds4 wide;
    wide.set(2, {{0.5, -kInfinity, 0.0}, {kInfinity, 3.0, -0.0}});
    EXPECT_EQ(wide.box(2).lo, Vec3(0.5, -kInfinity, 0.0));
    EXPECT_EQ(wide.box(2).hi, Vec3(kInfinity, 3.0, 0.0));
}

TEST(Bounds, FourBoxesAtOnceMatchOneAtATime) {
    testing::Rng rng(44);
    int hits = 0, misses = 0;
    for (int trial = 0; trial < 200000; ++trial) {
        // Integer-ish origins and directions put the ray in a box's face planes (0 * inf).
        const Vec3 o{awkward(rng), awkward(rng), awkward(rng)};
        const Vec3 d{awkward(rng), awkward(rng), awkward(rng)};
        if (!std::isfinite(o.x) || !std::isfinite(o.y) || !std::isfinite(o.z)) continue;
        const SlabRay ray(o, d);
        Bounds4 wide;
        for (int k = 0; k < 4; ++k) {
            Bounds3 box;
            for (int a = 0; a < 3; ++a) {
                box.lo[a] = awkward(rng), box.hi[a] = awkward(rng);
                if (rng.chance(0.9) && box.lo[a] > box.hi[a])
                    std::swap(box.lo[a], box.hi[a]);  // some stay empty
            }
            wide.set(k, box);
        }
        const double t0 = rng.chance(0.5) ? (rng.chance(0.5) ? 0.0 : -0.0) : rng.uniform(-1.0, 1.0);
        const double t1 = rng.chance(0.3) ? kInfinity : t0 + rng.uniform(0.0, 5.0);
        double near[4];
        const unsigned got = clipToBoxes(ray, wide, t0, t1, near);
        for (int k = 0; k < 4; ++k) {
            double a = t0, b = t1;
            const bool want = clipToBox(ray, wide.box(k), a, b);
            ASSERT_EQ((got >> k & 1u) != 0, want) << "trial " << trial << " box " << k;
            if (want) {
                // Same bits (+0 and -0 apart): the walk skips a slot by this entry.
                ASSERT_EQ(std::bit_cast<uint64_t>(near[k]), std::bit_cast<uint64_t>(a))
                    << "trial " << trial << " box " << k;
            }
            (want ? hits : misses)++;
        }
    }
    // Both answers occur often enough for the comparison to mean something.
    EXPECT_GT(hits, 50000);
    EXPECT_GT(misses, 50000);
}

// Boxes with integer corners touch, nest and miss often; empty and infinite ones too.
TEST(Bounds, FourOverlapsAtOnceMatchOneAtATime) {
    testing::Rng rng(45);
    int overlapping = 0, apart = 0;
    for (int trial = 0; trial < 100000; ++trial) {
        Bounds3 query;
        for (int a = 0; a < 3; ++a) {
            query.lo[a] = awkward(rng);
            query.hi[a] = awkward(rng);
            if (rng.chance(0.9) && query.lo[a] > query.hi[a]) std::swap(query.lo[a], query.hi[a]);
        }
        Bounds4 wide;
        for (int k = 0; k < 4; ++k) {
            Bounds3 box;
            for (int a = 0; a < 3; ++a) {
                box.lo[a] = awkward(rng), box.hi[a] = awkward(rng);
                if (rng.chance(0.9) && box.lo[a] > box.hi[a]) std::swap(box.lo[a], box.hi[a]);
            }
            wide.set(k, box);
        }
        const unsigned got = overlapBoxes(wide, query);
        for (int k = 0; k < 4; ++k) {
            const bool want = !overlap(wide.box(k), query).empty();
            ASSERT_EQ((got >> k & 1u) != 0, want) << "trial " << trial << " box " << k;
            (want ? overlapping : apart)++;
        }
    }
    EXPECT_GT(overlapping, 50000);
    EXPECT_GT(apart, 50000);
}

}  // namespace
}  // namespace csg
