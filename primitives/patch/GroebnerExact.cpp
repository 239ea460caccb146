// Notation: a ZPoly f(u, v) = sum row[j][i] u^i v^j with integer coefficients (j <= 3:
// reductions in lex v > u never raise the v-degree); lt(f) its leading monomial in lex v > u;
// every basis element is kept primitive (a basis over Q up to a rational factor each). A point of
// the parameter line is a dyadic rational N / 2^kGridBits (N an mpz): every double in [-1, 2] and
// every midpoint of the isolation is one, so the root isolation and refinement evaluate polynomials
// exactly in integers.
#include "primitives/patch/GroebnerExact.h"

#include <gmpxx.h>

#include <algorithm>
#include <vector>

#include "primitives/base/Tolerances.h"
#include "primitives/patch/Bivariate.h"
#include "primitives/patch/PatchAlgebra.h"
#include "primitives/solvers/Solve.h"

namespace csg {

namespace {

using Q = mpq_class;
using Z = mpz_class;
using UPoly = std::vector<Q>;  // ascending in u, no trailing zero (empty: the zero polynomial)

constexpr int kRows = Bivariate::kMaxDegreeV + 1;
// Bits below the binary point of the dyadic grid: a double's 53 bits at exponent >= -90 (the
// slack 1e-9 is ~2^-30) and up to ~420 levels of halving below it (the refinement of u).
constexpr int kGridBits = 512;
// Each root u is refined to an interval this many bits wide below 1 before v is read from it
// (more where v is ill-conditioned in u: Step 5): far below double resolution, so the rounded
// u is the double nearest the root (to an ulp).
constexpr int kRefineBits = 110;

// An element of the basis: integer coefficients, primitive (content 1, positive leading
// coefficient). Fraction-free reduction (f := a f - c m g with a = lc(g)) and content removal
// keep the numbers as small as the ideal allows; rationals (gcd at every operation) were ~50x
// slower on general bicubic pairs.
using ZRow = std::vector<Z>;
struct ZPoly {
    std::array<ZRow, kRows> row;
};

template <typename Row>
void trim(Row& p) {
    while (!p.empty() && sgn(p.back()) == 0) p.pop_back();
}

Monomial leading(const ZPoly& f) {
    for (int j = kRows - 1; j >= 0; --j)
        if (!f.row[j].empty()) return {int(f.row[j].size()) - 1, j};
    return {-1, -1};
}

// f divided by its content, leading coefficient made positive; false for 0.
bool makePrimitive(ZPoly& f, Monomial& lt) {
    for (ZRow& r : f.row) trim(r);
    lt = leading(f);
    if (lt.u < 0) return false;
    Z g = 0;
    for (const ZRow& r : f.row)
        for (const Z& c : r)
            if (sgn(c) != 0) mpz_gcd(g.get_mpz_t(), g.get_mpz_t(), c.get_mpz_t());
    if (sgn(f.row[lt.v][lt.u]) < 0) g = -g;
    if (g != 1)
        for (ZRow& r : f.row)
            for (Z& c : r) mpz_divexact(c.get_mpz_t(), c.get_mpz_t(), g.get_mpz_t());
    return true;
}

// f := a f - k u^shift.u v^shift.v g (the v-degree stays <= 3 where this is called).
void combine(ZPoly& f, const Z& a, const Z& k, Monomial shift, const ZPoly& g) {
    if (a != 1)
        for (ZRow& r : f.row)
            for (Z& c : r) c *= a;
    for (int j = 0; j < kRows; ++j) {
        const ZRow& gr = g.row[j];
        if (gr.empty()) continue;
        ZRow& fr = f.row[j + shift.v];
        if (fr.size() < gr.size() + shift.u) fr.resize(gr.size() + shift.u);
        for (size_t i = 0; i < gr.size(); ++i)
            if (sgn(gr[i]) != 0)
                mpz_submul(fr[i + shift.u].get_mpz_t(), k.get_mpz_t(), gr[i].get_mpz_t());
    }
}

// Full reduction of f by the primitive elements G[use[..]] (leading terms lt): every term
// some lt divides is cancelled, from the largest down; f is left primitive (or 0).
void reduce(ZPoly& f, const std::vector<ZPoly>& G, const std::vector<Monomial>& lt,
            const std::vector<int>& use) {
    Z a, k, g;
    for (int j = kRows - 1; j >= 0; --j)
        for (int i = int(f.row[j].size()) - 1; i >= 0; --i) {
            // (a step's makePrimitive trims the row: it may now end below i)
            if (i >= int(f.row[j].size()) || sgn(f.row[j][i]) == 0) continue;
            for (int e : use) {
                if (!lt[e].divides({i, j})) continue;
                const Z& lc = G[e].row[lt[e].v][lt[e].u];
                mpz_gcd(g.get_mpz_t(), f.row[j][i].get_mpz_t(), lc.get_mpz_t());
                mpz_divexact(a.get_mpz_t(), lc.get_mpz_t(), g.get_mpz_t());
                mpz_divexact(k.get_mpz_t(), f.row[j][i].get_mpz_t(), g.get_mpz_t());
                combine(f, a, k, {i - lt[e].u, j - lt[e].v}, G[e]);
                Monomial unused;
                makePrimitive(f, unused);
                break;
            }
        }
    for (ZRow& r : f.row) trim(r);
}

bool isConstant(const Monomial& m) {
    return m.u == 0 && m.v == 0;
}

// ---- Univariate polynomials over Q ----

UPoly derivative(const UPoly& p) {
    UPoly r;
    for (size_t i = 1; i < p.size(); ++i) r.push_back(p[i] * int(i));
    trim(r);
    return r;
}

// a = q b + r; returns r (b nonzero).
UPoly remainder(UPoly a, const UPoly& b, UPoly* quotient = nullptr) {
    const int nb = int(b.size()) - 1;
    if (quotient) quotient->assign(a.size() > b.size() ? a.size() - b.size() + 1 : 1, Q(0));
    while (int(a.size()) - 1 >= nb && !a.empty()) {
        const int shift = int(a.size()) - 1 - nb;
        const Q c = a.back() / b.back();
        if (quotient) (*quotient)[shift] = c;
        for (int i = 0; i <= nb; ++i) a[i + shift] -= c * b[i];
        a.pop_back();  // cancelled exactly
        trim(a);
    }
    if (quotient) trim(*quotient);
    return a;
}

UPoly monicGcd(UPoly a, UPoly b) {
    while (!b.empty()) {
        UPoly r = remainder(a, b);
        a = std::move(b);
        b = std::move(r);
    }
    if (!a.empty()) {
        const Q lc = a.back();
        for (Q& c : a) c /= lc;
    }
    return a;
}

// p scaled by a positive rational to coprime integers (same roots, same signs).
std::vector<Z> primitiveIntegers(const UPoly& p) {
    Z den = 1, g = 0;
    for (const Q& c : p) mpz_lcm(den.get_mpz_t(), den.get_mpz_t(), c.get_den_mpz_t());
    std::vector<Z> z(p.size());
    for (size_t i = 0; i < p.size(); ++i) {
        z[i] = p[i].get_num() * (den / p[i].get_den());
        mpz_gcd(g.get_mpz_t(), g.get_mpz_t(), z[i].get_mpz_t());
    }
    if (g > 1)
        for (Z& c : z) mpz_divexact(c.get_mpz_t(), c.get_mpz_t(), g.get_mpz_t());
    return z;
}

// The sign of p(N / 2^kGridBits), p with integer coefficients: 2^(K n) p(N / 2^K) by Horner.
int signAt(const std::vector<Z>& p, const Z& N) {
    const int n = int(p.size()) - 1;
    if (n < 0) return 0;
    Z acc = p[n], term;
    for (int i = n - 1; i >= 0; --i) {
        acc *= N;
        mpz_mul_2exp(term.get_mpz_t(), p[i].get_mpz_t(), mp_bitcnt_t(kGridBits) * (n - i));
        acc += term;
    }
    return sgn(acc);
}

Q gridValue(const Z& N) {
    Q x(N);
    mpq_div_2exp(x.get_mpq_t(), x.get_mpq_t(), kGridBits);
    return x;
}

Q evaluate(const UPoly& p, const Q& x) {
    Q y = 0;
    for (int i = int(p.size()) - 1; i >= 0; --i) y = y * x + p[i];
    return y;
}

Z gridOf(double x) {  // x exactly, as N / 2^kGridBits
    Q q(x);
    mpq_mul_2exp(q.get_mpq_t(), q.get_mpq_t(), kGridBits);
    return q.get_num();  // an integer: x's exponent is far above -kGridBits
}

// A root of the square-free eliminant: exactly at a grid point (exact) or alone in the open
// interval (a, b), with p's sign sa just right of a.
struct RootInterval {
    Z a, b;
    bool exact = false;
    int sa = 0;
};

int signVariations(const std::vector<Z>& b, int* first = nullptr, int* last = nullptr) {
    int changes = 0, prev = 0;
    for (const Z& c : b) {
        const int s = sgn(c);
        if (s == 0) continue;
        if (prev == 0 && first) *first = s;
        if (prev != 0 && s != prev) ++changes;
        prev = s;
    }
    if (last) *last = prev;
    return changes;
}

void removeContent(std::vector<Z>& b) {
    Z g = 0;
    for (const Z& c : b) mpz_gcd(g.get_mpz_t(), g.get_mpz_t(), c.get_mpz_t());
    if (g > 1)
        for (Z& c : b) mpz_divexact(c.get_mpz_t(), c.get_mpz_t(), g.get_mpz_t());
}

// Descartes' rule on the Bernstein coefficients b of p on (a, b): 0 variations, no root; 1,
// exactly one; else halve (de Casteljau in integers: level r of the triangle is 2^r times the
// true value, each half rescaled to a common 2^n, which leaves every sign as it is).
void isolate(std::vector<Z> bern, const Z& a, const Z& b, std::vector<RootInterval>& roots) {
    int first = 0, last = 0;
    const int var = signVariations(bern, &first, &last);
    if (var == 0) return;
    if (var == 1 || b - a <= 1) {
        roots.push_back({a, b, false, first});
        return;
    }
    const int n = int(bern.size()) - 1;
    const Z sum = a + b;
    if (mpz_odd_p(sum.get_mpz_t())) {  // below the grid: cannot happen for doubles' roots
        roots.push_back({a, b, false, first});
        return;
    }
    const Z m = sum / 2;
    std::vector<Z> left(n + 1), right(n + 1);
    std::vector<Z> level = bern;
    left[0] = level[0];
    right[n] = level[n];
    for (int r = 1; r <= n; ++r) {
        for (int i = 0; i + r <= n; ++i) level[i] += level[i + 1];
        left[r] = level[0];
        right[n - r] = level[n - r];
    }
    for (int k = 0; k <= n; ++k) {
        mpz_mul_2exp(left[k].get_mpz_t(), left[k].get_mpz_t(), n - k);
        mpz_mul_2exp(right[k].get_mpz_t(), right[k].get_mpz_t(), k);
    }
    removeContent(left);
    removeContent(right);
    isolate(std::move(left), a, m, roots);
    if (sgn(right[0]) == 0) roots.push_back({m, m, true, 0});  // p(m) = 0 exactly
    isolate(std::move(right), m, b, roots);
}

// The exact Bernstein coefficients of p on [a, b] (grid numerators), as coprime integers.
std::vector<Z> bernsteinOn(const UPoly& p, const Z& a, const Z& b) {
    const int n = int(p.size()) - 1;
    const Q lo = gridValue(a), w = gridValue(b) - gridValue(a);
    UPoly q = p;  // p(lo + w x): Taylor shift, then scaling
    for (int k = 0; k < n; ++k)
        for (int i = n - 1; i >= k; --i) q[i] += lo * q[i + 1];
    Q f = 1;
    for (int i = 0; i <= n; ++i, f *= w) q[i] *= f;
    UPoly bern(n + 1);
    Z binom;
    for (int k = 0; k <= n; ++k) {
        Q s = 0;
        for (int i = 0; i <= k; ++i) {
            Q ratio;  // C(k, i) / C(n, i)
            mpz_bin_uiui(binom.get_mpz_t(), k, i);
            Z cni;
            mpz_bin_uiui(cni.get_mpz_t(), n, i);
            ratio = Q(binom, cni);
            ratio.canonicalize();
            s += ratio * q[i];
        }
        bern[k] = s;
    }
    return primitiveIntegers(bern);
}

// The plane equation n . (S(u, v) - o) of patch over Q, in the monomial basis (transposed:
// the roles of u and v swapped).
ZPoly planeEquation(const BezierPatch& patch, const Vec3& o, const Q n[3], bool transposed) {
    static const int C[4] = {1, 3, 3, 1};
    Q b[4][4];  // Bernstein coefficients n . (P_ij - o), exact
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) {
            const Vec3& p = transposed ? patch.at(j, i) : patch.at(i, j);
            b[i][j] = 0;
            for (int c = 0; c < 3; ++c) b[i][j] += n[c] * (Q(p[c]) - Q(o[c]));
        }
    // B_i(x) = C(3, i) x^i (1 - x)^(3 - i) = sum_m C(3, i) C(3 - i, m - i) (-1)^(m - i) x^m.
    auto basis = [](int i, int m) {
        static const int C3[4][4] = {{1, 0, 0, 0}, {1, 1, 0, 0}, {1, 2, 1, 0}, {1, 3, 3, 1}};
        if (m < i) return 0;
        return C[i] * C3[3 - i][m - i] * ((m - i) % 2 ? -1 : 1);
    };
    UPoly all(16, Q(0));  // row mv at 4 mv: one common integer scaling for the 4 rows
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j)
            for (int mu = i; mu < 4; ++mu)
                for (int mv = j; mv < 4; ++mv)
                    all[4 * mv + mu] += b[i][j] * (basis(i, mu) * basis(j, mv));
    Z den = 1;
    for (const Q& c : all) mpz_lcm(den.get_mpz_t(), den.get_mpz_t(), c.get_den_mpz_t());
    ZPoly f;
    for (int mv = 0; mv < 4; ++mv)
        for (int mu = 0; mu < 4; ++mu)
            f.row[mv].push_back(all[4 * mv + mu].get_num() * (den / all[4 * mv + mu].get_den()));
    for (ZRow& r : f.row) trim(r);
    return f;
}

