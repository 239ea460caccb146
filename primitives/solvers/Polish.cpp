// Notation: x is the root being polished (double-double), P, P', P''/2 the polynomial's values
// there (PolynomialDD::at). Every step is formed in double from those double-double values:
// the residual P carries the accuracy, and a step whose relative error is ~1e-16 still
// converges to double-double precision (the error after a step is ~1e-16 times the step).
#include "primitives/solvers/Polish.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>

#include "primitives/base/NamedChoice.h"
#include "primitives/base/Tolerances.h"
#include "primitives/solvers/Roots.h"

namespace csg {

const char* polisherName(Polisher polisher) {
    switch (polisher) {
        case Polisher::Auto:
            return "auto";
        case Polisher::None:
            return "none";
        case Polisher::Newton:
            return "newton";
        case Polisher::Laguerre:
            return "laguerre";
        case Polisher::Bairstow:
            return "bairstow";
    }
    return "?";
}

bool polisherFromName(const char* name, Polisher* polisher) {
    return choiceFromName(name, kAllPolishers, polisherName, polisher);
}

double ulpOf(double x) {
    // 2^(e - 52) for |x| in [2^e, 2^(e + 1)): x's exponent bits alone, scaled (libm's nextafter
    // showed in a torus render's instructions). 0 for 0 and subnormals, inf for inf and NaN.
    const uint64_t exponent = std::bit_cast<uint64_t>(x) & 0x7ff0000000000000ull;
    return std::bit_cast<double>(exponent) * 0x1p-52;
}

void rootBracket(const double* roots, int n, int i, double tlo, double thi, double* lo,
                 double* hi) {
    *lo = i > 0 ? 0.5 * roots[i - 1] + 0.5 * roots[i] : tlo;
    *hi = i + 1 < n ? 0.5 * roots[i] + 0.5 * roots[i + 1] : thi;
}

double rootErrorEstimate(const Polynomial& p, double x) {
    double bound, v, dv;
    p.eval(x, &bound);
    p.evalWithDerivative(x, v, dv);
    return dv != 0.0 ? bound / std::abs(dv) : kInfinity;
}

namespace {

bool converged(double step, const DoubleDouble& x) {
    return std::abs(step) <= tol::kPolishStepRel * std::abs(x.hi);
}

// p in double-double and p' in double at x (what a Newton step needs), one Horner pass.
struct Slope {
    DoubleDouble p;
    double dp;
};
Slope valueAndSlope(const PolynomialDD& p, const DoubleDouble& x) {
    Slope v{p.c[p.degree], 0.0};
    for (int i = p.degree - 1; i >= 0; --i) {
        v.dp = v.dp * x.hi + v.p.hi;
        v.p = v.p * x + p.c[i];
    }
    return v;
}

// Newton: x -= P / P', each step taken only when it lowers |P| (so no other safeguard on the
// residual is needed) or when it is already below kPolishStepRel (then it is not evaluated).
DoubleDouble newton(const PolynomialDD& p, DoubleDouble x) {
    Slope v = valueAndSlope(p, x);
    for (int k = 0; k < tol::kPolishMaxSteps; ++k) {
        if (v.p.hi == 0.0 || v.dp == 0.0) break;
        const double step = v.p.value() / v.dp;
        const DoubleDouble next = x - step;
        if (converged(step, next)) return next;
        const Slope nv = valueAndSlope(p, next);
        if (!(std::abs(nv.p.value()) < std::abs(v.p.value()))) break;
        x = next, v = nv;
    }
    return x;
}

// Laguerre: with G = P'/P and H = G^2 - P''/P, x -= n / (G +- sqrt((n - 1)(n H - G^2))), the
// sign that makes the denominator larger. Cubic near a simple root; the square root's argument
// is clamped at 0 (a complex step would leave the real line).
DoubleDouble laguerre(const PolynomialDD& p, DoubleDouble x) {
    const double n = p.degree;
    for (int k = 0; k < tol::kPolishMaxSteps; ++k) {
        const PolynomialDD::Values v = p.at(x);
        if (v.p.hi == 0.0) break;
        const double P = v.p.value();
        const double G = v.dp.value() / P;
        const double H = G * G - 2.0 * v.halfDdp.value() / P;
        const double root = std::sqrt(std::max(0.0, (n - 1.0) * (n * H - G * G)));
        const double denom = G >= 0.0 ? G + root : G - root;
        if (denom == 0.0 || !std::isfinite(denom)) break;
        const double step = n / denom;
        x = x - step;
        if (converged(step, x)) break;
    }
    return x;
}

// Bairstow: the quadratic factor x^2 + r x + s of p through the root and a partner, by Newton
// on the remainder of p / (x^2 + r x + s) (formed in double-double), then the factor's root
// nearest the start. With b_k = a_k - r b_{k+1} - s b_{k+2} (remainder b1 (x + r) + b0) and c_k
// the same recurrence on b, d b_k / dr = -c_{k+1} and d b_k / ds = -c_{k+2}.
DoubleDouble bairstow(const PolynomialDD& p, double x0, double partner) {
    const int n = p.degree;
    if (n < 2) return newton(p, x0);
    DoubleDouble r = -(DoubleDouble(x0) + DoubleDouble(partner));
    DoubleDouble s = DoubleDouble(twoProduct(x0, partner).hi, twoProduct(x0, partner).lo);
    for (int k = 0; k < tol::kPolishMaxSteps; ++k) {
        // Step 1: the remainder, in double-double; the Jacobian's c, in double.
        DoubleDouble bNext1 = 0.0, bNext2 = 0.0;  // b_{i+1}, b_{i+2}
        double c[Polynomial::kMaxDegree + 3] = {};
        double cNext1 = 0.0, cNext2 = 0.0;
        DoubleDouble rem1 = 0.0;  // b_1
        for (int i = n; i >= 0; --i) {
            const DoubleDouble b = p.c[i] - r * bNext1 - s * bNext2;
            c[i] = b.value() - r.value() * cNext1 - s.value() * cNext2;
            cNext2 = cNext1, cNext1 = c[i];
            bNext2 = bNext1, bNext1 = b;
            if (i == 1) rem1 = b;
        }
        const DoubleDouble rem0 = bNext1;  // b_0
        if (rem1.hi == 0.0 && rem0.hi == 0.0) break;
        // Step 2: the Newton step on (b_1, b_0): [c2 c3; c1 c2] [dr ds] = [b1 b0].
        const double c1 = c[1], c2 = c[2], c3 = n >= 3 ? c[3] : 0.0;
        const double det = c2 * c2 - c1 * c3;
        if (det == 0.0 || !std::isfinite(det)) break;
        const double dr = (rem1.value() * c2 - rem0.value() * c3) / det;
        const double ds = (rem0.value() * c2 - rem1.value() * c1) / det;
        if (!std::isfinite(dr) || !std::isfinite(ds)) break;
        r = r + dr, s = s + ds;
        if (converged(dr, r) && converged(ds, s)) break;
    }
    // Step 3: the factor's real roots (stable form), the one nearest the start.
    const DoubleDouble disc = r * r - DoubleDouble(4.0) * s;
    if (disc.hi < 0.0) return x0;  // the factor went complex: the real root was lost
    const DoubleDouble sq = ddSqrt(disc);
    const DoubleDouble q = (r.hi >= 0.0 ? -(r + sq) : sq - r) * DoubleDouble(0.5);
    if (q.hi == 0.0) return x0;
    const DoubleDouble a = q, b = s / q;
    return std::abs((a - x0).value()) <= std::abs((b - x0).value()) ? a : b;
}

// Bairstow's partner for roots[i]: its nearest neighbour in the list, else the other root of
// p's Taylor quadratic at it (x - 2 P' / P''), else none (NaN).
double bairstowPartner(const PolynomialDD& p, const double* roots, int n, int i) {
    double best = std::numeric_limits<double>::quiet_NaN();
    for (int j = 0; j < n; ++j)
        if (roots[j] != roots[i] && !(std::abs(roots[j] - roots[i]) >= std::abs(best - roots[i])))
            best = roots[j];
    if (std::isfinite(best)) return best;
    const PolynomialDD::Values v = p.at(roots[i]);
    const double hddp = v.halfDdp.value();
    if (hddp == 0.0) return best;
    return roots[i] - v.dp.value() / hddp;
}

}  // namespace

DoubleDouble polishRootWith(Polisher method, const PolynomialDD& p, const double* roots, int n,
                            int i, double lo, double hi) {
    const double x0 = roots[i];
    if (method == Polisher::None || p.degree < 1) return x0;
    DoubleDouble x = x0;
    switch (method) {
        case Polisher::Auto:
        case Polisher::Newton:
            x = newton(p, x0);
            break;
        case Polisher::Laguerre:
            x = laguerre(p, x0);
            break;
        case Polisher::Bairstow: {
            const double partner = bairstowPartner(p, roots, n, i);
            x = std::isfinite(partner) ? bairstow(p, x0, partner) : newton(p, x0);
            break;
        }
        case Polisher::None:
            break;
    }
    // Safeguard: in the bracket, and no larger a residual than the start's (Newton keeps that
    // itself).
    if (!(x.hi > lo && x.hi < hi) || !std::isfinite(x.hi)) return x0;
    if (method != Polisher::Auto && method != Polisher::Newton &&
        ddAbs(p(x)).value() > std::abs(p(DoubleDouble(x0)).value()))
        return x0;
    return x;
}

int polishRoots(Polisher polisher, const Polynomial& p, double* roots, int n, double tlo,
                double thi) {
    if (polisher == Polisher::None || n == 0) return 0;
    const PolynomialDD dd(p);
    double start[Polynomial::kMaxDegree];
    std::copy(roots, roots + n, start);
    int polished = 0;
    for (int i = 0; i < n; ++i) {
        if (isTangency(start, n, i)) continue;
        if (polisher == Polisher::Auto &&
            !(rootErrorEstimate(p, start[i]) > tol::kPolishConditionUlps * ulpOf(start[i])))
            continue;
        double lo, hi;
        rootBracket(start, n, i, tlo, thi, &lo, &hi);
        roots[i] = polishRootWith(polisher, dd, start, n, i, lo, hi).value();
        ++polished;
    }
    return polished;
}

}  // namespace csg
