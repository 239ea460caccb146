// Notation: x = (t - tlo) / w, w = thi - tlo, maps the range to [0, 1]; a piece is a dyadic
// [a, b] in x (b - a = 2^-depth), [ta, tb] in t; its local polynomial is p(ta + (tb - ta) x),
// x in [0, 1]. Every piece is formed from p directly (a Taylor shift to ta, then a rescaling),
// so rounding does not accumulate down the bisection tree as it would with repeated halving.
#include "primitives/solvers/Descartes.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "primitives/solvers/Roots.h"

namespace csg {

namespace {

// The Descartes count of p on the piece [ta, ta + 2^(k - depth) f] (t units), where the
// whole range's width is 2^k f, 1 <= f < 2; -1 when every coefficient of the transformed
// polynomial is within its rounding-error bound (p is indistinguishable from 0 on the piece,
// as next to a tangency).
int pieceVariations(const Polynomial& p, const Polynomial& absP, double ta, double f, int k,
                    int depth) {
    const int n = p.degree();
    // Step 1: local polynomial r(x) = p(ta + h x), h = 2^(k - depth) f, shifted from p itself
    // (at ta, near the roots once the pieces are small, so small roots keep their digits).
    // The power of two in h^i is applied with ldexp, centred by h^(-n/2) so that neither
    // end of the coefficient list over- or underflows; the same steps on |p| at |ta| (no
    // cancellation there) bound the magnitudes the rounding errors scale with.
    Polynomial r = p.shifted(ta).argumentScaled(f),
               e = absP.shifted(std::abs(ta)).argumentScaled(f);
    const int e2 = k - depth;
    for (int i = 0; i <= n; ++i) {
        r[i] = std::ldexp(r[i], e2 * i - e2 * n / 2);
        e[i] = std::ldexp(e[i], e2 * i - e2 * n / 2);
    }
    // Step 2: reverse (x^n r(1/x)) and shift by 1: the map of (0, 1) onto (0, inf).
    Polynomial rev = Polynomial::ofDegree(n), revE = Polynomial::ofDegree(n);
    for (int i = 0; i <= n; ++i) rev[i] = r[n - i], revE[i] = e[n - i];
    const Polynomial m = rev.shifted(1.0), bound = revE.shifted(1.0);
    // Step 3: the count, with coefficients within their error bound (two shifts of n^2 / 2
    // fmas each, gamma(2 n) per shift on the magnitudes) taken as either sign.
    std::array<double, Polynomial::kMaxDegree + 1> c, noise;
    const double g = tol::gamma(4 * n + 4);
    for (int i = 0; i <= n; ++i) c[i] = m[i], noise[i] = g * bound[i];
    return maxSignVariations(c.data(), noise.data(), n);
}

}  // namespace

int solveDescartes(const Polynomial& input, double tlo, double thi, double* roots, double relTol) {
    const Polynomial p = input.trimmed();
    if (p.degree() == 0 || !(tlo <= thi)) return 0;
    const double w = thi - tlo;
    if (!(w > 0.0)) return isNumericalZero(p, tlo) ? (roots[0] = tlo, 1) : 0;
    // Step 1: p scaled so its largest coefficient is about 1, |p|, and the range's width as
    // 2^k f with 1 <= f < 2.
    Polynomial q = p;
    const double qm = q.maxMagnitude();
    if (qm > 0.0) q = q.scaled(std::ldexp(1.0, -std::ilogb(qm)));
    Polynomial absQ = q;
    for (int i = 0; i <= q.degree(); ++i) absQ[i] = std::abs(q[i]);
    const int k = std::ilogb(w);
    const double f = std::ldexp(w, -k);
    const Polynomial dp = p.derivative();
    auto toT = [&](double x) { return x >= 1.0 ? thi : std::fma(w, x, tlo); };

    struct Piece {
        double a;  // left end in x; the width is 2^-depth
        int depth;
    };
    std::array<Piece, tol::kMaxSubdivisionDepth + 2> stack;
    // Room for the roots, rounding's extra candidates and one flush of undecided pieces.
    std::array<double, 4 * Polynomial::kMaxDegree + 16> found;
    const int capacity = int(found.size()) - 18;
    UndecidedPieces undecided;
    int top = 0, n = 0;
    stack[top++] = {0.0, 0};
    listExactZero(p, dp, tlo, found.data(), &n);
    listExactZero(p, dp, thi, found.data(), &n);
    while (top > 0 && n < capacity) {
        const Piece piece = stack[--top];
        const double b = piece.a + std::ldexp(1.0, -piece.depth);
        const double ta = toT(piece.a), tb = toT(b);
        // Step 2: Descartes' count of the roots in the open piece.
        const int v = pieceVariations(q, absQ, ta, f, k, piece.depth);
        if (v == 0) continue;
        const double fa = p(ta), fb = p(tb);
        const bool signChange = (fa < 0.0 && fb > 0.0) || (fa > 0.0 && fb < 0.0);
        if (v == 1 && fa != 0.0 && fb != 0.0) {
            // Step 3: exactly one root, a crossing (a count of 1 with no sign change is
            // rounding in the count). With an exact zero at an end (a split point, listed
            // already) the count says nothing about a sign change: split on.
            if (signChange) found[n++] = refineBracketed(p, ta, tb, relTol);
            continue;
        }
        // Step 4: at resolution, tolerance or noise level, decide the cluster; else halve.
        const double m = piece.a + std::ldexp(1.0, -piece.depth - 1);
        const double tm = toT(m);
        if (v < 0 || piece.depth >= tol::kMaxSubdivisionDepth || tm <= ta || tm >= tb ||
            bracketSmallEnough(ta, tb, relTol)) {
            undecided.add(ta, tb, p, found.data(), &n);
            continue;
        }
        listExactZero(p, dp, tm, found.data(), &n);
        stack[top++] = {m, piece.depth + 1};
        stack[top++] = {piece.a, piece.depth + 1};
    }
    return finishSubdivision(p, undecided, found.data(), n, tlo, thi, roots);
}

}  // namespace csg
