#include "primitives/patch/GroebnerCertified.h"

#include <atomic>

#include "primitives/patch/Groebner.h"
#include "primitives/patch/GroebnerExact.h"
#include "primitives/patch/PatchCertify.h"

namespace csg {

namespace {

std::atomic<uint64_t> certifiedCount{0}, exactCount{0};

}  // namespace

int intersectByCertifiedGroebner(const BezierPatch& patch, const Vec3& o, const Vec3& d,
                                 PatchCrossings& out, CertifiedGroebnerStats* stats) {
    CertifiedGroebnerStats local;
    CertifiedGroebnerStats& st = stats ? *stats : local;
    st = CertifiedGroebnerStats{};
    // Step 1: the float pass; a breakdown is no answer to certify.
    GroebnerStats gs;
    const int n = intersectByGroebner(patch, o, d, out, &gs);
    if (!gs.breakdown) {
        // Step 2: its crossings proved to be all of them, each simple.
        CertifyStats cs;
        st.certified = certifyCrossings(patch, o, d, out, n, &cs);
        st.pieces = cs.pieces;
        if (st.certified) {
            certifiedCount.fetch_add(1, std::memory_order_relaxed);
            return n;
        }
    }
    // Step 3: the exact pass.
    exactCount.fetch_add(1, std::memory_order_relaxed);
    return intersectByExactGroebner(patch, o, d, out);
}

GroebnerPassCounts groebnerPassCounts() {
    return {certifiedCount.load(std::memory_order_relaxed),
            exactCount.load(std::memory_order_relaxed)};
}

void resetGroebnerPassCounts() {
    certifiedCount = 0;
    exactCount = 0;
}

}  // namespace csg