int degreeU(const ZPoly& f) {
    int d = -1;
    for (const ZRow& r : f.row) d = std::max(d, int(r.size()) - 1);
    return d;
}

UPoly toQ(const ZRow& r) {
    return UPoly(r.begin(), r.end());
}

// ---- The shape basis: the reduced basis read off the Bezout resultant, then proved ----
// Integer polynomials in u (ZRow, ascending): no rational arithmetic, whose gcd at every
// operation made this step ~100x slower.

ZRow multiply(const ZRow& a, const ZRow& b) {
    if (a.empty() || b.empty()) return {};
    ZRow r(a.size() + b.size() - 1);
    for (size_t i = 0; i < a.size(); ++i)
        for (size_t j = 0; j < b.size(); ++j)
            mpz_addmul(r[i + j].get_mpz_t(), a[i].get_mpz_t(), b[j].get_mpz_t());
    trim(r);
    return r;
}

ZRow subtract(ZRow a, const ZRow& b) {
    if (a.size() < b.size()) a.resize(b.size());
    for (size_t i = 0; i < b.size(); ++i) a[i] -= b[i];
    trim(a);
    return a;
}

ZRow add(ZRow a, const ZRow& b) {
    if (a.size() < b.size()) a.resize(b.size());
    for (size_t i = 0; i < b.size(); ++i) a[i] += b[i];
    trim(a);
    return a;
}

