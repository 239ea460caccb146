// Notation: F1 = sum_l a_l(u) v^l, F2 = sum_l b_l(u) v^l (l = 0..3); c_pq = a_p b_q - a_q b_p.
// The Bezoutian (F1(x) F2(y) - F1(y) F2(x)) / (x - y) = sum_ij B_ij x^i y^j, and for p > q
// (x^p y^q - x^q y^p) / (x - y) = sum_{m < p - q} x^(q + m) y^(p - 1 - m), so c_pq adds to
// B[q + m][p - 1 - m]. At a common root v of F1(u, .), F2(u, .) the Bezoutian vanishes for
// every x, so B(u) (1, v, v^2) = 0.
#include "primitives/patch/Resultant.h"

#include <algorithm>

#include "primitives/base/Tolerances.h"
#include "primitives/patch/PatchAlgebra.h"
#include "primitives/solvers/Solve.h"

namespace csg {

namespace {

// A polynomial in u of degree <= 18, ascending coefficients (products below keep within it).
using UPoly = std::array<double, 19>;

UPoly multiply(const UPoly& p, int degP, const UPoly& q, int degQ) {
    UPoly r{};
    for (int i = 0; i <= degP; ++i)
        for (int j = 0; j <= degQ; ++j) r[i + j] = std::fma(p[i], q[j], r[i + j]);
    return r;
}

double evalU(const UPoly& p, int deg, double u) {
    double y = p[deg];
    for (int i = deg - 1; i >= 0; --i) y = std::fma(y, u, p[i]);
    return y;
}

// The Bezout matrix of F1, F2 as polynomials of degree n in v (n <= 3), entries of degree
// <= 6 in u.
struct Bezout {
    int n = 0;
    std::array<std::array<UPoly, 3>, 3> m{};
};

// The degree in v of F1, F2 together: the highest v^l whose coefficient is not zero under
// the small-value rule (a degree-elevated patch of lower degree has rounding residue there,
// and a resultant formed at the formal degree 3 would then be rounding noise).
int degreeInV(const Bivariate& f1, const Bivariate& f2, double smallRel) {
    const double scale = std::max(f1.maxMagnitude(), f2.maxMagnitude());
    for (int l = 3; l >= 1; --l)
        for (int i = 0; i <= 3; ++i)
            if (std::abs(f1(i, l)) > smallRel * scale || std::abs(f2(i, l)) > smallRel * scale)
                return l;
    return 0;
}

Bezout bezout(const Bivariate& f1, const Bivariate& f2, double smallRel) {
    Bezout b;
    b.n = degreeInV(f1, f2, smallRel);
    UPoly a[4]{}, c[4]{};
    for (int l = 0; l <= b.n; ++l)
        for (int i = 0; i <= 3; ++i) {
            a[l][i] = f1(i, l);
            c[l][i] = f2(i, l);
        }
    for (int p = 1; p <= b.n; ++p)
        for (int q = 0; q < p; ++q) {
            const UPoly ac = multiply(a[p], 3, c[q], 3), ca = multiply(a[q], 3, c[p], 3);
            for (int k = 0; k < p - q; ++k)
                for (int i = 0; i <= 6; ++i) b.m[q + k][p - 1 - k][i] += ac[i] - ca[i];
        }
    return b;
}

// v from the null vector (1, v, .., v^(n-1)) of the numeric Bezout matrix at u. False when
// B(u) has rank < n - 1 (the gcd in v has degree >= 2: two crossings share this u) or v is
// far outside [0, 1].
bool nullVectorV(const Bezout& b, double u, double& v) {
    if (b.n == 1) return false;  // F1, F2 linear in v: the caller solves F1(u, .) directly
    double x, y;                 // the null vector's first two entries
    if (b.n == 2) {
        // (1, v) is orthogonal to the row of larger norm.
        double r0[2], r1[2];
        for (int k = 0; k < 2; ++k) {
            r0[k] = evalU(b.m[0][k], 6, u);
            r1[k] = evalU(b.m[1][k], 6, u);
        }
        const bool first = r0[0] * r0[0] + r0[1] * r0[1] >= r1[0] * r1[0] + r1[1] * r1[1];
        const double* r = first ? r0 : r1;
        if (r[0] == 0.0 && r[1] == 0.0) return false;
        x = r[1];
        y = -r[0];
    } else {
        Vec3 rows[3];
        for (int r = 0; r < 3; ++r)
            rows[r] = Vec3(evalU(b.m[r][0], 6, u), evalU(b.m[r][1], 6, u), evalU(b.m[r][2], 6, u));
        Vec3 best(0.0);
        double bestNorm = 0.0, scale = 0.0;
        for (int r = 0; r < 3; ++r) {
            scale = std::max(scale, glm::dot(rows[r], rows[r]));
            const Vec3 w = glm::cross(rows[r], rows[(r + 1) % 3]);
            const double n = glm::dot(w, w);
            if (n > bestNorm) {
                bestNorm = n;
                best = w;
            }
        }
        // Rank 2 in double: the cross product is not rounding noise of the rows' size.
        if (!(bestNorm > tol::kPatchResidualRel * scale * scale)) return false;
        x = best.x;
        y = best.y;
    }
    if (!(std::abs(x) > 0.5 * std::abs(y))) return false;  // |v| >= 2: not on the patch
    v = y / x;
    return true;
}

UPoly determinant(const Bezout& b, int& degree) {
    const auto& m = b.m;
    degree = 6 * b.n;
    if (b.n == 0) {
        degree = 0;
        return UPoly{};
    }
    if (b.n == 1) return m[0][0];
    if (b.n == 2) {
        UPoly x = multiply(m[0][0], 6, m[1][1], 6), y = multiply(m[0][1], 6, m[1][0], 6);
        for (int i = 0; i <= 12; ++i) x[i] -= y[i];
        return x;
    }
    // 3x3 by the first row's cofactors.
    auto minor = [&](int c0, int c1) {
        UPoly x = multiply(m[1][c0], 6, m[2][c1], 6), y = multiply(m[1][c1], 6, m[2][c0], 6);
        for (int i = 0; i <= 12; ++i) x[i] -= y[i];
        return x;
    };
    const UPoly t0 = multiply(m[0][0], 6, minor(1, 2), 12);
    const UPoly t1 = multiply(m[0][1], 6, minor(0, 2), 12);
    const UPoly t2 = multiply(m[0][2], 6, minor(0, 1), 12);
    UPoly det{};
    for (int i = 0; i <= 18; ++i) det[i] = t0[i] - t1[i] + t2[i];
    return det;
}

}  // namespace

std::array<double, 19> resultantInU(const Bivariate& f1, const Bivariate& f2) {
    int degree;
    return determinant(bezout(f1, f2, tol::kGroebnerSmallRel), degree);
}

int intersectByResultant(const BezierPatch& patch, const Vec3& o, const Vec3& d,
                         PatchCrossings& out, ResultantStats* stats,
                         const AlgebraOptions& options) {
    const PlaneEquations planes = planeEquations(patch, o, d);
    const Bezout b = bezout(planes.f1, planes.f2, options.smallRel);
    int degree;
    const UPoly res = determinant(b, degree);
    // Step 1: the resultant's roots in u. Degree 17 and 18 exceed Polynomial (16): the wide
    // Bernstein route of unitParameterRoots takes them, nothing is truncated.
    WidePolynomial p;
    p.degree = degree;
    std::copy(res.begin(), res.end(), p.c.begin());
    // The small-value rule on the leading coefficients: a patch of lower degree in u (the
    // article-style ones) leaves rounding residue where the resultant's top coefficients are
    // zero, which would only add roots far outside [0, 1] but misstate the degree.
    double largest = 0.0;
    for (int i = 0; i <= p.degree; ++i) largest = std::max(largest, std::abs(p.c[i]));
    while (p.degree > 0 && std::abs(p.c[p.degree]) <= options.smallRel * largest) --p.degree;
    const bool zero = p.degree == 0 && p.c[0] == 0.0;
    if (stats) stats->uDegree = zero ? -1 : p.degree;
    if (zero) return 0;  // F1, F2 share a factor (or do not involve v): no isolated crossings
    double us[18];
    const int uCount = unitParameterRoots(p, us);

    // Step 2: v at each u, from the Bezout null vector; else (below) from the plane equations.
    int n = 0;
    for (int r = 0; r < uCount && n < kMaxPatchCrossings; ++r) {
        const double u = us[r];
        const int before = n;
        double v;
        const bool rank2 = nullVectorV(b, u, v);
        if (rank2) acceptMethodRoot(patch, planes, o, d, u, v, options, out, n);
        if (n > before || (rank2 && !hasCloseNeighbour(us, uCount, r))) continue;
        // B(u) has rank < 2 (two crossings share this u), or u is a near-double root (two
        // crossings at nearly the same u) where the null vector's v is ill-conditioned: the
        // plane equations' own roots in v, polished and checked.
        crossingsFromPlaneRoots(patch, planes, o, d, u, options, out, n);
    }
    return finishCrossings(out, n);
}

int intersectByResultant(const BezierPatch& patch, const Vec3& o, const Vec3& d,
                         PatchCrossings& out) {
    return intersectByResultant(patch, o, d, out, nullptr);
}

}  // namespace csg
