// Notation: s[0] = p, s[1] = p', s[k+1] = -(s[k-1] mod s[k]); V(x) is the number of sign
// changes in s[0](x), s[1](x), ... (zeros skipped). For a < b, V(a) - V(b) is the number of
// distinct real roots in (a, b].
#include "primitives/solvers/Sturm.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "primitives/solvers/Roots.h"

namespace csg {

namespace {

struct SturmSequence {
    std::array<Polynomial, Polynomial::kMaxDegree + 1> s;
    int count = 0;

    // Sign changes along the sequence at x.
    int variations(double x) const {
        int changes = 0;
        double last = 0.0;
        for (int i = 0; i < count; ++i) {
            const double v = s[i](x);
            if (v == 0.0) continue;
            if (last != 0.0 && (v < 0.0) != (last < 0.0)) ++changes;
            last = v;
        }
        return changes;
    }
};

// Scales p so its largest coefficient is 1 in magnitude (by a power of two: exact, and the
// signs are kept), so 16 divisions in a row neither overflow nor underflow.
Polynomial normalized(const Polynomial& p) {
    const double m = p.maxMagnitude();
    return m > 0.0 ? p.scaled(std::ldexp(1.0, -std::ilogb(m))) : p;
}

// The remainder of a divided by b (b.degree() <= a.degree(), b's leading coefficient nonzero),
// with leading coefficients that are rounding noise (below a few ulps of a's size) dropped.
Polynomial remainder(const Polynomial& a, const Polynomial& b) {
    Polynomial r = a;
    const int db = b.degree();
    for (int k = a.degree(); k >= db; --k) {
        const double q = r[k] / b.leading();
        for (int j = 0; j <= db; ++j) r[k - db + j] -= q * b[j];
        r[k] = 0.0;
    }
    Polynomial out = Polynomial::ofDegree(db > 0 ? db - 1 : 0);
    const double noise = 4.0 * tol::gamma(2 * a.degree()) * a.maxMagnitude();
    for (int i = 0; i <= out.degree(); ++i) out[i] = std::abs(r[i]) <= noise ? 0.0 : r[i];
    return out.trimmed();
}

SturmSequence buildSequence(const Polynomial& p) {
    SturmSequence seq;
    seq.s[0] = normalized(p);
    seq.s[1] = normalized(p.derivative());
    seq.count = 2;
    while (seq.s[seq.count - 1].degree() > 0) {
        const Polynomial r = remainder(seq.s[seq.count - 2], seq.s[seq.count - 1]);
        // A zero remainder ends the sequence early: p has multiple roots (the last element
        // is their gcd), and the counts are still of distinct roots.
        if (r.degree() == 0 && r[0] == 0.0) break;
        seq.s[seq.count++] = normalized(r.scaled(-1.0));
    }
    return seq;
}

double bisect(const Polynomial& p, double a, double b, double relTol) {
    const bool negAtA = p(a) < 0.0;
    while (!bracketSmallEnough(a, b, relTol)) {
        const double m = 0.5 * a + 0.5 * b;
        const double v = p(m);
        if (v == 0.0) return m;
        ((v < 0.0) == negAtA ? a : b) = m;
    }
    return 0.5 * a + 0.5 * b;
}

// Illinois: regula falsi that halves the stale end's value when the same end is kept twice;
// a bisection step whenever the bracket failed to halve over the last two steps.
double illinois(const Polynomial& p, double a, double b, double relTol) {
    double fa = p(a), fb = p(b);
    int side = 0;
    double widthBefore = b - a, widthLast = b - a;
    for (int i = 0; i < 200 && !bracketSmallEnough(a, b, relTol); ++i) {
        double x = (a * fb - b * fa) / (fb - fa);
        if (b - a > 0.5 * widthBefore || !(x > a && x < b)) x = 0.5 * a + 0.5 * b;
        widthBefore = widthLast, widthLast = b - a;
        const double fx = p(x);
        if (fx == 0.0) return x;
        if ((fx < 0.0) == (fb < 0.0)) {
            b = x, fb = fx;
            if (side == -1) fa *= 0.5;
            side = -1;
        } else {
            a = x, fa = fx;
            if (side == +1) fb *= 0.5;
            side = +1;
        }
    }
    return std::abs(fa) < std::abs(fb) ? a : b;
}

struct Interval {
    double a, b;
    int va, vb;
};

}  // namespace

int solveSturm(const Polynomial& input, double tlo, double thi, double* roots, SturmRefine refine,
               double relTol) {
    const Polynomial p = input.trimmed();
    if (p.degree() == 0 || !(tlo <= thi)) return 0;
    const SturmSequence seq = buildSequence(p);

    // Step 1: isolate by bisection on the counts, with an explicit stack (at most one pending
    // interval per bisection level and root).
    std::array<Interval, 64 * Polynomial::kMaxDegree> stack;
    // Rounded counts may claim more roots than the degree allows; collect them all before
    // finalizeRoots merges what p cannot tell apart.
    std::array<double, 2 * Polynomial::kMaxDegree + 2> found;
    const int capacity = int(found.size()) - 1;
    int depth = 0, n = 0;
    stack[depth++] = {tlo, thi, seq.variations(tlo), seq.variations(thi)};
    // A root exactly at tlo is not counted in (tlo, thi]; look for it directly.
    const Polynomial dp = p.derivative();
    listExactZero(p, dp, tlo, found.data(), &n);
    while (depth > 0 && n < capacity) {
        const Interval iv = stack[--depth];
        const int count = iv.va - iv.vb;
        if (count <= 0) continue;
        const double fa = p(iv.a), fb = p(iv.b);
        const bool signChange = (fa < 0.0) != (fb < 0.0) && fa != 0.0;
        if (count == 1 && signChange) {
            // Step 2a: one crossing, bracketed by a sign change.
            found[n++] = refine == SturmRefine::Illinois ? illinois(p, iv.a, iv.b, relTol)
                                                         : bisect(p, iv.a, iv.b, relTol);
            continue;
        }
        if (fb == 0.0 && count == 1) {
            // An exact root at the end (dyadic roots are met exactly by bisection): a
            // tangency when p' vanishes there too.
            listExactZero(p, dp, iv.b, found.data(), &n);
            continue;
        }
        const double m = 0.5 * iv.a + 0.5 * iv.b;
        if (m <= iv.a || m >= iv.b || depth + 2 > int(stack.size())) {
            // Step 2b: a cluster the counts cannot split (or a tangency) at full precision:
            // one crossing if p changes sign over it, else one tangency.
            found[n++] = m;
            if (!signChange) found[n++] = m;
            continue;
        }
        // Step 2c: split. Push the right half first so roots come out roughly ascending.
        const int vm = seq.variations(m);
        stack[depth++] = {m, iv.b, vm, iv.vb};
        stack[depth++] = {iv.a, m, iv.va, vm};
    }
    n = finalizeRoots(p, found.data(), n, tlo, thi);
    n = std::min(n, p.degree());
    std::copy(found.begin(), found.begin() + n, roots);
    return n;
}

}  // namespace csg