// True when m (nonzero) divides a in Q[u]: the pseudo-remainder lc(m)^k a mod m, in integers.
bool divides(const ZRow& m, ZRow a) {
    const size_t nm = m.size();
    const Z& lc = m.back();
    while (a.size() >= nm) {
        const Z c = a.back();
        const size_t shift = a.size() - nm;
        for (Z& x : a) x *= lc;
        for (size_t i = 0; i < nm; ++i)
            mpz_submul(a[i + shift].get_mpz_t(), c.get_mpz_t(), m[i].get_mpz_t());
        a.pop_back();  // cancelled exactly
        trim(a);
        removeContent(a);
    }
    return a.empty();
}

// True when a and m (m of degree >= 1) have no common factor over Q. Euclid modulo the prime
// 2^61 - 1: a common factor g over Q (primitive, lc(g) divides lc(m)) stays one modulo any
// prime not dividing lc(m), so a constant gcd modulo p proves coprimality; when p divides
// lc(m) (never seen) the answer is "not proved".
bool coprime(const ZRow& a, const ZRow& m) {
    using u64 = unsigned long long;
    __extension__ typedef unsigned __int128 u128;  // GCC and Clang: the product of two u64
    constexpr u64 P = (1ull << 61) - 1;
    auto mulmod = [](u64 x, u64 y) { return u64(u128(x) * y % P); };
    auto powmod = [&](u64 x, u64 e) {
        u64 r = 1;
        for (; e; e >>= 1, x = mulmod(x, x))
            if (e & 1) r = mulmod(r, x);
        return r;
    };
    auto reduceMod = [&](const ZRow& f, std::vector<u64>& out) {
        const Z modulus = Z(1) << 61;
        const Z prime = modulus - 1;
        out.clear();
        Z r;
        for (const Z& c : f) {
            mpz_fdiv_r(r.get_mpz_t(), c.get_mpz_t(), prime.get_mpz_t());  // in [0, P)
            out.push_back(u64(mpz_get_ui(r.get_mpz_t())));
        }
        while (!out.empty() && out.back() == 0) out.pop_back();
    };
    std::vector<u64> x, y;
    reduceMod(m, x);
    if (int(x.size()) != int(m.size())) return false;  // p divides lc(m)
    reduceMod(a, y);
    while (!y.empty()) {  // x := x mod y, swap
        const u64 inv = powmod(y.back(), P - 2);
        while (x.size() >= y.size()) {
            const u64 c = mulmod(x.back(), inv);
            const size_t shift = x.size() - y.size();
            for (size_t i = 0; i < y.size(); ++i)
                x[i + shift] = (x[i + shift] + P - mulmod(c, y[i])) % P;
            x.pop_back();
            while (!x.empty() && x.back() == 0) x.pop_back();
        }
        std::swap(x, y);
    }
    return x.size() == 1;
}

