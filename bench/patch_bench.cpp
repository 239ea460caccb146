// The ray/patch methods measured: per method and patch class, rays per second and the error
// distribution of t against a 50-digit reference, with missed and spurious crossings; for the
// algebraic methods, the u-polynomial's degree and the Groebner basis size per ray. A plain
// program (no Google Benchmark): it prints tables, not timings of one call.
//
//   patch_bench [--rays N]      N rays per class (default 1000); the bidegree table uses
//                               N / 5 rays per bidegree (at least 20)
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

#include "bench/ArticleGroebner.h"
#include "io/Diagnostic.h"
#include "io/Evaluate.h"
#include "primitives/PatchSet.h"
#include "primitives/patch/Groebner.h"
#include "primitives/patch/GroebnerCertified.h"
#include "primitives/patch/GroebnerExact.h"
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

int groebnerFloatRaw(const BezierPatch& p, const Vec3& o, const Vec3& d, PatchCrossings& out) {
    return intersectByGroebner(p, o, d, out, nullptr,
                               AlgebraOptions{tol::kGroebnerSmallRel, false});
}
int resultantRaw(const BezierPatch& p, const Vec3& o, const Vec3& d, PatchCrossings& out) {
    return intersectByResultant(p, o, d, out, nullptr,
                                AlgebraOptions{tol::kGroebnerSmallRel, false});
}
template <PatchMethod M>
int byMethod(const BezierPatch& p, const Vec3& o, const Vec3& d, PatchCrossings& out) {
    return intersectPatch(M, p, o, d, out);
}

