// Notation: the monic quartic is y^4 + a y^3 + b y^2 + c y + d in a variable y = t / s scaled
// by a power of two s so that the coefficients are of order one. Ferrari:
//   y^4 + a y^3 + b y^2 + c y + d = (y^2 + a/2 y + phi/2)^2 - (alpha y + beta)^2
//                                 = (y^2 + a1 y + b1)(y^2 + a2 y + b2),
// with a1,2 = a/2 +- alpha, b1,2 = phi/2 +- beta, where phi is a root of the resolvent cubic
// phi^3 - b phi^2 + (ac - 4d) phi + (4bd - a^2 d - c^2) and alpha^2 = a^2/4 - b + phi,
// beta^2 = phi^2/4 - d, 2 alpha beta = a phi / 2 - c.
#include "primitives/solvers/Quartic.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>

#include "primitives/solvers/Cubic.h"
#include "primitives/solvers/Roots.h"

namespace csg {

namespace {

// 2^k for |k| <= 1022 (a normal double), built from its bits.
double powerOfTwo(int k) {
    return std::bit_cast<double>(uint64_t(1023 + k) << 52);
}

// The factor coefficients (a1, b1, a2, b2).
using Factors = std::array<double, 4>;

// Sum of the relative residuals of the four equations the factors must satisfy.
double factorError(const Factors& f, double a, double b, double c, double d) {
    const double target[4] = {a, b, c, d};
    const double got[4] = {f[0] + f[2], f[1] + f[3] + f[0] * f[2], f[0] * f[3] + f[2] * f[1],
                           f[1] * f[3]};
    double e = 0.0;
    for (int i = 0; i < 4; ++i) {
        const double r = got[i] - target[i];
        e += target[i] != 0.0 ? std::abs(r / target[i]) : std::abs(r);
    }
    return e;
}

// The factors from (alpha, beta), with the smaller-magnitude b from b1 b2 = d and the
// smaller-magnitude a from a1 b2 + a2 b1 = c, so neither comes from a cancelling sum.
Factors factorsFrom(double alpha, double beta, double a, double phi, double c, double d) {
    Factors f{0.5 * a + alpha, 0.5 * phi + beta, 0.5 * a - alpha, 0.5 * phi - beta};
    if (std::abs(f[1]) > std::abs(f[3]) && f[1] != 0.0)
        f[3] = d / f[1];
    else if (f[3] != 0.0)
        f[1] = d / f[3];
    if (std::abs(f[0]) > std::abs(f[2]) && f[1] != 0.0)
        f[2] = (c - f[0] * f[3]) / f[1];
    else if (std::abs(f[2]) >= std::abs(f[0]) && f[3] != 0.0)
        f[0] = (c - f[2] * f[1]) / f[3];
    return f;
}

// Solves the 4x4 system m x = r by Gaussian elimination with partial pivoting; false when
// singular.
bool solve4(double m[4][4], double r[4]) {
    for (int k = 0; k < 4; ++k) {
        int pivot = k;
        for (int i = k + 1; i < 4; ++i)
            if (std::abs(m[i][k]) > std::abs(m[pivot][k])) pivot = i;
        if (m[pivot][k] == 0.0) return false;
        std::swap(m[pivot], m[k]);
        std::swap(r[pivot], r[k]);
        for (int i = k + 1; i < 4; ++i) {
            const double f = m[i][k] / m[k][k];
            for (int j = k; j < 4; ++j) m[i][j] -= f * m[k][j];
            r[i] -= f * r[k];
        }
    }
    for (int k = 3; k >= 0; --k) {
        for (int j = k + 1; j < 4; ++j) r[k] -= m[k][j] * r[j];
        r[k] /= m[k][k];
    }
    return true;
}

// Newton on the factorization equations while the residual drops (Orellana & De Michele's
// refinement): a few steps bring a factorization with a few right digits to full accuracy.
void refineFactors(Factors& f, double a, double b, double c, double d) {
    double err = factorError(f, a, b, c, d);
    for (int iter = 0; iter < 8 && err > 0.0; ++iter) {
        double jac[4][4] = {{1.0, 0.0, 1.0, 0.0},
                            {f[2], 1.0, f[0], 1.0},
                            {f[3], f[2], f[1], f[0]},
                            {0.0, f[3], 0.0, f[1]}};
        double r[4] = {f[0] + f[2] - a, f[1] + f[3] + f[0] * f[2] - b,
                       f[0] * f[3] + f[2] * f[1] - c, f[1] * f[3] - d};
        if (!solve4(jac, r)) return;
        const Factors next{f[0] - r[0], f[1] - r[1], f[2] - r[2], f[3] - r[3]};
        const double nextErr = factorError(next, a, b, c, d);
        if (!(nextErr < err)) return;
        f = next, err = nextErr;
    }
}

}  // namespace

static int quarticRoots(const Polynomial& input, double* roots, bool* verified, bool allowShift);

int solveQuarticAll(const Polynomial& input, double* roots, bool* verified) {
    if (verified) *verified = true;
    return quarticRoots(input, roots, verified, true);
}

static int quarticRoots(const Polynomial& input, double* roots, bool* verified, bool allowShift) {
    const Polynomial p = input.trimmed();
    if (p.degree() < 4) {
        double c[4] = {0.0, 0.0, 0.0, 0.0};
        for (int i = 0; i <= p.degree(); ++i) c[i] = p[i];
        return solveCubicAll(c[3], c[2], c[1], c[0], roots);
    }
    // Step 1: the monic form. A leading coefficient so small that it overflows is a quartic
    // with a root beyond the doubles: the cubic part is what remains.
    const double lead = p[4];
    double a = p[3] / lead, b = p[2] / lead, c = p[1] / lead, d = p[0] / lead;
    if (!std::isfinite(a) || !std::isfinite(b) || !std::isfinite(c) || !std::isfinite(d)) {
        if (verified) *verified = false;
        return solveCubicAll(p[3], p[2], p[1], p[0], roots);
    }
    int n = 0;
    // Roots huddled within spread s < |c| / 4 of their centroid c = -a/4 make the monic
    // constant term d = q(-c) = c^4 + O(c^4 (1/16 + 1/64 + 1/256)), so |d| > 0.9 c^4: a
    // quartic with |d| < c^4 / 2 (every torus ray, whose c is ~0) skips the Taylor shift.
    const double centre = -0.25 * a;
    const double centre4 = (centre * centre) * (centre * centre);
    const bool mayHuddle = !(std::isfinite(centre4) && std::abs(d) < 0.5 * centre4);
    if (allowShift && a != 0.0 && mayHuddle) {
        // Step 1a: roots huddled around their centroid -a/4, far from 0 compared with their
        // spread (Flocke's cluster {2, 2.001, 2.002, 2.003}), make the resolvent
        // ill-conditioned; in y = t + a/4 they are spread around 0 and well resolved. The
        // Taylor shift costs only the rounding that evaluating p near the cluster costs anyway.
        const Polynomial q = p.shifted(centre);
        const double spread =
            std::max({std::sqrt(std::abs(q[2] / lead)), std::cbrt(std::abs(q[1] / lead)),
                      std::sqrt(std::sqrt(std::abs(q[0] / lead)))});
        if (spread < 0.25 * std::abs(centre)) {
            n = quarticRoots(q, roots, verified, false);
            for (int i = 0; i < n; ++i) roots[i] = polishRoot(p, roots[i] + centre);
            return finalizeRoots(p, roots, n, -kInfinity, kInfinity);
        }
    }
    if (d == 0.0) {
        // Step 1b: t = 0 is a root and the rest is a cubic.
        roots[n++] = 0.0;
        n += solveCubicAll(1.0, a, b, c, roots + n);
        return finalizeRoots(p, roots, n, -kInfinity, kInfinity);
    }

    // Step 2: scale t = s y by a power of two (exact) so the coefficients are of order one;
    // the resolvent's terms (up to degree 6 in the roots) then cannot overflow.
    const double size = std::max({std::abs(a), std::sqrt(std::abs(b)), std::cbrt(std::abs(c)),
                                  std::sqrt(std::sqrt(std::abs(d)))});
    const int e = std::ilogb(size);
    // Products with exact powers of two round as ldexp does, without its library calls; the
    // powers are normal doubles (up to 2^(4 * 255)) while |e| <= 255.
    const bool powersInRange = std::abs(e) <= 255;
    if (powersInRange) {
        const double down = powerOfTwo(-e), down2 = down * down;
        a *= down, b *= down2, c *= down2 * down, d *= down2 * down2;
    } else {
        a = std::ldexp(a, -e), b = std::ldexp(b, -2 * e), c = std::ldexp(c, -3 * e);
        d = std::ldexp(d, -4 * e);
    }
    const Polynomial monic{d, c, b, a, 1.0};

    // Step 3: the largest root of the resolvent, for which alpha^2 >= 0 (at phi = b - a^2/4
    // the resolvent is -(a phi / 2 - c)^2 <= 0, so a root lies at or above it).
    double phis[3];
    const int np = solveCubicAll(1.0, -b, a * c - 4.0 * d, 4.0 * b * d - a * a * d - c * c, phis);
    const double phi = np > 0 ? phis[np - 1] : b - 0.25 * a * a;

    // Step 4: (alpha, beta) two ways, from alpha^2 or from beta^2; keep the factorization with
    // the smaller residual, then refine it.
    const double alpha2 = std::max(0.0, std::fma(0.25 * a, a, phi - b));
    const double beta2 = std::max(0.0, std::fma(0.25 * phi, phi, -d));
    const double gamma = std::fma(0.5 * a, phi, -c);  // = 2 alpha beta
    const double alphaA = std::sqrt(alpha2);
    const double betaA = alphaA != 0.0 ? gamma / (2.0 * alphaA) : std::sqrt(beta2);
    const double betaB = std::copysign(std::sqrt(beta2), gamma);
    const double alphaB = betaB != 0.0 ? gamma / (2.0 * betaB) : alphaA;
    Factors f = factorsFrom(alphaA, betaA, a, phi, c, d);
    const Factors g = factorsFrom(alphaB, betaB, a, phi, c, d);
    if (factorError(g, a, b, c, d) < factorError(f, a, b, c, d)) f = g;
    refineFactors(f, a, b, c, d);

    // Step 5: the roots of each factor, scaled back and polished on the original quartic.
    const double s = powersInRange ? powerOfTwo(e) : std::ldexp(1.0, e);
    for (int k = 0; k < 2; ++k) {
        const double fa = f[2 * k], fb = f[2 * k + 1];
        const int m = appendQuadraticFactorRoots(monic, 1.0, fa, fb, roots + n);
        if (m == 0 && verified) {
            // A complex pair is confirmed when the quartic has, at the pair's real part x0,
            // the sign of the other factor there (the pair's own factor is positive at x0); a
            // provably opposite sign means lost real roots. Comparing with the leading
            // coefficient alone would reject every pair whose real part lies between the other
            // factor's real roots (every line through a torus's hole: many of torus_mirror's
            // rays, bench/README.md at 68b03c3).
            const double x0 = -0.5 * fa;
            const double other = (x0 + f[2 - 2 * k]) * x0 + f[3 - 2 * k];
            double bound;
            const double v = monic.eval(x0, &bound);
            const double noise = tol::kRootResidualFactor * bound;
            if (other >= 0.0 ? v < -noise : v > noise) *verified = false;
        }
        n += m;
    }
    for (int i = 0; i < n; ++i) roots[i] = polishRoot(p, roots[i] * s);
    n = finalizeRoots(p, roots, n, -kInfinity, kInfinity);
    if (verified)
        for (int i = 0; i < n; ++i)
            if (!isNumericalZero(p, roots[i])) *verified = false;
    return n;
}

int solveQuartic(const Polynomial& p, double tlo, double thi, double* roots, bool* verified) {
    double all[4];
    int n = solveQuarticAll(p, all, verified);
    int out = 0;
    for (int i = 0; i < n; ++i)
        if (all[i] >= tlo && all[i] <= thi) roots[out++] = all[i];
    return out;
}

}  // namespace csg
