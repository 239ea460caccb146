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
#include "primitives/patch/GroebnerCertified.h"
#include "primitives/patch/GroebnerExact.h"
#include "primitives/patch/PatchCertify.h"
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

// A patch of bidegree (du, dv), degree-elevated to bicubic in doubles (so its higher
// coefficients are rounding residue, which the exact method sees as data).
BezierPatch patchOfBidegree(std::mt19937_64& rng, int du, int dv) {
    std::uniform_real_distribution<double> c(-1.0, 1.0);
    std::array<std::array<Vec3, 4>, 4> a{};
    for (int k = 0; k <= du; ++k)
        for (int l = 0; l <= dv; ++l) a[k][l] = Vec3(0.3 * c(rng), 0.3 * c(rng), c(rng));
    a[1][0] += Vec3(1, 0, 0);
    a[0][1] += Vec3(0, 1, 0);
    return patchref::fromMonomials(a);
}

// A ray that grazes the patch: through S(u, v) along a tangent direction, tilted off the
// tangent plane by `tilt` (0: tangent; small: two crossings at nearly the same point).
void grazingRay(std::mt19937_64& rng, const BezierPatch& patch, double tilt, Vec3& o, Vec3& d) {
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    const double u = 0.1 + 0.8 * unit(rng), v = 0.1 + 0.8 * unit(rng), a = 6.283 * unit(rng);
    const Vec3 su = patch.du(u, v), sv = patch.dv(u, v);
    const Vec3 n = glm::normalize(glm::cross(su, sv));
    const Vec3 tangent = glm::normalize(std::cos(a) * su + std::sin(a) * sv);
    d = glm::normalize(tangent + tilt * n);
    o = patch.eval(u, v) - 2.0 * d;
}

TEST(ExactGroebner, AgreesWithTheReferenceAtEveryBidegreeAndOnGrazingRays) {
    std::mt19937_64 rng(23);
    const int shapes[][2] = {{1, 1}, {2, 1}, {1, 2}, {3, 1}, {1, 3}, {2, 2}, {3, 2}, {2, 3}};
    int wrong = 0, rays = 0;
    auto check = [&](const BezierPatch& patch, const Vec3& o, const Vec3& d, const char* what) {
        PatchCrossings res, clip, exact;
        const int nr = intersectByResultant(patch, o, d, res);
        const int nc = intersectByClip(patch, o, d, clip);
        const int ne = intersectByExactGroebner(patch, o, d, exact);
        const std::vector<double> ref =
            referenceCrossings(patch, o, d, {{&res, nr}, {&clip, nc}, {&exact, ne}});
        ++rays;
        if (!sameCrossings(exact, ne, ref) && ++wrong <= 5)
            ADD_FAILURE() << what << ": exact " << ne << " crossings, reference " << ref.size();
    };
    for (const auto& shape : shapes)
        for (int r = 0; r < 60; ++r) {
            const BezierPatch patch = patchOfBidegree(rng, shape[0], shape[1]);
            Vec3 o, d;
            patchref::randomRay(rng, patch, o, d);
            check(patch, o, d, "bidegree ray");
        }
    // Tilted off the tangent plane by 1e-3: two crossings 1e-3 apart, a near-double root that
    // the float methods find only to ~sqrt(ulp).
    for (int r = 0; r < 150; ++r) {
        const BezierPatch patch = patchref::randomPatch(rng);
        Vec3 o, d;
        grazingRay(rng, patch, 1e-3, o, d);
        check(patch, o, d, "grazing ray");
    }
    std::printf("exact groebner: %d rays at bidegrees (1,1)..(2,3) and grazing, %d wrong\n", rays,
                wrong);
    EXPECT_EQ(wrong, 0);
}