// "groebner" is the certified float pass with the exact fallback; "groebner-float" the
// article's float method (with csgray's polish; "no polish": as the article has it).
std::vector<Method> methods() {
    return {{"groebner", byMethod<PatchMethod::Groebner>},
            {"groebner-exact", byMethod<PatchMethod::GroebnerExact>},
            {"groebner-float", byMethod<PatchMethod::GroebnerFloat>},
            {"groebner-float (no polish)", groebnerFloatRaw},
            {"resultant", byMethod<PatchMethod::Resultant>},
            {"resultant (no polish)", resultantRaw},
            {"clip", byMethod<PatchMethod::Clip>},
            {"newton", byMethod<PatchMethod::Newton>}};
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
    // Step 1: time each method alone over all rays (median of 3 passes).
    std::vector<double> raysPerSecond(ms.size());
    std::vector<std::vector<std::vector<PatchCrossing>>> found(
        ms.size(), std::vector<std::vector<PatchCrossing>>(rays.size()));
    for (size_t m = 0; m < ms.size(); ++m) {
        std::vector<double> passes;
        for (int pass = 0; pass < 3; ++pass) {
            PatchCrossings out;
            long sink = 0;
            const auto start = std::chrono::steady_clock::now();
            for (const Ray& r : rays) sink += ms[m].run(patches[r.patch], r.o, r.d, out);
            const double s =
                std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
            passes.push_back(s);
            if (sink < 0) std::printf("?");
        }
        raysPerSecond[m] = double(rays.size()) / percentile(passes, 0.5);
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
        "| method | rays/s | correct rays | crossings | missed | spurious | median err | p99 err "
        "| max err |\n");
    std::printf("|---|---:|---:|---:|---:|---:|---:|---:|---:|\n");
    for (size_t m = 0; m < ms.size(); ++m) {
        std::vector<double> errors;
        int missed = 0, spurious = 0, total = 0, correct = 0;
        for (size_t i = 0; i < rays.size(); ++i) {
            const int missedBefore = missed, spuriousBefore = spurious;
            const size_t errorsBefore = errors.size();
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
            // A correct ray: every reference crossing reported once, nothing else, t to 1e-9.
            bool right = missed == missedBefore && spurious == spuriousBefore &&
                         found[m][i].size() == refs[i].size();
            for (size_t e = errorsBefore; e < errors.size() && right; ++e)
                right = errors[e] <= 1e-9;
            correct += right;
        }
        std::printf("| %s | %.0f | %.1f %% | %d | %d | %d | %.1e | %.1e | %.1e |\n",
                    ms[m].name.c_str(), raysPerSecond[m], 100.0 * correct / double(rays.size()),
                    total, missed, spurious, percentile(errors, 0.5), percentile(errors, 0.99),
                    errors.empty() ? 0.0 : percentile(errors, 1.0));
    }
    // Step 3: the algebraic methods' per-ray figures.
    std::map<std::pair<int, int>, int> groebnerShape;
    std::map<int, int> rawSize, resultantDegree;
    std::map<std::pair<int, int>, int> exactShape;
    int breakdowns = 0, empties = 0, certified = 0, exactEmpty = 0, buchberger = 0;
    for (const Ray& r : rays) {
        PatchCrossings out;
        GroebnerStats gs;
        ResultantStats rs;
        CertifiedGroebnerStats cs;
        ExactGroebnerStats es;
        intersectByCertifiedGroebner(patches[r.patch], r.o, r.d, out, &cs);
        intersectByExactGroebner(patches[r.patch], r.o, r.d, out, &es);
        certified += cs.certified;
        exactEmpty += es.empty;
        buchberger += !es.shapeBasis && !es.empty;
        if (!es.empty) ++exactShape[{es.basisSize, es.uDegree}];
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
    std::printf(
        "\ngroebner (certified): float pass certified on %d of %zu rays, exact pass on %zu\n",
        certified, rays.size(), rays.size() - size_t(certified));
    std::printf(
        "groebner-exact: %d empty (1 in G), basis by Buchberger (not the proved shape "
        "basis) on %d\n| exact basis size | u-degree | rays |\n|---:|---:|---:|\n",
        exactEmpty, buchberger);
    for (const auto& [k, n] : exactShape) std::printf("| %d | %d | %d |\n", k.first, k.second, n);
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

// True when a method's crossings on a ray are the reference's: each once, nothing else, t to
// 1e-9 relative (the criterion of the "correct rays" column).
bool correctRay(const std::vector<PatchCrossing>& found, const std::vector<RefCrossing>& ref) {
    if (found.size() != ref.size()) return false;
    for (const RefCrossing& r : ref) {
        int matches = 0;
        for (const PatchCrossing& c : found)
            matches += std::abs(r.u - c.u) < 1e-4 && std::abs(r.v - c.v) < 1e-4 &&
                       std::abs(c.t - r.t) <= 1e-9 * std::max(1.0, std::abs(r.t));
        if (matches != 1) return false;
    }
    return true;
}

// Per bidegree of a random patch: each method's share of correct rays and its rays/s (median
// of 3 passes), and how often the certified Groebner pass answered without the exact one.
void bidegreeMethodTable(int count) {
    std::mt19937_64 rng(78);
    const std::vector<Method> ms = methods();
    std::printf("\n## Correct rays and rays/s per method and bidegree\n\n");
    std::printf(
        "Random patches of bidegree (du, dv) (degree-elevated to bicubic in double), %d "
        "rays each; cells: %% of rays answered right / rays per second (median of 3 "
        "passes).\n\n| bidegree |",
        count);
    for (const Method& m : ms) std::printf(" %s |", m.name.c_str());
    std::printf(" groebner: certified float pass |\n|---|");
    for (size_t m = 0; m < ms.size(); ++m) std::printf("---:|");
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
        std::vector<std::vector<std::vector<PatchCrossing>>> found(
            ms.size(), std::vector<std::vector<PatchCrossing>>(rays.size()));
        std::vector<double> rate(ms.size());
        for (size_t m = 0; m < ms.size(); ++m) {
            std::vector<double> passes;
            for (int pass = 0; pass < 3; ++pass) {
                const auto start = std::chrono::steady_clock::now();
                for (size_t i = 0; i < rays.size(); ++i) {
                    PatchCrossings out;
                    const int n = ms[m].run(patches[i], rays[i].o, rays[i].d, out);
                    if (pass == 0) found[m][i].assign(out.begin(), out.begin() + n);
                }
                passes.push_back(
                    std::chrono::duration<double>(std::chrono::steady_clock::now() - start)
                        .count());
            }
            rate[m] = double(rays.size()) / percentile(passes, 0.5);
        }
        std::vector<int> correct(ms.size());
        int certified = 0;
        for (size_t i = 0; i < rays.size(); ++i) {
            std::vector<std::vector<PatchCrossing>> all;
            for (size_t m = 0; m < ms.size(); ++m) all.push_back(found[m][i]);
            const std::vector<RefCrossing> ref = reference(patches[i], rays[i], all);
            for (size_t m = 0; m < ms.size(); ++m) correct[m] += correctRay(found[m][i], ref);
            PatchCrossings out;
            CertifiedGroebnerStats cs;
            intersectByCertifiedGroebner(patches[i], rays[i].o, rays[i].d, out, &cs);
            certified += cs.certified;
        }
        std::printf("| (%d, %d) |", shape[0], shape[1]);
        for (size_t m = 0; m < ms.size(); ++m)
            std::printf(" %.1f %% / %.0f |", 100.0 * correct[m] / count, rate[m]);
        std::printf(" %.0f %% |\n", 100.0 * certified / count);
    }
}

std::vector<Ray> raysThrough(std::mt19937_64& rng, const std::vector<BezierPatch>& patches,
                             int count);

// The article's table by its own counting (bench/ArticleGroebner.h): per patch, the
// distribution over rays of Groebner()'s N (the "size"), the u-degree and the v-degree, in
// the article's arithmetic (double, ZERO = 1e-9) and exactly (rationals, ZERO = 0), beside
// csgray's exact method (reduced basis size / eliminant degree). Each article patch twice:
// degree-elevated in double (its higher coefficients are 1e-17 residue of rounding 1/3) and
// exactly (scaled by 9, tests/PatchReference.h exactArticlePatch).
void articleTable(int count) {
    std::mt19937_64 rng(1988);
    std::printf(
        "\n## The article's table by its own counting\n\n%d rays per patch. Cells: "
        "value (rays); N is Groebner()'s return, \"no hit\" an F_N constant.\n\n",
        count);
    std::printf(
        "| patch | arithmetic | size N | u-degree | v-degree | csgray exact: reduced "
        "basis / u-degree |\n|---|---|---|---|---|---|\n");
    auto cell = [](const std::map<int, int>& h) {
        std::string s;
        for (const auto& [k, n] : h)
            s += (s.empty() ? "" : ", ") + (k == -1 ? std::string("none") : std::to_string(k)) +
                 " (" + std::to_string(n) + ")";
        return s;
    };
    struct Case {
        std::string name;
        BezierPatch patch;
        bool exactToo;
    };
    std::vector<Case> cases;
    const char* kinds[] = {"", "bilinear", "ruled quadratic", "ruled cubic"};
    for (int kind = 1; kind <= 3; ++kind) {
        cases.push_back({std::string("article ") + std::to_string(kind) + " (" + kinds[kind] +
                             "), elevated in double",
                         patchref::articlePatch(kind), true});
        cases.push_back({std::string("article ") + std::to_string(kind) + " (" + kinds[kind] +
                             "), elevated exactly",
                         patchref::exactArticlePatch(kind), true});
    }
    cases.push_back({"random (2, 2)", randomOfBidegree(rng, 2, 2), false});
    cases.push_back({"random (3, 3)", patchref::randomPatch(rng), false});
    for (const Case& c : cases) {
        std::vector<Ray> rays = raysThrough(rng, {c.patch}, count);
        for (int exact = 0; exact <= (c.exactToo ? 1 : 0); ++exact) {
            std::map<int, int> size, uDeg, vDeg, csgray;
            int noHit = 0, overflow = 0;
            for (const Ray& r : rays) {
                const article::Counts k = exact ? article::run<mpq_class>(c.patch, r.o, r.d)
                                                : article::run<double>(c.patch, r.o, r.d);
                overflow += k.overflow;
                if (k.overflow) continue;
                ++size[k.size];
                noHit += k.noHit;
                if (!k.noHit) {
                    ++uDeg[k.uDegree];
                    ++vDeg[k.vDegree];
                }
                PatchCrossings out;
                ExactGroebnerStats es;
                intersectByExactGroebner(c.patch, r.o, r.d, out, &es);
                ++csgray[es.empty ? -1 : 100 * es.basisSize + es.uDegree];
            }
            std::string ours;
            for (const auto& [k, n] : csgray)
                ours += (ours.empty() ? "" : ", ") +
                        (k == -1 ? std::string("1 in G")
                                 : std::to_string(k / 100) + " / " + std::to_string(k % 100)) +
                        " (" + std::to_string(n) + ")";
            std::printf("| %s | %s | %s%s%s | %s | %s | %s |\n", c.name.c_str(),
                        exact ? "exact" : "double, ZERO 1e-9", cell(size).c_str(),
                        noHit ? (", no hit on " + std::to_string(noHit)).c_str() : "",
                        overflow ? (", overflow on " + std::to_string(overflow)).c_str() : "",
                        cell(uDeg).c_str(), cell(vDeg).c_str(), ours.c_str());
        }
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
    articleTable(std::max(20, count / 10));
    bidegreeMethodTable(std::max(20, count / 5));
    breakdownTable(std::max(20, count / 5));
    return 0;
}
