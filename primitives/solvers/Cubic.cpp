// Notation: the cubic is A t^3 + B t^2 + C t + D (Kahan, "To Solve a Real Cubic Equation",
// 1986). x is the root found by iteration; a t^2 + b t + c is the quotient after deflating it.
#include "primitives/solvers/Cubic.h"

#include <cmath>

#include "primitives/solvers/Quadratic.h"
#include "primitives/solvers/Roots.h"

namespace csg {

namespace {

// Horner on the cubic at x, keeping the deflated quadratic's coefficients b1, c2 as well.
struct CubicAt {
    double q, dq, b1, c2;
};
CubicAt evalCubic(double x, double A, double B, double C, double D) {
    const double b1 = A * x + B;
    const double c2 = b1 * x + C;
    return {c2 * x + D, (A * x + b1) * x + c2, b1, c2};
}

}  // namespace

int appendQuadraticFactorRoots(const Polynomial& whole, double a, double b, double c,
                               double* roots) {
    double r0, r1;
    const int n = solveQuadratic(a, b, c, r0, r1);
    if (n == 2 || n == 1) {
        roots[0] = r0;
        if (n == 1) return 1;
        roots[1] = r1;
        return 2;
    }
    if (a == 0.0) return 0;
    // A complex pair this close to the axis is a rounded double root when p has no
    // trustworthy sign at the vertex.
    const double vertex = -b / (2.0 * a);
    if (!std::isfinite(vertex) || !isNumericalZero(whole, vertex)) return 0;
    roots[0] = roots[1] = vertex;
    return 2;
}

int solveCubicAll(double A, double B, double C, double D, double* roots) {
    const Polynomial p{D, C, B, A};
    int n = 0;
    double a = A, b, c;
    if (A == 0.0 || !std::isfinite(B / A) || !std::isfinite(C / A) || !std::isfinite(D / A)) {
        // Step 0: effectively a quadratic; a root beyond the range of doubles is dropped.
        if (A != 0.0 && std::isfinite(-B / A) && B != 0.0) roots[n++] = -B / A;
        a = B, b = C, c = D;
        n += appendQuadraticFactorRoots(p, a, b, c, roots + n);
        return finalizeRoots(p, roots, n, -kInfinity, kInfinity);
    }
    double x;
    if (D == 0.0) {
        // Step 1a: t = 0 is a root; the quotient is exact.
        x = 0.0, b = B, c = C;
    } else {
        // Step 1b: Newton from a start beyond the root on the side where the cubic is convex
        // in the root's direction, so the iterates move monotonically to it (Kahan's QBC).
        x = -(B / A) / 3.0;
        CubicAt e = evalCubic(x, A, B, C, D);
        double t = e.q / A;
        double r = std::cbrt(std::abs(t));
        const double s = t < 0.0 ? -1.0 : 1.0;
        t = -e.dq / A;
        if (t > 0.0) r = 1.324718 * std::max(r, std::sqrt(t));
        double x0 = x - s * r;
        b = e.b1, c = e.c2;
        if (x0 != x) {
            do {
                x = x0;
                e = evalCubic(x, A, B, C, D);
                // The factor just above 1 makes the last steps undershoot, so the loop ends
                // once rounding stops the monotone progress.
                x0 = e.dq == 0.0 ? x : x - (e.q / e.dq) / 1.000000000000001;
            } while (s * x0 > s * x);
            b = e.b1, c = e.c2;
            // Step 2: of the two ways to deflate, take the one without cancellation.
            if (std::abs(A) * x * x > std::abs(D / x)) {
                c = -D / x;
                b = (c - C) / x;
            }
        }
    }
    roots[n++] = x;
    // Step 3: the quadratic quotient, then every root polished on the cubic itself.
    n += appendQuadraticFactorRoots(p, a, b, c, roots + n);
    for (int i = 1; i < n; ++i) roots[i] = polishRoot(p, roots[i]);
    return finalizeRoots(p, roots, n, -kInfinity, kInfinity);
}

int solveCubic(const Polynomial& p, double tlo, double thi, double* roots) {
    const Polynomial q = p.trimmed();
    double all[3];
    int n = 0;
    switch (q.degree()) {
        case 0:
            return 0;
        case 1:
            all[n++] = -q[0] / q[1];
            break;
        case 2:
            n = appendQuadraticFactorRoots(q, q[2], q[1], q[0], all);
            break;
        case 3:
            n = solveCubicAll(q[3], q[2], q[1], q[0], all);
            break;
        default:
            return 0;
    }
    n = finalizeRoots(q, all, n, tlo, thi);
    for (int i = 0; i < n; ++i) roots[i] = all[i];
    return n;
}

}  // namespace csg
