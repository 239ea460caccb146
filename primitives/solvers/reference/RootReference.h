// The real roots of a polynomial in [lo, hi], in 50 digits (Boost.Multiprecision): the
// reference that solver errors are measured against by `csgray bench accuracy`
// (AccuracyReport.cpp) and by tests/torus_test.cpp. Here, not in tests/, because the command
// line is product code and must not depend on tests/. Independent of primitives/solvers/: no
// closed form, no double.
// Notation: c is a coefficient list {c0, c1, ...} for c0 + c1 t + ...; an empty list or one
// that is constant has no roots.
#pragma once

#include <boost/multiprecision/cpp_bin_float.hpp>
#include <vector>

#include "primitives/base/Tolerances.h"

namespace csg::rootref {

using Big = boost::multiprecision::cpp_bin_float_50;

// c at t, by Horner's rule. c must not be empty.
inline Big evaluate(const std::vector<Big>& c, const Big& t) {
    Big y = c.back();
    for (int i = int(c.size()) - 2; i >= 0; --i) y = y * t + c[i];
    return y;
}

// The root of c in [a, b], where c(a), c(b) have opposite signs and c is monotone (no critical
// point inside); dc is c'. Newton kept inside the shrinking bracket, bisection when it would
// leave it.
inline Big monotoneRoot(const std::vector<Big>& c, const std::vector<Big>& dc, Big a, Big b) {
    Big fa = evaluate(c, a);
    Big t = (a + b) / 2;
    for (int i = 0; i < 400; ++i) {
        const Big f = evaluate(c, t);
        if (f == 0) return t;
        if ((f < 0) == (fa < 0)) {
            a = t;
            fa = f;
        } else {
            b = t;
        }
        const Big d = evaluate(dc, t);
        Big next = d != 0 ? t - f / d : (a + b) / 2;
        if (!(next > a && next < b)) next = (a + b) / 2;
        const Big step = tol::kReferenceRootStepRel * (1 + abs(t));
        if (abs(next - t) <= step || b - a <= step) return next;
        t = next;
    }
    return t;
}

// The distinct real roots of c in the closed range [lo, hi], ascending: the critical points
// (roots of c', recursively) split the range into monotone pieces, each holding at most one
// root. A root of even multiplicity is found only where it falls exactly on a piece's end.
inline std::vector<Big> realRoots(std::vector<Big> c, const Big& lo, const Big& hi) {
    while (c.size() > 1 && c.back() == 0) c.pop_back();
    if (c.size() <= 1) return {};
    std::vector<Big> dc(c.size() - 1);
    for (size_t i = 1; i < c.size(); ++i) dc[i - 1] = c[i] * int(i);
    std::vector<Big> cuts = {lo};
    for (const Big& r : realRoots(dc, lo, hi))
        if (r > cuts.back() && r < hi) cuts.push_back(r);
    cuts.push_back(hi);
    std::vector<Big> out;
    for (size_t i = 0; i + 1 < cuts.size(); ++i) {
        const Big fa = evaluate(c, cuts[i]), fb = evaluate(c, cuts[i + 1]);
        if (fa == 0) {
            if (out.empty() || out.back() != cuts[i]) out.push_back(cuts[i]);
        } else if (fb != 0 && (fa < 0) != (fb < 0)) {
            out.push_back(monotoneRoot(c, dc, cuts[i], cuts[i + 1]));
        }
    }
    if (evaluate(c, hi) == 0 && (out.empty() || out.back() != hi)) out.push_back(hi);
    return out;
}

// The quartic of the torus (|p|^2 + R^2 - r^2)^2 - 4 R^2 (x^2 + y^2) (R, r: major and minor
// radii, the z axis its axis) along o + t d, expanded exactly from the double inputs. V is any
// type with double members x, y, z.
template <class V>
std::vector<Big> torusQuartic(double majorRadius, double minorRadius, const V& o, const V& d) {
    const Big R = majorRadius, r = minorRadius;
    const Big ox = o.x, oy = o.y, oz = o.z, dx = d.x, dy = d.y, dz = d.z;
    // q(t) = |o + t d|^2 + R^2 - r^2 and h(t) = x^2 + y^2, as {t^0, t^1, t^2}.
    const Big q[3] = {ox * ox + oy * oy + oz * oz + R * R - r * r,
                      2 * (ox * dx + oy * dy + oz * dz), dx * dx + dy * dy + dz * dz};
    const Big h[3] = {ox * ox + oy * oy, 2 * (ox * dx + oy * dy), dx * dx + dy * dy};
    std::vector<Big> c(5, Big(0));
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) c[size_t(i + j)] += q[i] * q[j];
    for (int i = 0; i < 3; ++i) c[size_t(i)] -= 4 * R * R * h[i];
    return c;
}

// G(o - centre + t d) as a polynomial in t, expanded exactly (up to 50 digits) from the double
// inputs: a trivariate G with degree() and coefficients at(i, j, k) of x^i y^j z^k (Trivariate),
// the centre it is seen from, and the line. V is any type with double members x, y, z.
template <class G, class V>
std::vector<Big> trivariateLine(const G& g, const V& centre, const V& o, const V& d) {
    const int n = g.degree();
    const auto times = [](const std::vector<Big>& a, const std::vector<Big>& b) {
        std::vector<Big> out(a.size() + b.size() - 1, Big(0));
        for (size_t i = 0; i < a.size(); ++i)
            for (size_t k = 0; k < b.size(); ++k) out[i + k] += a[i] * b[k];
        return out;
    };
    // powers[a][e] = (o_a - centre_a + t d_a)^e.
    const std::vector<Big> lines[3] = {{Big(o.x) - Big(centre.x), Big(d.x)},
                                       {Big(o.y) - Big(centre.y), Big(d.y)},
                                       {Big(o.z) - Big(centre.z), Big(d.z)}};
    std::vector<std::vector<Big>> powers[3];
    for (int a = 0; a < 3; ++a) {
        powers[a].push_back({Big(1)});
        for (int e = 1; e <= n; ++e) powers[a].push_back(times(powers[a].back(), lines[a]));
    }
    std::vector<Big> out(size_t(n + 1), Big(0));
    for (int i = 0; i <= n; ++i)
        for (int j = 0; i + j <= n; ++j)
            for (int k = 0; i + j + k <= n; ++k) {
                if (g.at(i, j, k) == 0.0) continue;
                const std::vector<Big> term =
                    times(times(powers[0][size_t(i)], powers[1][size_t(j)]), powers[2][size_t(k)]);
                for (size_t e = 0; e < term.size(); ++e) out[e] += Big(g.at(i, j, k)) * term[e];
            }
    return out;
}

}  // namespace csg::rootref
