#include "primitives/solvers/Roots.h"

#include <algorithm>
#include <cmath>

namespace csg {

bool isNumericalZero(const Polynomial& p, double t) {
    double bound;
    const double v = p.eval(t, &bound);
    return std::abs(v) <= tol::kRootResidualFactor * bound;
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

double refineBracketed(const Polynomial& p, double lo, double hi) {
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
                         isNumericalZero(p, 0.5 * roots[j - 1] + 0.5 * roots[j]))) {
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

}  // namespace csg
