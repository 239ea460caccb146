// The ray/patch methods measured: per method and patch class, rays per second and the error
// distribution of t against a 50-digit reference, with missed and spurious crossings; for the
// algebraic methods, the u-polynomial's degree and the Groebner basis size per ray. A plain
// program (no Google Benchmark): it prints tables, not timings of one call.
//
//   patch_bench [--rays N]      N rays per class (default 1000)
//
// Rays of the teapot class go through a random point of one patch's control-point box, from
// outside it (as PatchSet calls a method only for a patch whose box the ray meets).
//
// Notation: the reference of a ray is every crossing any method reports, each refined by
// 50-digit Newton on S(u, v) = o + t d (tests/PatchReference.h) and merged when the refined
// points agree; a reported crossing that does not refine to a point in [0, 1]^2 is spurious.
// error = |t - t_ref| / max(1, |t_ref|). "missed" counts reference crossings a method did not
// report. Classes: the article-style patches (bilinear, ruled quadratic, ruled cubic), random
// bicubic patches, and the Utah teapot's 32 patches (samples/teapot.scad, when the io
// library's bezier_patches is available) with rays through the patch boxes.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <random>
#include <string>
#include <vector>

#include "io/Diagnostic.h"
#include "io/Evaluate.h"
#include "primitives/PatchSet.h"
#include "primitives/patch/Groebner.h"
#include "primitives/patch/Intersect.h"
#include "primitives/patch/Resultant.h"
#include "tests/PatchReference.h"

