// The Groebner method as `method = "groebner"` runs it (issue 23): the floating-point basis
// (Groebner.h, the article's method with csgray's polish), its answer certified by interval
// arithmetic (PatchCertify.h: every crossing alone in a Krawczyk box, no other anywhere on
// the patch); where the certificate fails (a breakdown, a missed or spurious crossing, a
// tangent ray, a crossing within the slack of an edge), the exact basis (GroebnerExact.h).
// So the answer is always the exact method's crossings, up to the rounding of t.
#pragma once

#include <cstdint>

#include "primitives/patch/BezierPatch.h"

namespace csg {

// Which pass answered, for the benchmark and tests.
struct CertifiedGroebnerStats {
    bool certified = false;  // the float pass, proved; false: the exact pass answered
    int pieces = 0;          // pieces the certificate's exclusion examined
};

// The crossings of the line o + t d with patch; contract as in BezierPatch.h.
int intersectByCertifiedGroebner(const BezierPatch& patch, const Vec3& o, const Vec3& d,
                                 PatchCrossings& out, CertifiedGroebnerStats* stats = nullptr);

// Process-wide counts of the passes that answered intersectByCertifiedGroebner (relaxed
// atomics, touched only by this method), for a caller that wants totals over a render;
// nothing prints them yet (patch_bench counts per call, CertifiedGroebnerStats).
struct GroebnerPassCounts {
    uint64_t certified = 0, exact = 0;
};
GroebnerPassCounts groebnerPassCounts();
void resetGroebnerPassCounts();

}  // namespace csg