// The lex basis {g0(u), e v - c(u)} of <f1, f2>, when the ideal is in shape position, without
// Buchberger's intermediate swell: g0 = Res_v(f1, f2) (the Bezout determinant, as in
// Resultant.cpp), v = c / e at a common root from the Bezout null vector, e coprime to g0. The
// reduced basis is {g0, v - h} with h = c / e mod g0; the second element is kept as e v - c,
// which has the same value of v at every root (what back-substitution reads) and spares the
// inverse modulo g0 (rational extended Euclid: the slowest step by far). Proof that it is the
// basis: f1 and f2 vanish modulo {g0, v - h} (so <f1, f2> lies in <g0, v - h>), and
// deg g0 = 2 a b for f1, f2 of bidegree (a, b) without a common factor: the quotient by
// <g0, v - h> then has dimension 2 a b, the bihomogeneous Bezout bound on the quotient by
// <f1, f2>, so the two ideals are equal. False (use Buchberger) when any step does not hold:
// two crossings sharing a u, solutions at infinity (a degenerate patch), a common factor.
bool shapeBasis(const ZPoly& f1, const ZPoly& f2, std::vector<ZPoly>& basis) {
    const int n = std::max(leading(f1).v, leading(f2).v);
    const int a = std::max(degreeU(f1), degreeU(f2));
    if (n < 1 || a < 1) return false;
    const ZRow* p = f1.row.data();
    const ZRow* q = f2.row.data();
    // No common factor in u alone: one row of f1 coprime to one row of f2 proves it.
    bool noCommonFactor = false;
    for (int l = 0; l <= n && !noCommonFactor; ++l)
        for (int m = 0; m <= n && !noCommonFactor; ++m)
            noCommonFactor = !p[l].empty() && !q[m].empty() && coprime(p[l], q[m]);
    if (!noCommonFactor) return false;
    // The Bezout matrix: (f1(x) f2(y) - f1(y) f2(x)) / (x - y) = sum B_ij x^i y^j.
    ZRow B[3][3];
    for (int hi = 1; hi <= n; ++hi)
        for (int lo = 0; lo < hi; ++lo) {
            const ZRow c = subtract(multiply(p[hi], q[lo]), multiply(p[lo], q[hi]));
            for (int k = 0; k < hi - lo; ++k) B[lo + k][hi - 1 - k] = add(B[lo + k][hi - 1 - k], c);
        }
    auto det2 = [](const ZRow& w, const ZRow& x, const ZRow& y, const ZRow& z) {
        return subtract(multiply(w, z), multiply(x, y));
    };
    auto negate = [](ZRow x) {
        for (Z& c : x) c = -c;
        return x;
    };
    ZRow g0;
    // Candidates (c, e) for v = c / e at a root (the null vector (1, v, ..) of B(u)).
    std::vector<std::pair<ZRow, ZRow>> candidates;
    if (n == 1) {
        g0 = B[0][0];
        candidates = {{negate(p[0]), p[1]}, {negate(q[0]), q[1]}};
    } else if (n == 2) {
        g0 = det2(B[0][0], B[0][1], B[1][0], B[1][1]);
        candidates = {{negate(B[0][0]), B[0][1]}, {negate(B[1][0]), B[1][1]}};
    } else {
        g0 = add(subtract(multiply(B[0][0], det2(B[1][1], B[1][2], B[2][1], B[2][2])),
                          multiply(B[0][1], det2(B[1][0], B[1][2], B[2][0], B[2][2]))),
                 multiply(B[0][2], det2(B[1][0], B[1][1], B[2][0], B[2][1])));
        for (auto [r, s] : {std::pair{0, 1}, std::pair{1, 2}, std::pair{0, 2}})  // row r x row s
            candidates.push_back({det2(B[r][2], B[r][0], B[s][2], B[s][0]),
                                  det2(B[r][1], B[r][2], B[s][1], B[s][2])});
    }
    if (int(g0.size()) - 1 != 2 * a * n) return false;
    removeContent(g0);
    for (auto& [c, e] : candidates) {
        if (e.empty() || !coprime(e, g0)) continue;
        // e^n f_k(u, c / e) = sum_l f_kl c^l e^(n - l) must vanish modulo g0.
        bool vanish = true;
        for (const ZRow* f : {p, q}) {
            std::vector<ZRow> cPowers{{Z(1)}}, ePowers{{Z(1)}};
            for (int l = 1; l <= n; ++l) {
                cPowers.push_back(multiply(cPowers.back(), c));
                ePowers.push_back(multiply(ePowers.back(), e));
            }
            ZRow sum;
            for (int l = 0; l <= n; ++l)
                sum = add(sum, multiply(f[l], multiply(cPowers[l], ePowers[n - l])));
            vanish = vanish && divides(g0, sum);
        }
        if (!vanish) continue;
        ZPoly e0, e1;
        e0.row[0] = g0;
        e1.row[1] = e;
        e1.row[0] = negate(c);
        Monomial m;
        makePrimitive(e0, m);
        makePrimitive(e1, m);
        basis = {std::move(e0), std::move(e1)};
        return true;
    }
    return false;
}

