// Four axis-aligned boxes against one ray in one go: the slab test of a wide BVH node's
// children. Lanes are GCC/Clang vector extensions (boxes stored as floats, tested as doubles),
// so a build for x86-64-v3 tests the four boxes with AVX2 and a generic build with SSE2 pairs,
// from the same source.
#pragma once

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>

#include "primitives/base/Bounds.h"

#if defined(__AVX__)
#include <immintrin.h>
#endif

namespace csg {

using Double4 = double __attribute__((vector_size(32)));
using Float4 = float __attribute__((vector_size(16)));

// The largest float no greater than x, and the smallest no less (x beyond float's range goes
// to FLT_MAX or infinity on its side; NaN stays NaN).
inline float floatBelow(double x) {
    const float f = static_cast<float>(x);
    return static_cast<double>(f) > x ? std::nextafter(f, -std::numeric_limits<float>::infinity())
                                      : f;
}
inline float floatAbove(double x) {
    const float f = static_cast<float>(x);
    return static_cast<double>(f) < x ? std::nextafter(f, std::numeric_limits<float>::infinity())
                                      : f;
}

// Four boxes by axis and lane: box k is [lo[a][k], hi[a][k]] on axis a. Stored as floats,
// each box rounded outward to the floats around it (set), so that a wide BVH node is two cache
// lines, not four: half the memory of a large union's tree (67 MB instead of 134 for 10^6
// objects; no change in speed measured, bench/README.md "BVH nodes with float boxes"), and a
// looser box only ever costs a test. The tests below widen the lanes to doubles and answer for
// the boxes as stored (box(k)).
struct Bounds4 {
    Float4 lo[3];
    Float4 hi[3];

    void set(int k, const Bounds3& box) {
        for (int a = 0; a < 3; ++a) {
            lo[a][k] = floatBelow(box.lo[a]);
            hi[a][k] = floatAbove(box.hi[a]);
        }
    }
    Bounds3 box(int k) const {
        return {{lo[0][k], lo[1][k], lo[2][k]}, {hi[0][k], hi[1][k], hi[2][k]}};
    }
};

// Four floats as four doubles, exactly: one vcvtps2pd under AVX (GCC 12 splits the generic
// conversion into halves).
inline Double4 widen4(const Float4& v) {
#if defined(__AVX__)
    return Double4(_mm256_cvtps_pd(__m128(v)));
#else
    return __builtin_convertvector(v, Double4);
#endif
}

// Lane by lane out = a < b ? a : b and out = a > b ? a : b, so b when either is NaN: x86's
// minpd and maxpd, one instruction each (from a ternary, GCC shares one comparison between a
// min and a max of the same pair and blends). Out-parameters, because a 32-byte vector passed
// or returned by value draws an ABI warning in a build without AVX.
inline void min4(Double4& out, const Double4& a, const Double4& b) {
#if defined(__AVX__)
    out = Double4(_mm256_min_pd(__m256d(a), __m256d(b)));
#else
    out = a < b ? a : b;
#endif
}
inline void max4(Double4& out, const Double4& a, const Double4& b) {
#if defined(__AVX__)
    out = Double4(_mm256_max_pd(__m256d(a), __m256d(b)));
#else
    out = a > b ? a : b;
#endif
}

// Which of the four boxes share a point with box (closed boxes: touching counts; an empty box
// shares none): bit k is set exactly when !overlap(b.box(k), box).empty() (Bounds.h), for boxes
// without NaN.
inline unsigned overlapBoxes(const Bounds4& b, const Bounds3& box) {
    if (box.empty()) return 0u;
    const auto lanes = [](double v) { return Double4{v, v, v, v}; };
    auto in = Double4{} == Double4{};  // all lanes true
    for (int a = 0; a < 3; ++a) {
        const Double4 lo = widen4(b.lo[a]), hi = widen4(b.hi[a]);
        in &= (lo <= lanes(box.hi[a])) & (hi >= lanes(box.lo[a])) & (lo <= hi);
    }
#if defined(__AVX__)
    return unsigned(_mm256_movemask_pd(__m256d(in)));
#else
    return unsigned(in[0] & 1) | unsigned(in[1] & 2) | unsigned(in[2] & 4) | unsigned(in[3] & 8);
#endif
}

// clipToBox (Bounds.h) on four boxes at once: the same operations in the same order on every
// lane (NaN rules, widening), so bit k of the result is set exactly when clipToBox(r,
// b.box(k), t0, t1) would return true, and tNear[k] is the t0 it would leave (the widened
// entry).
inline unsigned clipToBoxes(const SlabRay& r, const Bounds4& b, double t0, double t1,
                            double (&tNear)[4]) {
    Double4 near0 = {t0, t0, t0, t0}, far1 = {t1, t1, t1, t1};
    for (int a = 0; a < 3; ++a) {
        const double o = r.o[a], invD = r.invD[a];
        const Double4 n = (widen4(b.lo[a]) - Double4{o, o, o, o}) * Double4{invD, invD, invD, invD};
        const Double4 f = (widen4(b.hi[a]) - Double4{o, o, o, o}) * Double4{invD, invD, invD, invD};
        // clipToBox's swap when n > f, and its updates that keep the running bound unless the
        // candidate beats it (a NaN candidate never does).
        Double4 tNearA, tFarA;
        min4(tNearA, f, n);
        max4(tFarA, n, f);
        max4(near0, tNearA, near0);
        min4(far1, tFarA, far1);
    }
    constexpr double kDown = 1.0 - tol::kSlabWiden, kUp = 1.0 + tol::kSlabWiden;
    const Double4 down0 = near0 * kDown, up0 = near0 * kUp;
    const Double4 down1 = far1 * kDown, up1 = far1 * kUp;
    min4(near0, up0, down0);  // std::min(down0, up0) is up0 < down0 ? up0 : down0
    max4(far1, up1, down1);   // std::max(down1, up1) is down1 < up1 ? up1 : down1
    std::memcpy(tNear, &near0, sizeof tNear);
    const auto hit = near0 <= far1;  // lanes of all ones or all zeros
#if defined(__AVX__)
    return unsigned(_mm256_movemask_pd(__m256d(hit)));
#else
    return unsigned(hit[0] & 1) | unsigned(hit[1] & 2) | unsigned(hit[2] & 4) |
           unsigned(hit[3] & 8);
#endif
}

}  // namespace csg
