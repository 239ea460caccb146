#include "primitives/patch/PatchAlgebra.h"

#include <algorithm>

#include "primitives/base/Tolerances.h"
#include "primitives/patch/RayPlanes.h"
#include "primitives/solvers/Solve.h"

namespace csg {

namespace {

constexpr int kWide = Bivariate::kMaxDegreeU + 1;
using Coeffs = std::array<double, kWide>;

double evalWide(const WidePolynomial& p, double x) {
    double y = p.c[p.degree];
    for (int i = p.degree - 1; i >= 0; --i) y = std::fma(y, x, p.c[i]);
    return y;
}

int signChanges(const Coeffs& b, int n) {
    int changes = 0;
    double last = 0.0;
    for (int i = 0; i <= n; ++i) {
        if (b[i] == 0.0) continue;
        if (last != 0.0 && (b[i] < 0.0) != (last < 0.0)) ++changes;
        last = b[i];
    }
    return changes;
}

// De Casteljau at 1/2: c keeps the left half, right receives the right half.
void split(Coeffs& c, int n, Coeffs& right) {
    right[n] = c[n];
    for (int r = 1; r <= n; ++r) {
        for (int i = n; i >= r; --i) c[i] = 0.5 * c[i - 1] + 0.5 * c[i];
        right[n - r] = c[n];
    }
}

// The root of p in [a, b], where p(a) and p(b) have opposite signs (or one is 0): bisection
// to double resolution, on the monomial form (its values, not the subdivided coefficients).
double bisect(const WidePolynomial& p, double a, double b) {
    double fa = evalWide(p, a);
    if (fa == 0.0) return a;
    for (int k = 0; k < 200; ++k) {
        const double m = 0.5 * (a + b);
        if (m <= a || m >= b) break;
        const double fm = evalWide(p, m);
        if (fm == 0.0) return m;
        if ((fm < 0.0) == (fa < 0.0)) {
            a = m;
            fa = fm;
        } else {
            b = m;
        }
    }
    return 0.5 * (a + b);
}

// Roots of p on [a, b] whose Bernstein coefficients are c (degree n), by subdivision.
void subdivide(const WidePolynomial& p, Coeffs c, int n, double a, double b, int depth,
               double* roots, int& count) {
    const int changes = signChanges(c, n);
    if (changes == 0) return;
    if (changes == 1 && (c[0] == 0.0 || c[n] == 0.0 || (c[0] < 0.0) != (c[n] < 0.0))) {
        roots[count++] = bisect(p, a, b);
        return;
    }
    if (depth >= tol::kMaxSubdivisionDepth || b - a <= tol::kUlp * std::max(1.0, std::abs(a))) {
        roots[count++] = 0.5 * (a + b);  // a cluster below resolution: one root
        return;
    }
    Coeffs right;
    split(c, n, right);
    const double m = 0.5 * (a + b);
    subdivide(p, c, n, a, m, depth + 1, roots, count);
    if (count < n) subdivide(p, right, n, m, b, depth + 1, roots, count);
}

}  // namespace

PlaneEquations planeEquations(const BezierPatch& patch, const Vec3& o, const Vec3& d) {
    const RayPlanes planes(o, d);  // the frame every patch method uses
    return {Bivariate::planeDistance(patch, planes.n1, o),
            Bivariate::planeDistance(patch, planes.n2, o)};
}

int unitParameterRoots(const WidePolynomial& input, double* roots) {
    WidePolynomial p = input;
    while (p.degree > 0 && p.c[p.degree] == 0.0) --p.degree;
    if (p.degree == 0) return 0;
    const double lo = -tol::kPatchParamSlack, hi = 1.0 + tol::kPatchParamSlack;
    // Degree <= 16 by solve(), as measured on patches before Polynomial held degree 20 (issue 23
    // raised it for the solvers' degree sweep); above, Bernstein subdivision as before.
    if (p.degree <= 16) {
        Polynomial q = Polynomial::ofDegree(p.degree);
        for (int i = 0; i <= p.degree; ++i) q[i] = p.c[i];
        return solve(q, lo, hi, roots);
    }
    // Bernstein coefficients on [lo, hi]: q(x) = p(lo + w x) by Taylor shift and scaling, then
    // b[k] = sum_{i <= k} C(k, i) / C(n, i) q[i].
    const int n = p.degree;
    const double w = hi - lo;
    Coeffs q = p.c;
    for (int k = 0; k < n; ++k)
        for (int i = n - 1; i >= k; --i) q[i] = std::fma(q[i + 1], lo, q[i]);
    double f = 1.0;
    for (int i = 0; i <= n; ++i, f *= w) q[i] *= f;
    Coeffs b{};
    for (int k = 0; k <= n; ++k) {
        double s = 0.0, ratio = 1.0;
        for (int i = 0; i <= k; ++i) {
            s = std::fma(ratio, q[i], s);
            ratio *= double(k - i) / double(n - i);
        }
        b[k] = s;
    }
    int count = 0;
    subdivide(p, b, n, lo, hi, 0, roots, count);
    return count;
}

bool isCommonRoot(const PlaneEquations& planes, double u, double v) {
    const double lo = -tol::kPatchParamSlack, hi = 1.0 + tol::kPatchParamSlack;
    if (!(u >= lo && u <= hi && v >= lo && v <= hi)) return false;
    return std::abs(planes.f1(u, v)) <= tol::kPatchResidualRel * planes.f1.termMagnitude(u, v) &&
           std::abs(planes.f2(u, v)) <= tol::kPatchResidualRel * planes.f2.termMagnitude(u, v);
}

int planeRootsInV(const PlaneEquations& planes, double u, double smallRel, double* vs) {
    int count = 0;
    for (const Bivariate* f : {&planes.f1, &planes.f2}) {
        const auto c = f->atU(u);
        double size = 0.0;
        for (double x : c) size = std::max(size, std::abs(x));
        int degree = Bivariate::kMaxDegreeV;
        while (degree > 0 && std::abs(c[degree]) <= smallRel * size) --degree;
        if (degree == 0) continue;
        Polynomial inV = Polynomial::ofDegree(degree);
        for (int j = 0; j <= degree; ++j) inV[j] = c[j];
        count += solve(inV, -tol::kPatchParamSlack, 1.0 + tol::kPatchParamSlack, vs + count);
    }
    return count;
}

bool hasCloseNeighbour(const double* roots, int count, int i) {
    return (i > 0 && roots[i] - roots[i - 1] <= tol::kPatchRootDriftParam) ||
           (i + 1 < count && roots[i + 1] - roots[i] <= tol::kPatchRootDriftParam);
}

void acceptMethodRoot(const BezierPatch& patch, const PlaneEquations& planes, const Vec3& o,
                      const Vec3& d, double u, double v, const AlgebraOptions& options,
                      PatchCrossings& out, int& n) {
    if (!isCommonRoot(planes, u, v)) return;
    if (options.polish) polishRoot(planes, u, v);
    appendCrossing(patch, o, d, u, v, out, n);
}

void crossingsFromPlaneRoots(const BezierPatch& patch, const PlaneEquations& planes, const Vec3& o,
                             const Vec3& d, double u, const AlgebraOptions& options,
                             PatchCrossings& out, int& n) {
    double vs[2 * Bivariate::kMaxDegreeV];
    const int count = planeRootsInV(planes, u, options.smallRel, vs);
    for (int k = 0; k < count && n < kMaxPatchCrossings; ++k) {
        double pu = u, pv = vs[k];
        if (options.polish) {
            polishRoot(planes, pu, pv);
            if (std::abs(pu - u) > tol::kPatchRootDriftParam) continue;
        }
        if (isCommonRoot(planes, pu, pv)) appendCrossing(patch, o, d, pu, pv, out, n);
    }
}

void polishRoot(const PlaneEquations& planes, double& u, double& v) {
    constexpr int kPolishSteps = 4;  // quadratic convergence: 4 steps take 1e-4 to rounding
    double residual = std::max(std::abs(planes.f1(u, v)), std::abs(planes.f2(u, v)));
    for (int step = 0; step < kPolishSteps && residual > 0.0; ++step) {
        const Vec2 g1 = planes.f1.gradient(u, v), g2 = planes.f2.gradient(u, v);
        const double det = g1.x * g2.y - g1.y * g2.x;
        if (det == 0.0) return;
        const double f1 = planes.f1(u, v), f2 = planes.f2(u, v);
        const double nu = u - (f1 * g2.y - f2 * g1.y) / det;
        const double nv = v - (g1.x * f2 - g2.x * f1) / det;
        const double next = std::max(std::abs(planes.f1(nu, nv)), std::abs(planes.f2(nu, nv)));
        const double lo = -tol::kPatchParamSlack, hi = 1.0 + tol::kPatchParamSlack;
        if (!(next < residual) || !(nu >= lo && nu <= hi && nv >= lo && nv <= hi)) return;
        u = nu;
        v = nv;
        residual = next;
    }
}

void appendCrossing(const BezierPatch& patch, const Vec3& o, const Vec3& d, double u, double v,
                    PatchCrossings& out, int& n) {
    u = std::clamp(u, 0.0, 1.0);
    v = std::clamp(v, 0.0, 1.0);
    const double t = glm::dot(d, patch.eval(u, v) - o) / glm::dot(d, d);
    out[n++] = {t, u, v};
}

int finishCrossings(PatchCrossings& out, int n) {
    std::sort(out.begin(), out.begin() + n,
              [](const PatchCrossing& a, const PatchCrossing& b) { return a.t < b.t; });
    int kept = 0;
    for (int i = 0; i < n; ++i) {
        bool seen = false;
        for (int k = 0; k < kept && !seen; ++k)
            seen = std::abs(out[k].u - out[i].u) <= tol::kPatchSamePointParam &&
                   std::abs(out[k].v - out[i].v) <= tol::kPatchSamePointParam;
        if (!seen) out[kept++] = out[i];
    }
    return kept;
}

}  // namespace csg
