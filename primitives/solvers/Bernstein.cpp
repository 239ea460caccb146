// Notation: a piece is [a, b] in t with its Bernstein coefficients c[0..n]; de Casteljau at
// 1/2 gives the coefficients of both halves.
#include "primitives/solvers/Bernstein.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "primitives/solvers/Roots.h"

namespace csg {

namespace {

constexpr int kN = Polynomial::kMaxDegree + 1;
using Coeffs = std::array<double, kN>;

// De Casteljau at 1/2: c becomes the left half's coefficients, right the right half's. In
// place, level r holds its values in w[r..n]: w[r] is the left half's r-th coefficient and
// w[n] the right half's (n - r)-th.
void split(Coeffs& c, int n, Coeffs& right) {
    right[n] = c[n];
    for (int r = 1; r <= n; ++r) {
        for (int i = n; i >= r; --i) c[i] = 0.5 * c[i - 1] + 0.5 * c[i];
        right[n - r] = c[n];
    }
}

}  // namespace

void toBernstein(const Polynomial& p, double tlo, double thi, double* b, double* noise) {
    const int n = p.degree();
    // Step 1: monomial coefficients on the unit interval, q(x) = p(tlo + w x), and the same
    // steps on |p| at |tlo| (no cancellation) for the error bound.
    const double w = thi - tlo;
    const Polynomial q = p.shifted(tlo).argumentScaled(w);
    Polynomial a = Polynomial::ofDegree(n);
    for (int i = 0; i <= n; ++i) a[i] = std::abs(p[i]);
    a = a.shifted(std::abs(tlo)).argumentScaled(w);
    // Step 2: b[k] = sum_{i <= k} C(k, i) / C(n, i) q[i], with the ratio updated as k grows.
    for (int k = 0; k <= n; ++k) {
        double s = 0.0, e = 0.0, ratio = 1.0;  // ratio = C(k, i) / C(n, i), starting at i = 0
        for (int i = 0; i <= k; ++i) {
            s = std::fma(ratio, q[i], s);
            e = std::fma(ratio, a[i] + std::abs(q[i]), e);
            ratio *= double(k - i) / double(n - i);
        }
        b[k] = s;
        if (noise) noise[k] = tol::gamma(3 * n + 4) * e;
    }
}

int solveBernstein(const Polynomial& input, double tlo, double thi, double* roots, double relTol) {
    const Polynomial p = input.trimmed();
    if (p.degree() == 0 || !(tlo <= thi)) return 0;
    const int n = p.degree();
    const Polynomial dp = p.derivative();

    // fresh: c was converted from p on [a, b] itself, not inherited through de Casteljau
    // from a wider piece, whose conversion noise may hide this piece's small values.
    struct Piece {
        double a, b;
        int depth;
        bool fresh;
        Coeffs c, noise;
    };
    std::array<Piece, tol::kMaxSubdivisionDepth + 2> stack;
    // Room for the roots, rounding's extra candidates and one flush of undecided pieces.
    std::array<double, 4 * Polynomial::kMaxDegree + 16> found;
    const int capacity = int(found.size()) - 18;
    UndecidedPieces undecided;
    int top = 0, count = 0;
    Piece& first = stack[top++];
    first.a = tlo, first.b = thi, first.depth = 0, first.fresh = true;
    toBernstein(p, tlo, thi, first.c.data(), first.noise.data());
    for (double end : {tlo, thi}) listExactZero(p, dp, end, found.data(), &count);
    while (top > 0 && count < capacity) {
        Piece piece = stack[--top];
        // Step 1: the variation count bounds the roots in the open piece (counting a
        // coefficient lost in rounding noise as either sign, so no root is dropped).
        int v = maxSignVariations(piece.c.data(), piece.noise.data(), n);
        bool ambiguous = v < 0;
        for (int i = 0; i <= n; ++i)
            ambiguous = ambiguous || std::abs(piece.c[i]) <= piece.noise[i];
        if (ambiguous && !piece.fresh) {
            toBernstein(p, piece.a, piece.b, piece.c.data(), piece.noise.data());
            piece.fresh = true;
            v = maxSignVariations(piece.c.data(), piece.noise.data(), n);
        }
        if (v == 0) continue;
        const double fa = p(piece.a), fb = p(piece.b);
        const bool signChange = (fa < 0.0 && fb > 0.0) || (fa > 0.0 && fb < 0.0);
        // Step 2: exactly one root, a crossing. With an exact zero at an end (a split point,
        // listed already) the count says nothing about the sign change: split on.
        if (v == 1 && fa != 0.0 && fb != 0.0) {
            if (signChange) found[count++] = refineBracketed(p, piece.a, piece.b, relTol);
            continue;
        }
        // Step 3: at resolution, tolerance or noise level, decide the cluster; else split.
        const double m = 0.5 * piece.a + 0.5 * piece.b;
        if (v < 0 || piece.depth >= tol::kMaxSubdivisionDepth || m <= piece.a || m >= piece.b ||
            bracketSmallEnough(piece.a, piece.b, relTol)) {
            undecided.add(piece.a, piece.b, p, found.data(), &count);
            continue;
        }
        listExactZero(p, dp, m, found.data(), &count);
        Piece& right = stack[top++];
        right.a = m, right.b = piece.b, right.depth = piece.depth + 1, right.fresh = false;
        right.noise = piece.noise;
        split(piece.c, n, right.c);
        stack[top++] = {piece.a, m, piece.depth + 1, false, piece.c, piece.noise};
    }
    return finishSubdivision(p, undecided, found.data(), count, tlo, thi, roots);
}

}  // namespace csg
