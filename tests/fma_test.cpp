// Tests of fusedMultiplyAdd (primitives/base/Fma.h): one rounding of a * b + c, whichever path it
// takes. The references are exact values worked out by hand from dyadic inputs, and libm's fma on
// seeded random inputs (an independent implementation of the same exactly rounded operation).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <random>

#include "primitives/base/Fma.h"

namespace csg {
namespace {

uint64_t bitsOf(double x) {
    uint64_t u;
    std::memcpy(&u, &x, sizeof u);
    return u;
}

TEST(FusedMultiplyAdd, RoundsOnceWhereTheUnfusedFormLosesTheResult) {
    // (1 + 2^-30)(1 - 2^-30) - 1 = -2^-60 exactly; the rounded product is 1, which gives 0.
    const double e = std::ldexp(1.0, -30);
    volatile double a = 1.0 + e, b = 1.0 - e, c = -1.0;  // volatile: no folding at compile time
    EXPECT_EQ(fusedMultiplyAdd(a, b, c), -std::ldexp(1.0, -60));
    volatile double roundedProduct = a * b;  // volatile: not contracted into an fma either
    EXPECT_EQ(roundedProduct + c, 0.0) << "the inputs no longer show the difference fma makes";
}

TEST(FusedMultiplyAdd, KeepsTheSignOfAnExactZero) {
    volatile double zero = 0.0, one = 1.0;
    EXPECT_TRUE(std::signbit(fusedMultiplyAdd(-zero, one, -zero)));
    EXPECT_FALSE(std::signbit(fusedMultiplyAdd(one, one, -one)));  // x - x is +0
}

TEST(FusedMultiplyAdd, PassesInfinityAndNanThrough) {
    const double inf = std::numeric_limits<double>::infinity();
    volatile double zero = 0.0, two = 2.0;
    EXPECT_EQ(fusedMultiplyAdd(two, inf, two), inf);
    EXPECT_TRUE(std::isnan(fusedMultiplyAdd(zero, inf, two)));
}

TEST(FusedMultiplyAdd, MatchesLibmBitForBitOnRandomInputs) {
    // Products that nearly cancel the addend are where a double rounding would show.
    std::mt19937_64 rng(20261122);
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    std::uniform_int_distribution<int> exponent(-40, 40);
    for (int i = 0; i < 100000; ++i) {
        const double a = std::ldexp(unit(rng), exponent(rng));
        const double b = std::ldexp(unit(rng), exponent(rng));
        const double c = i % 2 ? -a * b * (1.0 + std::ldexp(unit(rng), -40)) : unit(rng);
        ASSERT_EQ(bitsOf(fusedMultiplyAdd(a, b, c)), bitsOf(std::fma(a, b, c)))
            << "a=" << a << " b=" << b << " c=" << c;
    }
}

}  // namespace
}  // namespace csg
