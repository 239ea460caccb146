// Four axis-aligned boxes against one ray in one go: the slab test of a wide BVH node's
// children. Lanes are GCC/Clang vector-extension doubles, so a build for x86-64-v3 tests the
// four boxes with AVX2 and a generic build with SSE2 pairs, from the same source.
#pragma once

#include <cstdint>
#include <cstring>

#include "csg/Bounds.h"

#if defined(__AVX__)
#include <immintrin.h>
#endif

namespace csg {

using Double4 = double __attribute__((vector_size(32)));
using Mask4 = int64_t __attribute__((vector_size(32)));  // a lane is all ones or all zeros

// Four boxes by axis and lane: box k is [lo[a][k], hi[a][k]] on axis a.
struct Bounds4 {
    Double4 lo[3];
    Double4 hi[3];
};

inline Double4 broadcast4(double x) {
    return Double4{x, x, x, x};
}

// Lane by lane a < b ? a : b and a > b ? a : b, so b when either is NaN: x86's minpd and
// maxpd, one instruction each where a comparison and a blend would take two or three.
inline Double4 min4(Double4 a, Double4 b) {
#if defined(__AVX__)
    return Double4(_mm256_min_pd(__m256d(a), __m256d(b)));
#else
    const Mask4 less = a < b;
    return Double4((less & Mask4(a)) | (~less & Mask4(b)));
#endif
}
inline Double4 max4(Double4 a, Double4 b) {
#if defined(__AVX__)
    return Double4(_mm256_max_pd(__m256d(a), __m256d(b)));
#else
    const Mask4 greater = a > b;
    return Double4((greater & Mask4(a)) | (~greater & Mask4(b)));
#endif
}

// Bit k set when lane k of m is set.
inline unsigned maskBits4(Mask4 m) {
#if defined(__AVX__)
    return unsigned(_mm256_movemask_pd(__m256d(m)));
#else
    return unsigned(m[0] & 1) | unsigned(m[1] & 2) | unsigned(m[2] & 4) | unsigned(m[3] & 8);
#endif
}

// clipToBox (Bounds.h) on four boxes at once: the same operations in the same order on every
// lane (NaN rules, widening), so bit k of the result is set exactly when clipToBox(r, box k,
// t0, t1) would return true, and tNear[k] is the t0 it would leave (the widened entry).
inline unsigned clipToBoxes(const SlabRay& r, const Bounds4& b, double t0, double t1,
                            double (&tNear)[4]) {
    Double4 near0 = broadcast4(t0), far1 = broadcast4(t1);
    for (int a = 0; a < 3; ++a) {
        const Double4 o = broadcast4(r.o[a]), invD = broadcast4(r.invD[a]);
        const Double4 n = (b.lo[a] - o) * invD;
        const Double4 f = (b.hi[a] - o) * invD;
        // clipToBox's swap when n > f, and its updates that keep the running bound unless the
        // candidate beats it (a NaN candidate never does), as min4/max4 with those operands.
        const Double4 tNearA = min4(f, n), tFarA = max4(n, f);
        near0 = max4(tNearA, near0);
        far1 = min4(tFarA, far1);
    }
    constexpr double kDown = 1.0 - tol::kSlabWiden, kUp = 1.0 + tol::kSlabWiden;
    near0 = min4(near0 * kUp, near0 * kDown);  // std::min(down, up) is up < down ? up : down
    far1 = max4(far1 * kUp, far1 * kDown);     // std::max(down, up) is down < up ? up : down
    std::memcpy(tNear, &near0, sizeof tNear);
    return maskBits4(near0 <= far1);
}

}  // namespace csg
