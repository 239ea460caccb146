// Notation: [a, b] is a piece of [tlo, thi] under test, m its midpoint and r its half-width
// (rounded up); P and D enclose p and p' there (Interval.h, centred form).
#include "primitives/solvers/IntervalSolver.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "primitives/solvers/Interval.h"
#include "primitives/solvers/Roots.h"

namespace csg {

int solveIntervalSubdivision(const Polynomial& input, double tlo, double thi, double* roots,
                             double relTol) {
    const Polynomial p = input.trimmed();
    if (p.degree() == 0 || !(tlo <= thi)) return 0;
    const Polynomial dp = p.derivative();

    struct Piece {
        double a, b;
        int depth;
    };
    std::array<Piece, tol::kMaxSubdivisionDepth + 2> stack;
    // Room for the roots, rounding's extra candidates and one flush of undecided pieces.
    std::array<double, 4 * Polynomial::kMaxDegree + 16> found;
    const int capacity = int(found.size()) - 18;
    UndecidedPieces undecided;
    int top = 0, n = 0;
    stack[top++] = {tlo, thi, 0};
    // A root exactly at tlo is on no piece's open interior; list it here (split points below).
    listExactZero(p, dp, tlo, found.data(), &n);
    while (top > 0 && n < capacity) {
        const Piece piece = stack[--top];
        const double m = 0.5 * piece.a + 0.5 * piece.b;
        const double r = up(std::max(m - piece.a, piece.b - m));
        const TaylorEnclosure e = enclose(p, m, r);
        // Step 1: exclusion: 0 is not in the enclosure of p, so no root here.
        if (!e.value.containsZero()) continue;
        const double fa = p(piece.a), fb = p(piece.b);
        // Step 2: monotone piece: at most one root, a crossing iff the ends' signs differ.
        if (!e.slope.containsZero()) {
            // An end whose value is rounding noise has no trustworthy sign (next to a
            // tangency, noise fakes a sign change): judge it with its neighbours.
            if ((fa != 0.0 && isNumericalZero(p, piece.a)) ||
                (fb != 0.0 && isNumericalZero(p, piece.b)))
                undecided.add(piece.a, piece.b, p, found.data(), &n);
            else if ((fa < 0.0 && fb > 0.0) || (fa > 0.0 && fb < 0.0))
                found[n++] = refineBracketed(p, piece.a, piece.b, relTol);
            else if (fb == 0.0 && piece.b == thi)  // split points are listed in step 4
                found[n++] = piece.b;
            continue;
        }
        // Step 3: too small to split, or p is rounding noise all over the piece (splitting
        // would only chase the noise, 2^26 pieces around a tangency): a cluster or nothing,
        // decided by the values of p.
        // The noise level: Horner's bound on |p| of the absolute coefficients at |m|, of the
        // size of the enclosure's own rounding terms (Interval.h).
        double absAtM = 0.0;
        for (int i = p.degree(); i >= 0; --i) absAtM = absAtM * std::abs(m) + std::abs(p[i]);
        const double noise = tol::gamma(4 * p.degree() + 8) * absAtM;
        const bool allNoise = e.value.magnitude() <= tol::kRootResidualFactor * noise;
        if (piece.depth >= tol::kMaxSubdivisionDepth || allNoise ||
            bracketSmallEnough(piece.a, piece.b, relTol)) {
            undecided.add(piece.a, piece.b, p, found.data(), &n);
            continue;
        }
        // Step 4: halve; a root exactly on the split point is listed now (twice when p' is
        // numerically zero there too: a tangency). Right half first, so roots come out ascending.
        listExactZero(p, dp, m, found.data(), &n);
        stack[top++] = {m, piece.b, piece.depth + 1};
        stack[top++] = {piece.a, m, piece.depth + 1};
    }
    return finishSubdivision(p, undecided, found.data(), n, tlo, thi, roots);
}

}  // namespace csg
