// Test and benchmark support: the seeded random source of the randomized tests and of
// bench/torus_sweep, so that a seed names the same cases on every standard library and compiler.
// Not for product code.
#pragma once

#include <cmath>
#include <cstdint>
#include <random>

#include "primitives/base/Math.h"

namespace csg::testing {

// A seed names the same cases everywhere only if each value is drawn in its own statement or
// braced-list element: the operands of + and * and the arguments of a call are unsequenced, so
// rng.unit() * std::pow(10.0, rng.uniform()) draws in an order of the compiler's choosing.
class Rng {
public:
    explicit Rng(uint64_t seed) : gen_(seed) {}

    // Built from raw bits: std::uniform_real_distribution (and uniform_int_distribution)
    // differ between standard libraries; std::mt19937_64's sequence does not.
    // Uniform in [0, 1): the top 53 bits of one draw.
    double uniform() { return double(gen_() >> 11) * 0x1.0p-53; }
    double uniform(double a, double b) { return a + (b - a) * uniform(); }
    bool chance(double p) { return uniform() < p; }
    // 0 .. n - 1 (n > 0) from one draw; the modulo bias is below n / 2^64.
    int index(int n) { return int(gen_() % uint64_t(n)); }
    // lo .. hi inclusive.
    int integer(int lo, int hi) { return lo + index(hi - lo + 1); }

    // Vectors draw x, then y, then z: a braced list is evaluated in order, while the arguments
    // of a call or of Vec3(...) are not (gcc draws z first).
    Vec3 inBox(const Vec3& lo, const Vec3& hi) {
        return {uniform(lo.x, hi.x), uniform(lo.y, hi.y), uniform(lo.z, hi.z)};
    }
    // Uniform in the unit ball, by rejection from the cube.
    Vec3 inBall() {
        for (;;) {
            const Vec3 v = inBox(Vec3(-1.0), Vec3(1.0));
            if (glm::dot(v, v) <= 1.0) return v;
        }
    }
    // A uniformly random unit vector: a point of the ball, away from the centre, normalized.
    Vec3 unit() {
        for (;;) {
            const Vec3 v = inBox(Vec3(-1.0), Vec3(1.0));
            const double l2 = glm::dot(v, v);
            if (l2 > 1e-4 && l2 <= 1.0) return v / std::sqrt(l2);
        }
    }

private:
    std::mt19937_64 gen_;
};

}  // namespace csg::testing
