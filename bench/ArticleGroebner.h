// The thesis appendix's Groebner() (Annexe B, ray3.c: CalcBasis, Reduce, Reduce_2,
// S_Polynomial, Groebner, Roots, VRoots), re-implemented step for step to reproduce the
// article's table by its own counting: "size of the Groebner basis" is the index N that
// Groebner() returns (GroebnerSize[N]++), the u-degree is the eliminant's degree after Roots()
// strips coefficients ZERO() calls zero, the v-degree that of the polynomial VRoots() builds.
// Number is double (the article: ZERO(a) is |a| < PRECISION = 1e-9, absolute, applied to every
// coefficient a sum produces and to the input) or mpq_class (exact: ZERO is == 0).
// Notation: a polynomial is its nonzero terms, largest first in lex v > u (Greater()); every
// element is scaled to leading coefficient 1 (Scale()), as in the appendix.
#pragma once

#include <gmpxx.h>

#include <array>
#include <cmath>
#include <vector>

#include "primitives/patch/BezierPatch.h"

namespace csg::article {

inline constexpr double kPrecision = 1e-9;  // the appendix's PRECISION

inline bool isZero(double a) {
    return a < kPrecision && a > -kPrecision;
}
inline bool isZero(const mpq_class& a) {
    return sgn(a) == 0;
}
inline double toDouble(double a) {
    return a;
}
inline double toDouble(const mpq_class& a) {
    return a.get_d();
}

template <typename Number>
struct Term {
    int u, v;
    Number c;
};
template <typename Number>
using Poly = std::vector<Term<Number>>;

inline bool greater(int u1, int v1, int u2, int v2) {
    return v1 > v2 || (v1 == v2 && u1 > u2);
}

// Sum(): the merge of a and b, terms ZERO() calls zero dropped.
template <typename Number>
Poly<Number> sum(const Poly<Number>& a, const Poly<Number>& b) {
    Poly<Number> r;
    size_t i = 0, j = 0;
    while (i < a.size() || j < b.size()) {
        Term<Number> t;
        if (j == b.size() || (i < a.size() && greater(a[i].u, a[i].v, b[j].u, b[j].v))) {
            t = a[i++];
        } else if (i == a.size() || greater(b[j].u, b[j].v, a[i].u, a[i].v)) {
            t = b[j++];
        } else {
            t = {a[i].u, a[i].v, a[i].c + b[j].c};
            ++i;
            ++j;
        }
        if (!isZero(t.c)) r.push_back(t);
    }
    return r;
}

// Scale(): divide by the leading coefficient (unless it is already ZERO() away from 1).
template <typename Number>
void scale(Poly<Number>& f) {
    if (f.empty()) return;
    const Number s = f[0].c;
    if (isZero(Number(1 - s))) return;
    f[0].c = 1;
    for (size_t j = 1; j < f.size(); ++j) f[j].c = f[j].c / s;
}

// Reduce(f, 0, g): the leading term of f cancelled by g's (f -= lc(f) m g, g monic); false
// when lt(g) does not divide lt(f).
template <typename Number>
bool reduceLeading(Poly<Number>& f, const Poly<Number>& g) {
    if (f.empty() || g.empty()) return false;
    const int du = f[0].u - g[0].u, dv = f[0].v - g[0].v;
    if (du < 0 || dv < 0) return false;
    const Number k = -f[0].c;
    Poly<Number> shifted;
    for (const Term<Number>& t : g) shifted.push_back({t.u + du, t.v + dv, k * t.c});
    f = sum(f, shifted);
    return true;
}

// Reduce_2(): the mutual reduction, the one with the larger u-power of its leading term first.
template <typename Number>
void reduce2(Poly<Number>* a, Poly<Number>* b) {
    if (!a->empty() && !b->empty() && (*a)[0].u < (*b)[0].u) std::swap(a, b);
    while (reduceLeading(*a, *b)) {
        if (a->empty()) return;
        scale(*a);
        scale(*b);
        if ((*a)[0].u < (*b)[0].u) std::swap(a, b);
    }
}

// S_Polynomial().
template <typename Number>
Poly<Number> sPolynomial(const Poly<Number>& f, const Poly<Number>& g) {
    if (f.empty() || g.empty()) return {};
    const int du = std::max(f[0].u, g[0].u), dv = std::max(f[0].v, g[0].v);
    Poly<Number> a, b;
    for (size_t j = 1; j < f.size(); ++j)
        a.push_back({f[j].u + du - f[0].u, f[j].v + dv - f[0].v, f[j].c});
    for (size_t j = 1; j < g.size(); ++j)
        b.push_back({g[j].u + du - g[0].u, g[j].v + dv - g[0].v, -g[j].c});
    Poly<Number> s = sum(a, b);
    scale(s);
    return s;
}

// What the appendix's program records for one ray.
struct Counts {
    int size = -1;          // N, Groebner()'s return (GroebnerSize[N]++)
    bool noHit = false;     // F_N constant: NbCrit++, no intersection
    int uDegree = -1;       // DegPolU
    int vDegree = -1;       // DegPolV (at the eliminant's first root in [0, 1], when there is one)
    bool overflow = false;  // more than kMaxElements elements (the appendix's NBPOL)
};

inline constexpr int kMaxElements = 64;

// CalcBasis() then Groebner(), Roots() and VRoots() for the ray o + t d, from the patch's
// monomial coefficients m[k][l] (of u^k v^l, the appendix's P[k][l]) computed in Number.
template <typename Number>
Counts run(const BezierPatch& patch, const Vec3& o, const Vec3& d) {
    static const int M[4][4] = {
        {1, 0, 0, 0}, {-3, 3, 0, 0}, {3, -6, 3, 0}, {-1, 3, -3, 1}};  // [power][Bernstein]
    std::array<std::array<std::array<Number, 3>, 4>, 4> m;
    for (int k = 0; k < 4; ++k)
        for (int l = 0; l < 4; ++l)
            for (int c = 0; c < 3; ++c) {
                m[k][l][c] = 0;
                for (int i = 0; i < 4; ++i)
                    for (int j = 0; j < 4; ++j)
                        if (M[k][i] * M[l][j] != 0)
                            m[k][l][c] += Number(M[k][i] * M[l][j]) * Number(patch.at(i, j)[c]);
            }
    Counts counts;
    // CalcBasis: v1 the first axis along which d is not ZERO, the planes through the ray
    // normal to e_v2 x d and e_v3 x d, each scaled.
    int v1 = 0, v2 = 1, v3 = 2;
    if (isZero(d[0])) {
        if (!isZero(d[1])) {
            v1 = 1;
            v2 = 0;
        } else {
            v1 = 2;
            v2 = 0;
            v3 = 1;
        }
    }
    std::vector<Poly<Number>> F(2);
    for (int k = 3; k >= 0; --k)  // v-power k, u-power l, largest first
        for (int l = 3; l >= 0; --l) {
            const Number x0 = Number(d[v2]) * m[l][k][v1] - Number(d[v1]) * m[l][k][v2];
            const Number x1 = Number(d[v3]) * m[l][k][v1] - Number(d[v1]) * m[l][k][v3];
            Number c0 = x0, c1 = x1;
            if (k == 0 && l == 0) {
                c0 += Number(d[v1]) * Number(o[v2]) - Number(d[v2]) * Number(o[v1]);
                c1 += Number(d[v1]) * Number(o[v3]) - Number(d[v3]) * Number(o[v1]);
            }
            if (!isZero(c0)) F[0].push_back({l, k, c0});
            if (!isZero(c1)) F[1].push_back({l, k, c1});
        }
    scale(F[0]);
    scale(F[1]);
    // Groebner().
    F.resize(kMaxElements + 2);
    int i = 0;
    reduce2(&F[0], &F[1]);
    auto lmGreater = [&](int a, int b) {
        return !F[a].empty() &&
               (F[b].empty() || greater(F[a][0].u, F[a][0].v, F[b][0].u, F[b][0].v));
    };
    if (lmGreater(1, 0)) std::swap(F[0], F[1]);
    while (!F[i + 1].empty()) {
        if (i + 2 >= kMaxElements) {
            counts.overflow = true;
            return counts;
        }
        F[i + 2] = sPolynomial(F[i], F[i + 1]);
        reduce2(&F[i + 2], &F[i]);
        if (lmGreater(i + 2, i)) std::swap(F[i + 2], F[i]);
        ++i;
        reduce2(&F[i + 1], &F[i]);
        if (lmGreater(i + 1, i)) std::swap(F[i + 1], F[i]);
    }
    counts.size = i;
    const Poly<Number>& fn = F[i];
    if (fn.empty() || (fn[0].u == 0 && fn[0].v == 0)) {
        counts.noHit = true;
        return counts;
    }
    // Roots(): the eliminant's coefficients, leading first; ZERO() constant terms stripped
    // (as the appendix's loop on a[deg] does).
    int deg = fn[0].u;
    std::vector<Number> a(deg + 1, Number(0));
    for (const Term<Number>& t : fn)
        if (t.v == 0) a[deg - t.u] = t.c;
    while (deg > 0 && isZero(a[deg])) --deg;
    counts.uDegree = deg;
    // The first root in [0, 1] (bisection on sign changes of a 4096-sample grid, in double:
    // only its v-degree is recorded), then VRoots(): the element below F_N whose polynomial
    // in v at that u is not empty, its ZERO() leading coefficients stripped.
    auto eliminantAt = [&](double u) {
        double y = 0.0;
        for (int k = 0; k <= deg; ++k) y = y * u + toDouble(a[k]);
        return y;
    };
    double root = -1.0;
    for (int s = 0; s < 4096 && root < 0.0; ++s) {
        double lo = s / 4096.0, hi = (s + 1) / 4096.0;
        if ((eliminantAt(lo) < 0.0) == (eliminantAt(hi) < 0.0)) continue;
        for (int it = 0; it < 60; ++it) {
            const double mid = 0.5 * (lo + hi);
            ((eliminantAt(lo) < 0.0) == (eliminantAt(mid) < 0.0) ? lo : hi) = mid;
        }
        root = 0.5 * (lo + hi);
    }
    if (root < 0.0) return counts;
    for (int n0 = i - 1; n0 >= 0; --n0) {
        const Poly<Number>& g = F[n0];
        if (g.empty()) continue;
        std::array<double, 4> inV{};
        for (const Term<Number>& t : g) inV[t.v] += toDouble(t.c) * std::pow(root, t.u);
        int dv = g[0].v;
        while (dv >= 0 && isZero(Number(inV[dv]))) --dv;
        if (dv < 0) continue;
        counts.vDegree = dv;
        break;
    }
    return counts;
}

}  // namespace csg::article