// Buchberger's algorithm (normal strategy, first criterion) and the reduced basis, sorted by
// leading term ascending. Returns false when 1 is in the ideal (stats.empty) or an input is 0.
bool reducedBasis(ZPoly f1, ZPoly f2, std::vector<ZPoly>& basis, ExactGroebnerStats& stats) {
    std::vector<ZPoly> G;
    std::vector<Monomial> lt;
    for (ZPoly* f : {&f1, &f2}) {
        Monomial m;
        if (!makePrimitive(*f, m)) {
            stats.notZeroDimensional = true;  // a plane contains the whole patch
            return false;
        }
        G.push_back(std::move(*f));
        lt.push_back(m);
    }
    std::vector<std::pair<int, int>> pairs{{0, 1}};
    std::vector<int> all{0, 1};
    auto lcmOf = [&](const std::pair<int, int>& p) {
        return Monomial{std::max(lt[p.first].u, lt[p.second].u),
                        std::max(lt[p.first].v, lt[p.second].v)};
    };
    while (!pairs.empty()) {
        size_t pick = 0;
        for (size_t k = 1; k < pairs.size(); ++k) {
            const Monomial a = lcmOf(pairs[k]), b = lcmOf(pairs[pick]);
            if (a.v != b.v ? a.v < b.v : a.u < b.u) pick = k;
        }
        const auto [i, j] = pairs[pick];
        pairs.erase(pairs.begin() + long(pick));
        const Monomial a = lt[i], b = lt[j];
        if ((a.u == 0 || b.u == 0) && (a.v == 0 || b.v == 0)) continue;  // coprime: reduces to 0
        const Monomial l = lcmOf({i, j});
        // Buchberger's chain criterion: an element k whose leading term divides the lcm, with
        // the pairs (i, k) and (j, k) already treated, makes this pair's S-polynomial reduce
        // to 0. Most pairs go this way; each would cost a reduction of ~1000-digit numbers.
        auto pending = [&](int x, int y) {
            for (const auto& q : pairs)
                if ((q.first == x && q.second == y) || (q.first == y && q.second == x)) return true;
            return false;
        };
        bool chained = false;
        for (int k = 0; k < int(G.size()) && !chained; ++k)
            chained = k != i && k != j && lt[k].divides(l) && !pending(i, k) && !pending(j, k);
        if (chained) continue;
        // s = (c_j / g) m_i G_i - (c_i / g) m_j G_j, c the leading coefficients, g their gcd.
        const Z& ci = G[i].row[a.v][a.u];
        const Z& cj = G[j].row[b.v][b.u];
        Z g, ki, kj;
        mpz_gcd(g.get_mpz_t(), ci.get_mpz_t(), cj.get_mpz_t());
        mpz_divexact(ki.get_mpz_t(), cj.get_mpz_t(), g.get_mpz_t());
        mpz_divexact(kj.get_mpz_t(), ci.get_mpz_t(), g.get_mpz_t());
        ZPoly s;
        combine(s, Z(1), Z(-ki), {l.u - a.u, l.v - a.v}, G[i]);
        combine(s, Z(1), kj, {l.u - b.u, l.v - b.v}, G[j]);
        s.row[l.v][l.u] = 0;  // cancelled exactly
        for (ZRow& r : s.row) trim(r);
        Monomial m;
        if (!makePrimitive(s, m)) continue;
        reduce(s, G, lt, all);
        if (!makePrimitive(s, m)) continue;
        if (isConstant(m)) {
            stats.empty = true;
            stats.rawBasisSize = int(G.size()) + 1;
            stats.basisSize = 1;
            return false;
        }
        for (int k = 0; k < int(G.size()); ++k) pairs.push_back({k, int(G.size())});
        all.push_back(int(G.size()));
        G.push_back(std::move(s));
        lt.push_back(m);
    }
    stats.rawBasisSize = int(G.size());
    // Minimal basis: drop an element whose leading term another's divides (of equal ones, the
    // later); sort the rest ascending; reduce each by the others.
    std::vector<int> kept;
    for (int k = 0; k < int(G.size()); ++k) {
        bool redundant = false;
        for (int m = 0; m < int(G.size()) && !redundant; ++m)
            redundant = m != k && lt[m].divides(lt[k]) &&
                        (lt[m].u != lt[k].u || lt[m].v != lt[k].v || m < k);
        if (!redundant) kept.push_back(k);
    }
    std::sort(kept.begin(), kept.end(), [&](int x, int y) {
        return lt[x].v != lt[y].v ? lt[x].v < lt[y].v : lt[x].u < lt[y].u;
    });
    for (size_t k = 0; k < kept.size(); ++k) {
        std::vector<int> others;
        for (size_t m = 0; m < kept.size(); ++m)
            if (m != k) others.push_back(kept[m]);
        ZPoly g = G[kept[k]];
        reduce(g, G, lt, others);  // lt(g) is not divisible by the others: it stays
        Monomial m;
        makePrimitive(g, m);
        basis.push_back(std::move(g));
    }
    stats.basisSize = int(basis.size());
    return true;
}

}  // namespace

