// Helpers every root solver shares: the numerical-zero test, Newton polishing, a bracketed
// safeguarded Newton, and the final step that turns candidate roots into the solvers' contract.
//
// The contract (see Solve.h): real roots in [tlo, thi], ascending; a root where p changes sign
// (odd multiplicity, a crossing) is listed once, a root where it does not (even multiplicity,
// a tangency) is listed twice with equal values. Roots whose separation p cannot resolve in
// double precision (p at their midpoint has no provable sign) are one such root.
#pragma once

#include "primitives/base/Math.h"
#include "primitives/solvers/Polynomial.h"

namespace csg {

// True when |p(t)| is within tol::kRootResidualFactor of its rounding-error bound, i.e. the
// computed value has no trustworthy sign.
bool isNumericalZero(const Polynomial& p, double t);

// True when the computed p(t) exceeds tol::kRootSeparationFactor times its rounding-error
// bound, so its sign is that of the exact value for the stored coefficients: two candidate
// roots with such a value between them are two roots, however close (a decimal cluster).
bool hasProvableSign(const Polynomial& p, double t);

// Newton steps from x while they lower |p|; returns the best point seen. For a simple root
// this converges quadratically to within an ulp or two.
double polishRoot(const Polynomial& p, double x);

// True when the bracket [lo, hi] is as small as asked: two adjacent doubles (relTol = 0 asks for
// full precision), or a width at most relTol * max(1, |lo|, |hi|) (relTol > 0: the accuracy a
// caller trades for time; unit: t, relative to the root's size but never below 1).
bool bracketSmallEnough(double lo, double hi, double relTol);

// The root of p in [lo, hi], where p(lo) and p(hi) have opposite signs (lo < hi): Newton steps
// that leave the bracket are replaced by bisection, so it always converges, to within an ulp
// of the bracket (relTol = 0) or until bracketSmallEnough(relTol).
double refineBracketed(const Polynomial& p, double lo, double hi, double relTol = 0.0);

// Fujiwara's bound: every complex root z of p has |z| <= rootBound(p) (infinity when the
// leading coefficient is 0 or the bound overflows), widened by tol::kRootBoundMargin against
// the rounding of the bound itself. Solvers clamp their range to it, so no value of p is
// evaluated where t^n overflows (the cause of the misses on the quartic {1e53, 1e50, ...}).
double rootBound(const Polynomial& p);

// True when roots[i] of a solver's answer roots[0..n) is a tangency: by the contract above,
// listed twice, so equal to a neighbour.
inline bool isTangency(const double* roots, int n, int i) {
    return (i > 0 && roots[i - 1] == roots[i]) || (i + 1 < n && roots[i + 1] == roots[i]);
}

// A subdivision solver's check of a point on no piece's open interior (a range end or a split
// point): an exact zero of p there is listed once, twice when p' (dp) is numerically zero too
// (a tangency). Appends to out at *n.
inline void listExactZero(const Polynomial& p, const Polynomial& dp, double t, double* out,
                          int* n) {
    if (p(t) != 0.0) return;
    out[(*n)++] = t;
    if (isNumericalZero(dp, t)) out[(*n)++] = t;
}

// The subdivision solvers' answer for an interval [a, b] they may not or need not split
// further (at double resolution, at the asked tolerance, or where p is rounding noise
// throughout) and that may hold roots: one crossing, refined, when p changes sign over it; one
// tangency (listed twice, at the midpoint: finalizeRoots polishes it) when p is numerically
// zero at its midpoint; else none. An exact zero at an end counts as neither (the solvers list
// split points themselves). Appends to out and returns how many.
int clusterRoots(const Polynomial& p, double a, double b, double* out);

// The pieces a subdivision solver could not decide, collected in ascending order so that
// neighbours are judged together: a tangency's rounding-noise zone is usually cut into several
// pieces, whose ends have no trustworthy sign, while the ends of their union border pieces
// that were proven root-free. resolve() runs clusterRoots() on each maximal run of touching
// pieces.
class UndecidedPieces {
public:
    // Pieces must come in ascending order (a >= the previous piece's b).
    void add(double a, double b, const Polynomial& p, double* out, int* n) {
        // Touching pieces join, except across an exact zero of p: a split point that the
        // solver has listed already (the joined run would list it again).
        if (count_ > 0 && pieces_[count_ - 1].b == a && p(a) != 0.0) {
            pieces_[count_ - 1].b = b;
            return;
        }
        if (count_ == kCapacity) *n += resolve(p, out + *n);
        pieces_[count_++] = {a, b};
    }
    // Appends the runs' roots to out, returns how many, and empties the list.
    int resolve(const Polynomial& p, double* out) {
        int n = 0;
        for (int i = 0; i < count_; ++i) n += clusterRoots(p, pieces_[i].a, pieces_[i].b, out + n);
        count_ = 0;
        return n;
    }

private:
    static constexpr int kCapacity = 8;
    struct Piece {
        double a, b;
    };
    Piece pieces_[kCapacity];
    int count_ = 0;
};

// The most sign changes the sequence c[0..n] can have when each c[i] with |c[i]| <= noise[i]
// may take either sign (or be 0): an upper bound on the Descartes count that rounding cannot
// break. Returns -1 when every entry is within its noise (the sequence has no known sign).
int maxSignVariations(const double* c, const double* noise, int n);

// Sorts the n candidates in roots (crossings once, tangencies twice), merges clusters that p
// cannot resolve (neighbours without a provable sign of p at their midpoint; a cluster of m
// candidates becomes one root listed once when m is odd, twice when even), keeps those in [tlo,
// thi], and returns their count.
int finalizeRoots(const Polynomial& p, double* roots, int n, double tlo, double thi);

// The subdivision solvers' common last step: resolves the undecided pieces into the n
// candidates in found, finalizes them over [tlo, thi], keeps at most p's degree and copies
// them to roots. Returns their count.
int finishSubdivision(const Polynomial& p, UndecidedPieces& undecided, double* found, int n,
                      double tlo, double thi, double* roots);

}  // namespace csg
