// The exact and the certified Groebner methods (issue 23; primitives/patch/GroebnerExact.h,
// GroebnerCertified.h, PatchCertify.h) against an oracle that does not use them: the
// crossings the resultant and clipping methods find, each refined by 50-digit Newton on
// S(u, v) = o + t d (tests/PatchReference.h), merged. The exact method's own crossings are
// refined too and must land on a reference crossing (so a crossing the other two both miss
// is not held against it, and a spurious one is caught: Newton from it converges elsewhere).
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "primitives/patch/Clip.h"
#include "primitives/patch/Groebner.h"
#include "primitives/patch/GroebnerExact.h"
#include "primitives/patch/Resultant.h"
#include "tests/PatchReference.h"

namespace csg {
namespace {

using patchref::Big;

double relError(double t, double ref) {
    return std::abs(t - ref) / std::max(1.0, std::abs(ref));
}

// A crossing refined in 50 digits; false when Newton does not converge or leaves the square.
bool refined(const BezierPatch& patch, const Vec3& o, const Vec3& d, const PatchCrossing& c,
             double& t) {
    double u = c.u, v = c.v;
    Big T = c.t;
    if (!patchref::refine(patch, o, d, u, v, T)) return false;
    const double s = 1e-9;
    if (!(u >= -s && u <= 1 + s && v >= -s && v <= 1 + s)) return false;
    t = double(T);
    return true;
}

// The reference t of every crossing of the ray: the refined crossings of all lists, merged.
std::vector<double> referenceCrossings(
    const BezierPatch& patch, const Vec3& o, const Vec3& d,
    const std::vector<std::pair<const PatchCrossings*, int>>& lists) {
    std::vector<double> ts;
    for (const auto& [list, n] : lists)
        for (int k = 0; k < n; ++k) {
            double t;
            if (!refined(patch, o, d, (*list)[k], t)) continue;
            bool seen = false;
            for (double x : ts) seen = seen || relError(x, t) <= 1e-9;
            if (!seen) ts.push_back(t);
        }
    return ts;
}

// True when crossings[0..n) and ref are the same set of t (to 1e-9 relative), one to one.
bool sameCrossings(const PatchCrossings& c, int n, const std::vector<double>& ref) {
    if (n != int(ref.size())) return false;
    for (double r : ref) {
        bool found = false;
        for (int k = 0; k < n && !found; ++k) found = relError(c[k].t, r) <= 1e-9;
        if (!found) return false;
    }
    return true;
}

TEST(ExactGroebner, AgreesWithTheReferenceOnRandomBicubicPatches) {
    std::mt19937_64 rng(2023);
    const int kRays = 2000;
    int wrong = 0, crossings = 0, degree18 = 0, swapped = 0;
    const auto start = std::chrono::steady_clock::now();
    for (int r = 0; r < kRays; ++r) {
        const BezierPatch patch = patchref::randomPatch(rng);
        Vec3 o, d;
        patchref::randomRay(rng, patch, o, d);
        PatchCrossings res, clip, exact;
        const int nr = intersectByResultant(patch, o, d, res);
        const int nc = intersectByClip(patch, o, d, clip);
        ExactGroebnerStats stats;
        const int ne = intersectByExactGroebner(patch, o, d, exact, &stats);
        degree18 += stats.uDegree == 18;
        swapped += stats.swapped;
        const std::vector<double> ref =
            referenceCrossings(patch, o, d, {{&res, nr}, {&clip, nc}, {&exact, ne}});
        crossings += int(ref.size());
        if (!sameCrossings(exact, ne, ref)) {
            ++wrong;
            if (wrong <= 5)
                ADD_FAILURE() << "ray " << r << ": exact " << ne << " crossings, reference "
                              << ref.size() << " (resultant " << nr << ", clip " << nc << ")";
        }
    }
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::printf(
        "exact groebner: %d random bicubic rays, %d crossings, eliminant degree 18 on %d, "
        "%d wrong; %.2f ms per ray (all three methods and the reference)\n",
        kRays, crossings, degree18, wrong, 1e3 * seconds / kRays);
    EXPECT_EQ(wrong, 0);
    EXPECT_GE(degree18, kRays * 9 / 10);  // the general case, not a degenerate one
    EXPECT_GE(crossings, kRays / 2);
}

}  // namespace
}  // namespace csg
