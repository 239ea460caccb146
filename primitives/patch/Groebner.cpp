// Notation: G is the basis under construction, lt(g) its leading monomial (lex v > u), every
// element kept monic (leading coefficient 1). "Reduce f by G": cancel, from the largest term
// down, every term of f that some lt(g) divides, by f -= c m g; the small-value rule then
// zeroes what rounding left of terms that cancel exactly.
#include "primitives/patch/Groebner.h"

#include <algorithm>

#include "primitives/patch/PatchAlgebra.h"
#include "primitives/solvers/Solve.h"

namespace csg {

namespace {

// S-polynomial pairs examined before the reduction counts as a breakdown. A bicubic pair in
// general position needs well under 20; this only stops runaway coefficient noise.
constexpr int kMaxPairs = 2000;
// An eliminant of a bicubic pair has degree <= 18 (Kajiya's bound); more is rounding noise
// that the small-value rule failed to cancel.
constexpr int kMaxEliminantDegree = 2 * 3 * 3;

struct Working {
    std::array<Bivariate, GroebnerBasis::kCapacity> g;
    std::array<Monomial, GroebnerBasis::kCapacity> lt;
    int n = 0;
};

// f / lc(f); false for the zero polynomial.
bool makeMonic(Bivariate& f, Monomial& lt) {
    lt = f.leading();
    if (lt.u < 0) return false;
    f.scale(1.0 / f(lt.u, lt.v));
    f(lt.u, lt.v) = 1.0;
    return true;
}

enum class Reduction { Unchanged, Changed, Overflow };

// Reduces f by the elements of G listed in use[0..count) (monic, leading terms lt).
Reduction reduce(Bivariate& f, const Working& G, const int* use, int count, double smallRel) {
    Reduction result = Reduction::Unchanged;
    for (int j = Bivariate::kMaxDegreeV; j >= 0; --j)
        for (int i = Bivariate::kMaxDegreeU; i >= 0; --i) {
            const double c = f(i, j);
            if (c == 0.0) continue;
            for (int k = 0; k < count; ++k) {
                const Monomial& m = G.lt[use[k]];
                if (!m.divides({i, j})) continue;
                const Bivariate& g = G.g[use[k]];
                const double scale = std::max(f.maxMagnitude(), std::abs(c) * g.maxMagnitude());
                if (!f.subtractMultiple(c, {i - m.u, j - m.v}, g)) return Reduction::Overflow;
                f(i, j) = 0.0;  // cancelled exactly in exact arithmetic
                f.dropBelow(smallRel * scale);
                result = Reduction::Changed;
                break;
            }
        }
    return result;
}

// The S-polynomial of monic f, g: lcm/lt(f) f - lcm/lt(g) g, its leading terms cancelled.
bool sPolynomial(const Bivariate& f, Monomial ltf, const Bivariate& g, Monomial ltg,
                 double smallRel, Bivariate& s) {
    const Monomial lcm{std::max(ltf.u, ltg.u), std::max(ltf.v, ltg.v)};
    s = Bivariate{};
    const double scale = std::max(f.maxMagnitude(), g.maxMagnitude());
    if (!s.subtractMultiple(-1.0, {lcm.u - ltf.u, lcm.v - ltf.v}, f)) return false;
    if (!s.subtractMultiple(1.0, {lcm.u - ltg.u, lcm.v - ltg.v}, g)) return false;
    s(lcm.u, lcm.v) = 0.0;
    s.dropBelow(smallRel * scale);
    return true;
}

template <typename Pair>
bool lcmBefore(const Working& G, const Pair& x, const Pair& y) {
    const int xv = std::max(G.lt[x[0]].v, G.lt[x[1]].v), yv = std::max(G.lt[y[0]].v, G.lt[y[1]].v);
    const int xu = std::max(G.lt[x[0]].u, G.lt[x[1]].u), yu = std::max(G.lt[y[0]].u, G.lt[y[1]].u);
    return xv != yv ? xv < yv : xu < yu;
}

bool isConstant(const Monomial& m) {
    return m.u == 0 && m.v == 0;
}

}  // namespace

void groebnerBasis(const Bivariate& f1, const Bivariate& f2, double smallRel,
                   GroebnerBasis& result) {
    GroebnerStats& stats = result.stats;
    stats = GroebnerStats{};
    Working G;
    G.g[0] = f1;
    G.g[1] = f2;
    // The small-value rule on the input too: a patch of lower degree, degree-elevated to
    // bicubic, has rounding residue where its higher coefficients are zero.
    const double inputScale = std::max(f1.maxMagnitude(), f2.maxMagnitude());
    G.g[0].dropBelow(smallRel * inputScale);
    G.g[1].dropBelow(smallRel * inputScale);
    // Step 1: R2, the mutual reduction of the pair, until neither reduces the other.
    const int first[] = {0}, second[] = {1};
    for (int round = 0;; ++round) {
        if (!makeMonic(G.g[0], G.lt[0]) || !makeMonic(G.g[1], G.lt[1])) {
            // A plane equation vanishes on the whole patch (the ray lies in the plane of a flat
            // patch, or F1, F2 are dependent): no isolated crossing.
            stats.rawBasisSize = stats.basisSize = 1;
            return;
        }
        if (round > 2 * Bivariate::kMaxDegreeU) {
            stats.breakdown = true;
            return;
        }
        const Reduction r2 = reduce(G.g[1], G, first, 1, smallRel);
        if (r2 == Reduction::Overflow) {
            stats.breakdown = true;
            return;
        }
        if (!makeMonic(G.g[1], G.lt[1])) continue;  // reported above
        const Reduction r1 = reduce(G.g[0], G, second, 1, smallRel);
        if (r1 == Reduction::Overflow) {
            stats.breakdown = true;
            return;
        }
        if (r1 == Reduction::Unchanged && r2 == Reduction::Unchanged) break;
    }
    G.n = 2;

    // Step 2: the S-polynomial loop. pairs holds (i, j) still to examine.
    std::array<std::array<int, 2>, GroebnerBasis::kCapacity * GroebnerBasis::kCapacity> pairs;
    int pairCount = 0, examined = 0;
    pairs[pairCount++] = {0, 1};
    int all[GroebnerBasis::kCapacity];
    for (int k = 0; k < GroebnerBasis::kCapacity; ++k) all[k] = k;
    while (pairCount > 0 && !isConstant(G.lt[G.n - 1]) && !isConstant(G.lt[0])) {
        // Buchberger's normal strategy: the pair with the smallest lcm (lex) first, which keeps
        // the u-degree of intermediate elements low.
        int pick = 0;
        for (int k = 1; k < pairCount; ++k)
            if (lcmBefore(G, pairs[k], pairs[pick])) pick = k;
        const auto [i, j] = pairs[pick];
        pairs[pick] = pairs[--pairCount];
        const Monomial a = G.lt[i], b = G.lt[j];
        if ((a.u == 0 || b.u == 0) && (a.v == 0 || b.v == 0)) continue;  // coprime: reduces to 0
        if (++examined > kMaxPairs) {
            stats.breakdown = true;
            return;
        }
        Bivariate s;
        if (!sPolynomial(G.g[i], a, G.g[j], b, smallRel, s) ||
            reduce(s, G, all, G.n, smallRel) == Reduction::Overflow) {
            stats.breakdown = true;
            return;
        }
        Monomial lt;
        if (!makeMonic(s, lt)) continue;
        if (G.n == GroebnerBasis::kCapacity) {
            stats.breakdown = true;
            return;
        }
        G.g[G.n] = s;
        G.lt[G.n] = lt;
        for (int k = 0; k < G.n; ++k) pairs[pairCount++] = {k, G.n};
        ++G.n;
    }
    stats.rawBasisSize = G.n;

    // Step 3: the emptiness test. 1 in G: F1 = F2 = 0 has no solution at all.
    for (int k = 0; k < G.n; ++k)
        if (isConstant(G.lt[k])) {
            stats.empty = true;
            stats.basisSize = 1;
            return;
        }

    // Step 4: the reduced basis. Drop elements whose leading term another's divides (of two
    // equal leading terms, the later), then reduce each survivor by the others.
    int kept[GroebnerBasis::kCapacity], keptCount = 0;
    for (int k = 0; k < G.n; ++k) {
        bool redundant = false;
        for (int m = 0; m < G.n && !redundant; ++m)
            redundant = m != k && G.lt[m].divides(G.lt[k]) &&
                        (G.lt[m].u != G.lt[k].u || G.lt[m].v != G.lt[k].v || m < k);
        if (!redundant) kept[keptCount++] = k;
    }
    auto before = [&](int x, int y) {
        return G.lt[x].v != G.lt[y].v ? G.lt[x].v < G.lt[y].v : G.lt[x].u < G.lt[y].u;
    };
    for (int k = 1; k < keptCount; ++k)  // insertion sort: a handful of elements
        for (int m = k; m > 0 && before(kept[m], kept[m - 1]); --m) std::swap(kept[m], kept[m - 1]);
    for (int k = 0; k < keptCount; ++k) {
        int others[GroebnerBasis::kCapacity], otherCount = 0;
        for (int m = 0; m < keptCount; ++m)
            if (m != k) others[otherCount++] = kept[m];
        Bivariate& g = G.g[kept[k]];
        if (reduce(g, G, others, otherCount, smallRel) == Reduction::Overflow ||
            !makeMonic(g, G.lt[kept[k]])) {
            stats.breakdown = true;
            return;
        }
        result.basis[k] = g;
    }
    stats.basisSize = keptCount;
    const Monomial eliminant = result.basis[0].leading();
    if (eliminant.v == 0) stats.uDegree = eliminant.u;
    if (stats.uDegree > kMaxEliminantDegree) stats.breakdown = true;
}

namespace {

// The method proper on planes = the plane equations of patch (lex v > u).
int intersectLexVU(const BezierPatch& patch, const PlaneEquations& planes, const Vec3& o,
                   const Vec3& d, PatchCrossings& out, GroebnerStats* stats,
                   const AlgebraOptions& options) {
    GroebnerBasis gb;
    groebnerBasis(planes.f1, planes.f2, options.smallRel, gb);
    if (stats) *stats = gb.stats;
    const GroebnerStats& s = gb.stats;
    if (s.breakdown || s.empty || s.uDegree <= 0) return 0;

    // Step 5: the roots in u of the eliminant.
    WidePolynomial eliminant;
    eliminant.degree = s.uDegree;
    for (int i = 0; i <= s.uDegree; ++i) eliminant.c[i] = gb.basis[0](i, 0);
    double us[Bivariate::kMaxDegreeU];
    const int uCount = unitParameterRoots(eliminant, us);

    // Step 6: back-substitution. At each u, v from the basis element of lowest v-degree whose
    // leading coefficient does not vanish there (the original F1 when none qualifies).
    int n = 0;
    for (int r = 0; r < uCount && n < kMaxPatchCrossings; ++r) {
        const double u = us[r];
        const Bivariate* pick = &planes.f1;
        for (int k = 1; k < s.basisSize; ++k) {
            const auto c = gb.basis[k].atU(u);
            const int dv = gb.basis[k].degreeV();
            double sum = 0.0;
            for (int j = 0; j <= dv; ++j) sum += std::abs(c[j]);
            if (std::abs(c[dv]) > tol::kPatchResidualRel * sum) {
                pick = &gb.basis[k];
                break;
            }
        }
        const auto c = pick->atU(u);
        Polynomial inV = Polynomial::ofDegree(std::max(pick->degreeV(), 1));
        for (int j = 0; j <= pick->degreeV(); ++j) inV[j] = c[j];
        double vs[Bivariate::kMaxDegreeV + 1];
        const int vCount =
            solve(inV.trimmed(), -tol::kPatchParamSlack, 1.0 + tol::kPatchParamSlack, vs);
        const int before = n;
        for (int k = 0; k < vCount && n < kMaxPatchCrossings; ++k)
            acceptMethodRoot(patch, planes, o, d, u, vs[k], options, out, n);
        if (n > before || !options.polish || !hasCloseNeighbour(us, uCount, r)) continue;
        // No v from the basis at a near-double root: where two crossings share nearly the
        // same u (the eliminant has two roots within tol::kPatchRootDriftParam), the element's
        // coefficients are huge and cancel (v = c0(u) / c1(u) with both ~1e6), so a u right
        // to 1e-8 gives v off by 1e-2. The plane equations themselves are well conditioned in
        // v: their roots there, polished in (u, v) together (with polish only: unpolished,
        // the method is the article's).
        crossingsFromPlaneRoots(patch, planes, o, d, u, options, out, n);
    }
    return finishCrossings(out, n);
}

// The degree of F1, F2 together in u (in v), under the small-value rule.
void degrees(const PlaneEquations& planes, double smallRel, int& inU, int& inV) {
    Bivariate f1 = planes.f1, f2 = planes.f2;
    const double scale = std::max(f1.maxMagnitude(), f2.maxMagnitude());
    f1.dropBelow(smallRel * scale);
    f2.dropBelow(smallRel * scale);
    inU = std::max(f1.degreeU(), f2.degreeU());
    inV = std::max(f1.degreeV(), f2.degreeV());
}

}  // namespace

int intersectByGroebner(const BezierPatch& patch, const Vec3& o, const Vec3& d, PatchCrossings& out,
                        GroebnerStats* stats, const AlgebraOptions& options) {
    const PlaneEquations planes = planeEquations(patch, o, d);
    int inU, inV;
    degrees(planes, options.smallRel, inU, inV);
    if (inV <= inU) return intersectLexVU(patch, planes, o, d, out, stats, options);
    // The variable order: v, the one eliminated, is the parameter of lower degree. A patch
    // linear in u and cubic in v is solved as its transpose (linear in v), whose elimination
    // is one R2 step instead of a long Buchberger run whose rounding noise often ends in a
    // false 1 in G (bench/reports/patches.md measures both orders).
    BezierPatch transposed;
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) transposed.points[4 * j + i] = patch.at(i, j);
    const int n =
        intersectLexVU(transposed, planeEquations(transposed, o, d), o, d, out, stats, options);
    for (int k = 0; k < n; ++k) std::swap(out[k].u, out[k].v);
    return n;
}

int intersectByGroebner(const BezierPatch& patch, const Vec3& o, const Vec3& d,
                        PatchCrossings& out) {
    return intersectByGroebner(patch, o, d, out, nullptr);
}

}  // namespace csg