namespace {

using namespace csg;
using patchref::Big;

struct Ray {
    int patch;
    Vec3 o, d;
};

struct Method {
    std::string name;
    int (*run)(const BezierPatch&, const Vec3&, const Vec3&, PatchCrossings&);
};

int groebnerRaw(const BezierPatch& p, const Vec3& o, const Vec3& d, PatchCrossings& out) {
    return intersectByGroebner(p, o, d, out, nullptr,
                               AlgebraOptions{tol::kGroebnerSmallRel, false});
}
int resultantRaw(const BezierPatch& p, const Vec3& o, const Vec3& d, PatchCrossings& out) {
    return intersectByResultant(p, o, d, out, nullptr,
                                AlgebraOptions{tol::kGroebnerSmallRel, false});
}
int groebner(const BezierPatch& p, const Vec3& o, const Vec3& d, PatchCrossings& out) {
    return intersectByGroebner(p, o, d, out);
}
int resultant(const BezierPatch& p, const Vec3& o, const Vec3& d, PatchCrossings& out) {
    return intersectByResultant(p, o, d, out);
}
int clip(const BezierPatch& p, const Vec3& o, const Vec3& d, PatchCrossings& out) {
    return intersectPatch(PatchMethod::Clip, p, o, d, out);
}
int newton(const BezierPatch& p, const Vec3& o, const Vec3& d, PatchCrossings& out) {
    return intersectPatch(PatchMethod::Newton, p, o, d, out);
}

std::vector<Method> methods() {
    std::vector<Method> m = {{"groebner", groebner},
                             {"groebner (no polish)", groebnerRaw},
                             {"resultant", resultant},
                             {"resultant (no polish)", resultantRaw}};
    m.push_back({"clip", clip});
    m.push_back({"newton", newton});
    return m;
}

struct RefCrossing {
    double t, u, v;
};

// The reference crossings of one ray: every method's crossings, refined and merged.
std::vector<RefCrossing> reference(const BezierPatch& patch, const Ray& ray,
                                   const std::vector<std::vector<PatchCrossing>>& found) {
    std::vector<RefCrossing> ref;
    for (const auto& list : found)
        for (const PatchCrossing& c : list) {
            double u = c.u, v = c.v;
            Big t = c.t;
            if (!patchref::refine(patch, ray.o, ray.d, u, v, t)) continue;
            if (u < -1e-9 || u > 1 + 1e-9 || v < -1e-9 || v > 1 + 1e-9) continue;
            const double td = double(t);
            bool seen = false;
            for (const RefCrossing& r : ref)
                seen = seen || (std::abs(r.u - u) < 1e-7 && std::abs(r.v - v) < 1e-7);
            if (!seen) ref.push_back({td, u, v});
        }
    return ref;
}

double percentile(std::vector<double> x, double q) {
    if (x.empty()) return 0.0;
    std::sort(x.begin(), x.end());
    return x[std::min(x.size() - 1, size_t(q * double(x.size() - 1) + 0.5))];
}

void runClass(const char* name, const std::vector<BezierPatch>& patches,
              const std::vector<Ray>& rays) {
    const std::vector<Method> ms = methods();
    std::printf("\n## %s: %zu rays over %zu patches\n\n", name, rays.size(), patches.size());
    // Step 1: time each method alone over all rays (best of 3 passes).
    std::vector<double> raysPerSecond(ms.size());
    std::vector<std::vector<std::vector<PatchCrossing>>> found(
        ms.size(), std::vector<std::vector<PatchCrossing>>(rays.size()));
    for (size_t m = 0; m < ms.size(); ++m) {
        double best = 1e300;
        for (int pass = 0; pass < 3; ++pass) {
            PatchCrossings out;
            long sink = 0;
            const auto start = std::chrono::steady_clock::now();
            for (const Ray& r : rays) sink += ms[m].run(patches[r.patch], r.o, r.d, out);
            const double s =
                std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
            best = std::min(best, s);
            if (sink < 0) std::printf("?");
        }
        raysPerSecond[m] = double(rays.size()) / best;
        for (size_t i = 0; i < rays.size(); ++i) {
            PatchCrossings out;
            const int n = ms[m].run(patches[rays[i].patch], rays[i].o, rays[i].d, out);
            found[m][i].assign(out.begin(), out.begin() + n);
        }
    }
    // Step 2: the reference per ray, then errors, misses and spurious crossings per method.
    std::vector<std::vector<RefCrossing>> refs(rays.size());
    size_t refTotal = 0;
    for (size_t i = 0; i < rays.size(); ++i) {
        std::vector<std::vector<PatchCrossing>> all;
        for (size_t m = 0; m < ms.size(); ++m) all.push_back(found[m][i]);
        refs[i] = reference(patches[rays[i].patch], rays[i], all);
        refTotal += refs[i].size();
    }
    std::printf("reference crossings: %zu\n\n", refTotal);
    std::printf(
        "| method | rays/s | crossings | missed | spurious | median err | p99 err | max err |\n");
    std::printf("|---|---:|---:|---:|---:|---:|---:|---:|\n");
    for (size_t m = 0; m < ms.size(); ++m) {
        std::vector<double> errors;
        int missed = 0, spurious = 0, total = 0;
        for (size_t i = 0; i < rays.size(); ++i) {
            for (const PatchCrossing& c : found[m][i]) {
                ++total;
                const RefCrossing* best = nullptr;
                for (const RefCrossing& r : refs[i])
                    if (std::abs(r.u - c.u) < 1e-4 && std::abs(r.v - c.v) < 1e-4 &&
                        (!best || std::abs(r.t - c.t) < std::abs(best->t - c.t)))
                        best = &r;
                if (!best) {
                    ++spurious;
                    continue;
                }
                errors.push_back(std::abs(c.t - best->t) / std::max(1.0, std::abs(best->t)));
            }
            for (const RefCrossing& r : refs[i]) {
                bool hit = false;
                for (const PatchCrossing& c : found[m][i])
                    hit = hit || (std::abs(r.u - c.u) < 1e-4 && std::abs(r.v - c.v) < 1e-4);
                missed += !hit;
            }
        }
        std::printf("| %s | %.0f | %d | %d | %d | %.1e | %.1e | %.1e |\n", ms[m].name.c_str(),
                    raysPerSecond[m], total, missed, spurious, percentile(errors, 0.5),
                    percentile(errors, 0.99), errors.empty() ? 0.0 : percentile(errors, 1.0));
    }
    // Step 3: the algebraic methods' per-ray figures.
    std::map<std::pair<int, int>, int> groebnerShape;
    std::map<int, int> rawSize, resultantDegree;
    int breakdowns = 0, empties = 0;
    for (const Ray& r : rays) {
        PatchCrossings out;
        GroebnerStats gs;
        ResultantStats rs;
        intersectByGroebner(patches[r.patch], r.o, r.d, out, &gs);
        intersectByResultant(patches[r.patch], r.o, r.d, out, &rs);
        if (gs.breakdown) {
            ++breakdowns;
        } else if (gs.empty) {
            ++empties;
        } else {
            ++groebnerShape[{gs.basisSize, gs.uDegree}];
            ++rawSize[gs.rawBasisSize];
        }
        ++resultantDegree[rs.uDegree];
    }
    std::printf("\ngroebner per ray: %d breakdowns, %d empty (1 in G)\n", breakdowns, empties);
    std::printf("| reduced basis size | u-degree | rays |\n|---:|---:|---:|\n");
    for (const auto& [k, n] : groebnerShape)
        std::printf("| %d | %d | %d |\n", k.first, k.second, n);
    std::printf("\n| raw basis size (Buchberger's output) | rays |\n|---:|---:|\n");
    for (const auto& [k, n] : rawSize) std::printf("| %d | %d |\n", k, n);
    std::printf("\n| resultant u-degree | rays |\n|---:|---:|\n");
    for (const auto& [k, n] : resultantDegree) std::printf("| %d | %d |\n", k, n);
}

// A random patch of bidegree (du, dv) in (u, v): monomial coefficients uniform in [-1, 1]
// beside a base sheet (u, v, 0), degree-elevated to bicubic.
BezierPatch randomOfBidegree(std::mt19937_64& rng, int du, int dv) {
    std::uniform_real_distribution<double> c(-1.0, 1.0);
    std::array<std::array<Vec3, 4>, 4> a{};
    for (int k = 0; k <= du; ++k)
        for (int l = 0; l <= dv; ++l) a[k][l] = Vec3(0.3 * c(rng), 0.3 * c(rng), c(rng));
    a[1][0] += Vec3(1, 0, 0);
    a[0][1] += Vec3(0, 1, 0);
    return patchref::fromMonomials(a);
}

// Where the Groebner method breaks down: per bidegree and small-value threshold, the share of
// rays it answers correctly (the crossings of the resultant, which the tables above check
// against the reference), breaks down on (capacity or degree), or calls empty (1 in G, a
// false miss when the resultant finds crossings or the eliminant should exist).
void breakdownTable(int count) {
    std::mt19937_64 rng(77);
    const double thresholds[] = {0.0, 1e-14, 1e-12, tol::kGroebnerSmallRel, 1e-8, 1e-6, 1e-4};
    std::printf("\n## Where the Groebner method breaks down\n\n");
    std::printf(
        "Per bidegree (du, dv) of a random patch (%d rays each) and small-value "
        "threshold: %% of the rays with crossings (by the resultant) answered right (the "
        "same crossings, to 1e-9) / %% of all rays broken down / %% of all rays empty (1 in "
        "G: false whenever the resultant has roots); then the median raw basis size and "
        "the expected u-degree 2 du dv.\n\n",
        count);
    std::printf("| bidegree | u-degree |");
    for (double t : thresholds) std::printf(" %.0e |", t);
    std::printf(" raw basis (median, at 1e-10) |\n|---|---:|");
    for (size_t i = 0; i < std::size(thresholds); ++i) std::printf("---|");
    std::printf("---:|\n");
    const int shapes[][2] = {{1, 1}, {2, 1}, {1, 2}, {3, 1}, {1, 3},
                             {2, 2}, {3, 2}, {2, 3}, {3, 3}};
    for (const auto& shape : shapes) {
        std::vector<BezierPatch> patches;
        std::vector<Ray> rays;
        for (int i = 0; i < count; ++i) {
            patches.push_back(randomOfBidegree(rng, shape[0], shape[1]));
            Ray r;
            r.patch = i;
            patchref::randomRay(rng, patches[i], r.o, r.d);
            rays.push_back(r);
        }
        std::printf("| (%d, %d) | %d |", shape[0], shape[1], 2 * shape[0] * shape[1]);
        std::vector<double> raw;
        for (double t : thresholds) {
            int right = 0, hitRays = 0, broken = 0, empty = 0;
            for (const Ray& r : rays) {
                PatchCrossings g, res;
                GroebnerStats gs;
                const int ng = intersectByGroebner(patches[r.patch], r.o, r.d, g, &gs,
                                                   AlgebraOptions{t, true});
                const int nr = intersectByResultant(patches[r.patch], r.o, r.d, res);
                if (t == tol::kGroebnerSmallRel && !gs.breakdown) raw.push_back(gs.rawBasisSize);
                broken += gs.breakdown;
                empty += gs.empty;
                if (nr == 0) continue;
                ++hitRays;
                bool same = ng == nr;
                for (int k = 0; k < ng && same; ++k)
                    same = std::abs(g[k].t - res[k].t) <= 1e-9 * std::max(1.0, std::abs(res[k].t));
                right += same;
            }
            std::printf(" %d / %d / %d |", hitRays ? 100 * right / hitRays : 0,
                        100 * broken / count, 100 * empty / count);
        }
        std::printf(" %.0f |\n", raw.empty() ? 0.0 : percentile(raw, 0.5));
    }
}

// The patches of the first patch set in a part file, loaded through the io library as the
// command line does (an empty list, with the reason on stderr, when that fails).
std::vector<BezierPatch> patchesOf(const char* file) {
    const io::EvaluateResult r = io::evaluateFile(file);
    if (!r.ok()) {
        for (const auto& diagnostic : r.diagnostics)
            std::fprintf(stderr, "%s\n", io::formatDiagnostic(diagnostic).c_str());
        return {};
    }
    std::vector<const csg::Node*> stack = {r.model->root.get()};
    while (!stack.empty()) {
        const csg::Node* node = stack.back();
        stack.pop_back();
        if (!node) continue;
        if (const PatchSet* set = std::get_if<PatchSet>(&node->primitive); set && set->data)
            return set->data->patches;
        stack.push_back(node->left.get());
        stack.push_back(node->right.get());
    }
    std::fprintf(stderr, "patch_bench: %s holds no bezier_patches\n", file);
    return {};
}

std::vector<Ray> raysThrough(std::mt19937_64& rng, const std::vector<BezierPatch>& patches,
                             int count) {
    std::vector<Ray> rays;
    for (int i = 0; i < count; ++i) {
        Ray r;
        r.patch = int(rng() % patches.size());
        patchref::randomRay(rng, patches[r.patch], r.o, r.d);
        rays.push_back(r);
    }
    return rays;
}

}  // namespace