// Two patches of the Utah teapot (samples/teapot.scad): a body patch, nearly a surface of
// revolution, and a bottom patch with a pole (its u = 0 edge is one point). Their eliminants
// have degree 13-15 (crossings at infinity), so the shape basis' proof fails and Buchberger
// runs; v = h(u) there is so ill-conditioned in u that a u right to 110 bits gave v off by
// 1e-5 until u was refined adaptively.
TEST(ExactGroebner, AgreesWithTheReferenceOnTeapotPatchesWithAPoleOrRevolution) {
    const double body[4][4][3] = {
        {{0, 1.5, 2.4}, {0.84, 1.5, 2.4}, {1.5, 0.84, 2.4}, {1.5, 0, 2.4}},
        {{0, 1.75, 1.875}, {0.98, 1.75, 1.875}, {1.75, 0.98, 1.875}, {1.75, 0, 1.875}},
        {{0, 2, 1.35}, {1.12, 2, 1.35}, {2, 1.12, 1.35}, {2, 0, 1.35}},
        {{0, 2, 0.9}, {1.12, 2, 0.9}, {2, 1.12, 0.9}, {2, 0, 0.9}}};
    const double bottom[4][4][3] = {
        {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}, {0, 0, 0}},
        {{0, -1.425, 0}, {0.798, -1.425, 0}, {1.425, -0.798, 0}, {1.425, 0, 0}},
        {{0, -1.5, 0.075}, {0.84, -1.5, 0.075}, {1.5, -0.84, 0.075}, {1.5, 0, 0.075}},
        {{0, -1.5, 0.15}, {0.84, -1.5, 0.15}, {1.5, -0.84, 0.15}, {1.5, 0, 0.15}}};
    std::mt19937_64 rng(32);
    int wrong = 0, rays = 0, buchberger = 0;
    for (const auto* points : {body, bottom}) {
        BezierPatch patch;
        for (int i = 0; i < 4; ++i)
            for (int j = 0; j < 4; ++j)
                patch.points[4 * i + j] = Vec3(points[i][j][0], points[i][j][1], points[i][j][2]);
        for (int r = 0; r < 150; ++r) {
            Vec3 o, d;
            patchref::randomRay(rng, patch, o, d);
            PatchCrossings res, clip, exact;
            const int nr = intersectByResultant(patch, o, d, res);
            const int nc = intersectByClip(patch, o, d, clip);
            ExactGroebnerStats stats;
            const int ne = intersectByExactGroebner(patch, o, d, exact, &stats);
            buchberger += !stats.shapeBasis;
            const std::vector<double> ref =
                referenceCrossings(patch, o, d, {{&res, nr}, {&clip, nc}, {&exact, ne}});
            ++rays;
            if (!sameCrossings(exact, ne, ref) && ++wrong <= 5)
                ADD_FAILURE() << "ray " << r << ": exact " << ne << " crossings, reference "
                              << ref.size();
        }
    }
    std::printf("exact groebner: %d teapot rays (Buchberger on %d), %d wrong\n", rays, buchberger,
                wrong);
    EXPECT_EQ(wrong, 0);
    EXPECT_GT(buchberger, 0);  // the path this test is for
}

// ---- The certified pass ----

// Whenever the certificate holds, the float pass' answer has the exact method's crossings:
// the same count (the promise) and the same t. Random patches of every bidegree, and rays
// grazing at 0, 1e-8 and 1e-4 off the tangent plane (double and near-double roots, where a
// float answer is most often wrong and must then not be certified).
TEST(CertifiedGroebner, NeverCertifiesAWrongRootCount) {
    std::mt19937_64 rng(2311);
    const int shapes[][2] = {{1, 1}, {2, 1}, {3, 1}, {2, 2}, {3, 2}, {3, 3}};
    const double tilts[] = {-1.0, 0.0, 1e-8, 1e-4};  // -1: a random ray through the box
    int rays = 0, certified = 0, wrongCount = 0, wrongT = 0;
    for (const auto& shape : shapes)
        for (double tilt : tilts)
            for (int r = 0; r < 50; ++r) {
                const BezierPatch patch = patchOfBidegree(rng, shape[0], shape[1]);
                Vec3 o, d;
                if (tilt < 0.0)
                    patchref::randomRay(rng, patch, o, d);
                else
                    grazingRay(rng, patch, tilt, o, d);
                PatchCrossings fl, exact;
                GroebnerStats gs;
                const int nf = intersectByGroebner(patch, o, d, fl, &gs);
                ++rays;
                if (gs.breakdown || !certifyCrossings(patch, o, d, fl, nf)) continue;
                ++certified;
                const int ne = intersectByExactGroebner(patch, o, d, exact);
                if (nf != ne) {
                    if (++wrongCount <= 5)
                        ADD_FAILURE() << "bidegree (" << shape[0] << ", " << shape[1] << "), tilt "
                                      << tilt << ": certified " << nf << " crossings, exact " << ne;
                    continue;
                }
                for (int k = 0; k < nf; ++k) wrongT += relError(fl[k].t, exact[k].t) > 1e-9;
            }
    std::printf("certified groebner: %d rays, certified %d, wrong count %d, wrong t %d\n", rays,
                certified, wrongCount, wrongT);
    EXPECT_EQ(wrongCount, 0);
    EXPECT_EQ(wrongT, 0);
    EXPECT_GE(certified, rays / 6);  // not vacuous: measured 266 of 1200 (ruled patches mostly)
}

