#include "primitives/solvers/Roots.h"

#include <algorithm>
#include <cmath>

namespace csg {

bool isNumericalZero(const Polynomial& p, double t) {
    double bound;
    const double v = p.eval(t, &bound);
    return std::abs(v) <= tol::kRootResidualFactor * bound;
}

bool hasProvableSign(const Polynomial& p, double t) {
    double bound;
    const double v = p.eval(t, &bound);
    return std::abs(v) > tol::kRootSeparationFactor * bound;
}

double polishRoot(const Polynomial& p, double x) {
    double v, dv;
    p.evalWithDerivative(x, v, dv);
    // Eight steps: quadratic convergence from a closed form's few correct digits needs three
    // or four; more would only walk along a flat (multiple-root) valley.
    for (int i = 0; i < 8 && v != 0.0 && dv != 0.0; ++i) {
        const double next = x - v / dv;
        double nv, ndv;
        p.evalWithDerivative(next, nv, ndv);
        if (!(std::abs(nv) < std::abs(v))) break;
        x = next, v = nv, dv = ndv;
    }
    return x;
}

bool bracketSmallEnough(double lo, double hi, double relTol) {
    const double mid = 0.5 * lo + 0.5 * hi;
    if (mid <= lo || mid >= hi) return true;
    return hi - lo <= relTol * std::max({1.0, std::abs(lo), std::abs(hi)});
}

double rootBound(const Polynomial& input) {
    const Polynomial p = input.trimmed();
    const int n = p.degree();
    if (n == 0 || p.leading() == 0.0) return kInfinity;
    // Step: max over i of |c[n-i] / c[n]|^(1/i), in logarithms so no ratio overflows; the
    // constant term's ratio is halved (Fujiwara's refinement).
    const double logLead = std::log2(std::abs(p.leading()));
    double best = -kInfinity;
    for (int i = 1; i <= n; ++i) {
        const double c = std::abs(p[n - i]) * (i == n ? 0.5 : 1.0);
        if (c == 0.0) continue;
        best = std::max(best, (std::log2(c) - logLead) / i);
    }
    if (best == -kInfinity) return 0.0;  // p = c t^n: the only root is 0
    return 2.0 * std::exp2(best) * (1.0 + tol::kRootBoundMargin);
}

int clusterRoots(const Polynomial& p, double a, double b, double* out) {
    const double fa = p(a), fb = p(b);
    const double m = 0.5 * a + 0.5 * b;
    if ((fa < 0.0 && fb > 0.0) || (fa > 0.0 && fb < 0.0)) {
        out[0] = refineBracketed(p, a, b);
        return 1;
    }
    // An exact zero at an end is a split point the caller has already listed.
    if (fa == 0.0 || fb == 0.0) return 0;
    // A tangency is where p' vanishes: look there (Newton on p' from the midpoint, kept in
    // the piece), since a piece that is noise by its coefficients' bound can be much wider
    // than the zone where Horner's tighter bound calls p zero.
    double x = m;
    if (!isNumericalZero(p, x) && p.degree() >= 2) {
        x = polishRoot(p.derivative(), m);
        if (!(x >= a && x <= b)) x = m;
    }
    if (isNumericalZero(p, x)) {
        out[0] = out[1] = x;
        return 2;
    }
    return 0;
}

int maxSignVariations(const double* c, const double* noise, int n) {
    // Dynamic programme over the sign of the last nonzero entry: best[s] is the most changes
    // of a prefix whose last nonzero entry has sign s (0: +, 1: -); -1 when none yet.
    int best[2] = {-1, -1};
    bool anySign = false;
    for (int i = 0; i <= n; ++i) {
        const bool unknown = std::abs(c[i]) <= noise[i];
        anySign = anySign || !unknown;
        int next[2] = {best[0], best[1]};  // an unknown entry may also be 0 (skipped)
        for (int s = 0; s < 2; ++s) {
            if (!unknown && (s == 1) != (c[i] < 0.0)) continue;
            next[s] = std::max({next[s], best[s], best[1 - s] >= 0 ? best[1 - s] + 1 : 0});
        }
        best[0] = next[0], best[1] = next[1];
    }
    return anySign ? std::max(best[0], best[1]) : -1;
}

double refineBracketed(const Polynomial& p, double lo, double hi, double relTol) {
    const bool risingAtLo = p(lo) < 0.0;
    double x = 0.5 * lo + 0.5 * hi;
    // 200 steps: bisection alone needs at most ~64 per binade crossed plus 53 digits; Newton
    // steps inside the bracket only shorten that.
    for (int i = 0; i < 200; ++i) {
        double v, dv;
        p.evalWithDerivative(x, v, dv);
        if (v == 0.0) return x;
        // Step 1: shrink the bracket to the side that still holds the sign change.
        if ((v < 0.0) == risingAtLo)
            lo = x;
        else
            hi = x;
        // Step 2: a Newton step if it stays strictly inside the bracket, else bisection.
        double next = dv != 0.0 ? x - v / dv : lo;
        if (!(next > lo && next < hi)) next = 0.5 * lo + 0.5 * hi;
        // Step 3: stop when the step no longer moves (converged, or the bracket is two
        // adjacent doubles).
        if (next == x || next <= lo || next >= hi) return x;
        if (relTol > 0.0 && bracketSmallEnough(lo, hi, relTol)) return next;
        x = next;
    }
    return x;
}

int finalizeRoots(const Polynomial& p, double* roots, int n, double tlo, double thi) {
    std::sort(roots, roots + n);
    int out = 0;
    for (int i = 0; i < n;) {
        // Step 1: gather the cluster starting at i: neighbours equal or with no resolvable
        // value of p between them.
        int j = i + 1;
        double sum = roots[i];
        while (j < n && (roots[j] == roots[j - 1] ||
                         !hasProvableSign(p, 0.5 * roots[j - 1] + 0.5 * roots[j]))) {
            sum += roots[j];
            ++j;
        }
        // Step 2: one crossing for an odd cluster, one tangency (listed twice) for an even one.
        const int m = j - i;
        double r = m == 1 ? roots[i] : sum / m;
        // A tangency is a simple root of p': polishing there recovers the digits that the
        // flat p hides (from ~sqrt(ulp) to the conditioning of p').
        if (m % 2 == 0 && p.degree() >= 2) {
            const double rd = polishRoot(p.derivative(), r);
            if (isNumericalZero(p, rd)) r = rd;
        }
        if (r >= tlo && r <= thi) {
            roots[out++] = r;
            if (m % 2 == 0) roots[out++] = r;
        }
        i = j;
    }
    return out;
}

int finishSubdivision(const Polynomial& p, UndecidedPieces& undecided, double* found, int n,
                      double tlo, double thi, double* roots) {
    n += undecided.resolve(p, found + n);
    n = finalizeRoots(p, found, n, tlo, thi);
    n = std::min(n, p.degree());
    std::copy(found, found + n, roots);
    return n;
}

}  // namespace csg