int main(int argc, char** argv) {
    int count = 1000;
    for (int i = 1; i < argc; ++i) {
        if (std::strcmp(argv[i], "--rays") == 0 && i + 1 < argc) {
            count = std::atoi(argv[++i]);
        } else {
            std::fprintf(stderr, "usage: patch_bench [--rays N]\n");
            return 2;
        }
    }
    if (count <= 0) {
        std::fprintf(stderr, "patch_bench: --rays must be positive\n");
        return 2;
    }
    std::mt19937_64 rng(2026);
    std::printf("# patch_bench: %d rays per class\n", count);
    for (int kind = 1; kind <= 3; ++kind) {
        const std::vector<BezierPatch> one = {patchref::articlePatch(kind)};
        const char* names[] = {"", "article patch 1 (bilinear)",
                               "article patch 2 (ruled quadratic)",
                               "article patch 3 (ruled cubic)"};
        runClass(names[kind], one, raysThrough(rng, one, count));
    }
    std::vector<BezierPatch> random;
    for (int i = 0; i < count; ++i) random.push_back(patchref::randomPatch(rng));
    std::vector<Ray> rays;
    for (int i = 0; i < count; ++i) {
        Ray r;
        r.patch = i;
        patchref::randomRay(rng, random[i], r.o, r.d);
        rays.push_back(r);
    }
    runClass("random bicubic patches", random, rays);
    const std::vector<BezierPatch> teapot = patchesOf(CSGRAY_SOURCE_DIR "/samples/teapot.scad");
    if (!teapot.empty())
        runClass("Utah teapot (samples/teapot.scad)", teapot, raysThrough(rng, teapot, count));
    breakdownTable(std::max(20, count / 5));
    return 0;
}
