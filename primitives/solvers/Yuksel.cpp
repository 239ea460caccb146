// Notation: x[0] = tlo < x[1] < ... < x[k] < x[k+1] = thi are the ends and the critical
// points (roots of p') in between; p is monotone on each [x[i], x[i+1]].
#include "primitives/solvers/Yuksel.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "primitives/solvers/Cubic.h"
#include "primitives/solvers/Roots.h"

namespace csg {

namespace {

constexpr int kMaxRoots = Polynomial::kMaxDegree;

// Roots of p in [lo, hi] as candidates (crossings once, tangencies twice), not yet merged.
int candidates(const Polynomial& p, double lo, double hi, double* out, double relTol) {
    // Step 1: degree <= 2 directly.
    if (p.degree() <= 0) return 0;
    if (p.degree() == 1) {
        const double r = -p[0] / p[1];
        if (!(r >= lo && r <= hi)) return 0;
        out[0] = r;
        return 1;
    }
    if (p.degree() == 2) {
        double r[2];
        const int m = appendQuadraticFactorRoots(p, p[2], p[1], p[0], r);
        int n = 0;
        for (int i = 0; i < m; ++i)
            if (r[i] >= lo && r[i] <= hi) out[n++] = r[i];
        return n;
    }

    // Step 2: the critical points inside (lo, hi), distinct and ascending.
    std::array<double, kMaxRoots + 2> x;
    int k = 0;
    x[k++] = lo;
    {
        const Polynomial dp = p.derivative();
        std::array<double, kMaxRoots> crit;
        const int nc = candidates(dp, lo, hi, crit.data(), relTol);
        std::sort(crit.begin(), crit.begin() + nc);
        for (int i = 0; i < nc; ++i)
            if (crit[i] > x[k - 1] && crit[i] < hi) x[k++] = crit[i];
    }
    x[k++] = hi;

    // Step 3: values there; at a critical point, a value with no trustworthy sign is 0.
    std::array<double, kMaxRoots + 2> v;
    for (int i = 0; i < k; ++i) {
        double bound;
        v[i] = p.eval(x[i], &bound);
        const bool interior = i > 0 && i < k - 1;
        if (interior && std::abs(v[i]) <= tol::kRootResidualFactor * bound) v[i] = 0.0;
    }

    // Step 4: a sign change between nonzero values brackets one crossing; a zero at a
    // critical point is a root, a tangency when p has the same sign on both sides of it.
    int n = 0;
    for (int i = 0; i < k && n < p.degree(); ++i) {
        if (v[i] == 0.0) {
            const bool interior = i > 0 && i < k - 1;
            int l = i - 1, r = i + 1;
            while (l >= 0 && v[l] == 0.0) --l;
            while (r < k && v[r] == 0.0) ++r;
            const bool touch = interior && l >= 0 && r < k && (v[l] < 0.0) == (v[r] < 0.0);
            out[n++] = x[i];
            if (touch && n < p.degree()) out[n++] = x[i];
        }
        if (i + 1 < k && v[i] != 0.0 && v[i + 1] != 0.0 && (v[i] < 0.0) != (v[i + 1] < 0.0))
            out[n++] = refineBracketed(p, x[i], x[i + 1], relTol);
    }
    return n;
}

}  // namespace

int solveYuksel(const Polynomial& input, double tlo, double thi, double* roots, double relTol) {
    const Polynomial p = input.trimmed();
    if (p.degree() == 0 || !(tlo <= thi)) return 0;
    std::array<double, kMaxRoots> found;
    const int n = candidates(p, tlo, thi, found.data(), relTol);
    const int m = finalizeRoots(p, found.data(), n, tlo, thi);
    std::copy(found.begin(), found.begin() + m, roots);
    return m;
}

}  // namespace csg