// The certificate refuses a list with a crossing left out, or one added: it proves the list,
// not merely each entry.
TEST(CertifiedGroebner, RefusesAListWithACrossingMissingOrAdded) {
    std::mt19937_64 rng(5);
    int tried = 0, refusedMissing = 0, refusedAdded = 0, acceptedRight = 0;
    for (int r = 0; r < 400 && tried < 100; ++r) {
        const BezierPatch patch = patchref::randomPatch(rng);
        Vec3 o, d;
        patchref::randomRay(rng, patch, o, d);
        PatchCrossings exact;
        const int ne = intersectByExactGroebner(patch, o, d, exact);
        if (ne == 0 || ne == kMaxPatchCrossings) continue;
        ++tried;
        acceptedRight += certifyCrossings(patch, o, d, exact, ne);
        PatchCrossings less = exact;
        refusedMissing += !certifyCrossings(patch, o, d, less, ne - 1);  // the last one dropped
        PatchCrossings more = exact;
        more[ne] = {0.0, 0.5 * (exact[0].u + 0.37), 0.5 * (exact[0].v + 0.61)};  // not a root
        refusedAdded += !certifyCrossings(patch, o, d, more, ne + 1);
    }
    std::printf(
        "certificate: %d rays with crossings: exact list proved on %d, list missing one "
        "refused on %d, list with a non-root refused on %d\n",
        tried, acceptedRight, refusedMissing, refusedAdded);
    EXPECT_EQ(refusedMissing, tried);
    EXPECT_EQ(refusedAdded, tried);
    EXPECT_GE(acceptedRight, tried * 9 / 10);  // the right list is proved on most rays
}

// method = "groebner": the certified pass or the exact one, right on every ray.
TEST(CertifiedGroebner, AgreesWithTheReferenceOnRandomBicubicPatches) {
    std::mt19937_64 rng(99);
    const int kRays = 1000;
    int wrong = 0, certified = 0;
    for (int r = 0; r < kRays; ++r) {
        const BezierPatch patch = patchref::randomPatch(rng);
        Vec3 o, d;
        patchref::randomRay(rng, patch, o, d);
        PatchCrossings res, clip, g;
        const int nr = intersectByResultant(patch, o, d, res);
        const int nc = intersectByClip(patch, o, d, clip);
        CertifiedGroebnerStats stats;
        const int ng = intersectByCertifiedGroebner(patch, o, d, g, &stats);
        certified += stats.certified;
        const std::vector<double> ref =
            referenceCrossings(patch, o, d, {{&res, nr}, {&clip, nc}, {&g, ng}});
        if (!sameCrossings(g, ng, ref) && ++wrong <= 5)
            ADD_FAILURE() << "ray " << r << ": " << ng << " crossings, reference " << ref.size();
    }
    std::printf("method groebner: %d random bicubic rays, %d certified float, %d exact, %d wrong\n",
                kRays, certified, kRays - certified, wrong);
    EXPECT_EQ(wrong, 0);
}

}  // namespace
}  // namespace csg