int intersectByExactGroebner(const BezierPatch& patch, const Vec3& o, const Vec3& d,
                             PatchCrossings& out, ExactGroebnerStats* statsOut) {
    ExactGroebnerStats stats;
    // Step 1: two planes through the line, exactly: n = e_a x d for the two axes a other than
    // d's largest component (independent: their cross product is d_k d).
    int k = 0;
    for (int c = 1; c < 3; ++c)
        if (std::abs(d[c]) > std::abs(d[k])) k = c;
    Q n[2][3];
    for (int p = 0, a = 0; a < 3; ++a) {
        if (a == k) continue;
        const int b = (a + 1) % 3, c = (a + 2) % 3;  // e_a x d = (0, -d_c, d_b) rotated to a
        n[p][a] = 0;
        n[p][b] = -Q(d[c]);
        n[p][c] = Q(d[b]);
        ++p;
    }
    // Step 2: the variable order: v, the eliminated one, is the parameter of lower degree.
    ZPoly f1 = planeEquation(patch, o, n[0], false), f2 = planeEquation(patch, o, n[1], false);
    const int degU = std::max(degreeU(f1), degreeU(f2));
    const int degV = std::max(leading(f1).v, leading(f2).v);
    if (degV > degU) {
        stats.swapped = true;
        f1 = planeEquation(patch, o, n[0], true);
        f2 = planeEquation(patch, o, n[1], true);
    }
    // Step 3: the reduced lex basis, v > u.
    // The shape basis when it can be proved; else Buchberger (exact either way).
    std::vector<ZPoly> basis;
    stats.shapeBasis = shapeBasis(f1, f2, basis);
    if (!stats.shapeBasis && degU == degV) {
        // Equal degrees: either order is the method's. A patch with a pole (an edge collapsed
        // to a point, as on the teapot's lid and bottom) has solutions at infinity in one
        // order, which the shape basis' proof cannot exclude, and often none in the other:
        // try it before Buchberger (~100x slower).
        ZPoly g1 = planeEquation(patch, o, n[0], true), g2 = planeEquation(patch, o, n[1], true);
        if (shapeBasis(g1, g2, basis)) {
            stats.shapeBasis = stats.swapped = true;
            f1 = std::move(g1);
            f2 = std::move(g2);
        }
    }
    if (stats.shapeBasis) stats.basisSize = 2;
    const bool ok = stats.shapeBasis || reducedBasis(f1, f2, basis, stats);
    if (statsOut) *statsOut = stats;
    if (!ok) return 0;
    if (leading(basis[0]).v != 0) {
        if (statsOut) statsOut->notZeroDimensional = true;
        return 0;
    }
    // Step 4: the square-free part of the eliminant and its roots in [lo, hi], isolated.
    const UPoly eliminant = toQ(basis[0].row[0]);
    stats.uDegree = int(eliminant.size()) - 1;
    // Square-free when the eliminant is coprime to its derivative (proved modulo a prime, the
    // usual case); else divided by the gcd over Q.
    UPoly squareFree;
    ZRow derivativeZ;
    for (size_t i = 1; i < basis[0].row[0].size(); ++i)
        derivativeZ.push_back(basis[0].row[0][i] * int(i));
    if (coprime(derivativeZ, basis[0].row[0]))
        squareFree = eliminant;
    else
        remainder(eliminant, monicGcd(eliminant, derivative(eliminant)), &squareFree);
    stats.squareFreeDegree = int(squareFree.size()) - 1;
    if (statsOut) *statsOut = stats;
    if (stats.squareFreeDegree < 1) return 0;
    const std::vector<Z> p = primitiveIntegers(squareFree);
    const Z lo = gridOf(-tol::kPatchParamSlack), hi = gridOf(1.0 + tol::kPatchParamSlack);
    std::vector<RootInterval> roots;
    if (signAt(p, lo) == 0) roots.push_back({lo, lo, true, 0});
    isolate(bernsteinOn(squareFree, lo, hi), lo, hi, roots);
    if (signAt(p, hi) == 0) roots.push_back({hi, hi, true, 0});

    // Step 5: each root refined by exact bisection to kRefineBits, then v from the first basis
    // element whose leading coefficient (in v) does not vanish at the root (Kalkbrener: it
    // generates the ideal specialized there), then t.
    auto refine = [&](RootInterval& r, int bits) {
        const Z width = Z(1) << (kGridBits - bits);
        while (!r.exact && r.b - r.a > width) {
            const Z m = (r.a + r.b) / 2;
            const int s = signAt(p, m);
            if (s == 0) {
                r.a = r.b = m;
                r.exact = true;
            } else if (s == r.sa) {
                r.a = m;
            } else {
                r.b = m;
            }
        }
    };
    int count = 0;
    for (RootInterval& r : roots) {
        int bits = kRefineBits;
        refine(r, bits);
        const ZPoly* pick = &basis.back();
        // (The shape basis' e v - c has e coprime to g0, proved: it is the element.)
        for (size_t e = 1; e < basis.size() && !stats.shapeBasis; ++e) {
            const UPoly lc = toQ(basis[e].row[leading(basis[e]).v]);
            bool vanishes;
            if (r.exact) {
                vanishes = sgn(evaluate(lc, gridValue(r.a))) == 0;
            } else {
                const UPoly h = monicGcd(squareFree, lc);
                const std::vector<Z> hz = primitiveIntegers(h);
                vanishes = h.size() > 1 && signAt(hz, r.a) != signAt(hz, r.b);
            }
            if (!vanishes) {
                pick = &basis[e];
                break;
            }
        }
        const int dv = leading(*pick).v;
        // v = -c0(u) / c1(u) is a rational function of u whose derivative can be huge (roots of
        // the eliminant clustered or near infinity: ~1e28 on teapot rays): refine u until v at
        // both ends of its interval agrees to 2^-64, so v is right to double precision.
        while (dv == 1 && !r.exact && bits + 40 < kGridBits - 8) {
            const Q va = -evaluate(toQ(pick->row[0]), gridValue(r.a)) /
                         evaluate(toQ(pick->row[1]), gridValue(r.a));
            const Q vb = -evaluate(toQ(pick->row[0]), gridValue(r.b)) /
                         evaluate(toQ(pick->row[1]), gridValue(r.b));
            Q gap = abs(va - vb);
            mpq_mul_2exp(gap.get_mpq_t(), gap.get_mpq_t(), 64);
            if (gap <= 1) break;
            bits += 40;
            refine(r, bits);
        }
        const Q u = r.exact ? gridValue(r.a) : gridValue((r.a + r.b) / 2);
        std::array<Q, kRows> c;
        for (int j = 0; j <= dv; ++j) c[j] = evaluate(toQ(pick->row[j]), u);
        double vs[kRows];
        int vCount = 0;
        if (dv == 1) {
            vs[vCount++] = Q(-c[0] / c[1]).get_d();
        } else {
            Q largest = 0;
            for (int j = 0; j <= dv; ++j) largest = std::max(largest, Q(abs(c[j])));
            Polynomial inV = Polynomial::ofDegree(dv);
            for (int j = 0; j <= dv; ++j) inV[j] = Q(c[j] / largest).get_d();
            vCount = solve(inV.trimmed(), -tol::kPatchParamSlack, 1.0 + tol::kPatchParamSlack, vs);
        }
        const double ud = u.get_d();
        for (int q = 0; q < vCount && count < kMaxPatchCrossings; ++q) {
            const double v = vs[q];
            if (!(v >= -tol::kPatchParamSlack && v <= 1.0 + tol::kPatchParamSlack)) continue;
            if (stats.swapped)
                appendCrossing(patch, o, d, v, ud, out, count);
            else
                appendCrossing(patch, o, d, ud, v, out, count);
        }
    }
    return finishCrossings(out, count);
}

}  // namespace csg
