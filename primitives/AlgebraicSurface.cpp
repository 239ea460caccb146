// Notation: t is the parameter of the line o + t d (d not unit); the chord is the part of the
// line inside the box, [tIn, tOut]; u is the solve variable, t = tMid + u h with tMid the
// chord's middle and h the power of two at or above its half-length, so u lies in [-1, 1]
// and scaling by h is exact. G is F seen from the box centre (AlgebraicSurface.h).
#include "primitives/AlgebraicSurface.h"

#include <algorithm>
#include <cmath>

#include "primitives/solvers/ErrorFree.h"
#include "primitives/solvers/LinePoint.h"
#include "primitives/solvers/Roots.h"

namespace csg {

AlgebraicSurface AlgebraicSurface::make(const ExactPolynomial& f, const Bounds3& box, Solver solver,
                                        double tolerance, Polisher polisher) {
    auto data = std::make_shared<AlgebraicData>();
    data->box = box;
    AlgebraicSurface s{nullptr, solver, tolerance, polisher};
    // Step 1: the input's domain.
    const int n = f.degree();
    if (!(box.finite() && box.lo.x < box.hi.x && box.lo.y < box.hi.y && box.lo.z < box.hi.z))
        data->invalid = "surface bbox must be finite with lo < hi on every axis";
    else if (n < 1)
        data->invalid = "surface polynomial must have degree 1 to 16 (a constant is no surface)";
    else if (!(tolerance >= 0.0) || !std::isfinite(tolerance))
        data->invalid = "surface solver tolerance must be finite and >= 0";
    if (data->invalid) {
        s.data = data;
        return s;
    }
    // Step 2: re-centre exactly at the box centre, then round once per coefficient.
    data->centre = 0.5 * box.lo + 0.5 * box.hi;
    Trivariate g = f.shifted(data->centre).toTrivariate();
    // Step 3: scale to coefficients <= 1 by a power of two (same solid, no overflow later).
    const double m = g.maxMagnitude();
    if (!(m > 0.0) || !std::isfinite(m)) {
        data->invalid = "surface polynomial coefficients must be finite and not all zero";
        s.data = data;
        return s;
    }
    const double k = std::ldexp(1.0, -std::ilogb(m));
    for (int i = 0; i <= n; ++i)
        for (int j = 0; i + j <= n; ++j)
            for (int l = 0; i + j + l <= n; ++l) g.at(i, j, l) *= k;
    data->g = g;
    for (int a = 0; a < 3; ++a) data->gradient[a] = g.partial(a);
    data->magnitude = g;
    for (int i = 0; i <= n; ++i)
        for (int j = 0; i + j <= n; ++j)
            for (int l = 0; i + j + l <= n; ++l)
                data->magnitude.at(i, j, l) = std::abs(g.at(i, j, l));
    s.data = data;
    return s;
}

const char* AlgebraicSurface::invalidReason() const {
    if (!data) return "surface was not built";
    return data->invalid;
}

void AlgebraicSurface::describe(JsonWriter& json) const {
    if (!data) return;
    json.key("degree").value(data->g.degree());
    json.key("bbox").beginArray().vec(data->box.lo, 3).vec(data->box.hi, 3).endArray();
    json.key("solver").value(solverName(solver));
    json.key("polish").value(polisherName(polisher));
}

Bounds3 AlgebraicSurface::bounds() const {
    return data ? data->box : Bounds3{Vec3(0.0), Vec3(0.0)};
}

bool AlgebraicSurface::chord(const Vec3& o, const Vec3& d, Chord& c) const {
    if (!data || data->invalid) return false;
    const Bounds3& box = data->box;
    // Step 1: the chord through the box (slabs, as Box::spans; faces 0..5).
    double tIn = -kInfinity, tOut = kInfinity;
    uint16_t faceIn = kClipFace, faceOut = kClipFace;
    for (int a = 0; a < 3; ++a) {
        if (d[a] == 0.0) {
            if (o[a] < box.lo[a] || o[a] > box.hi[a]) return false;
            continue;
        }
        double tLo = (box.lo[a] - o[a]) / d[a], tHi = (box.hi[a] - o[a]) / d[a];
        uint16_t fLo = uint16_t(2 * a), fHi = uint16_t(2 * a + 1);
        if (tLo > tHi) std::swap(tLo, tHi), std::swap(fLo, fHi);
        if (tLo > tIn) tIn = tLo, faceIn = fLo;
        if (tHi < tOut) tOut = tHi, faceOut = fHi;
    }
    if (faceIn == kClipFace || !std::isfinite(tIn) || !std::isfinite(tOut) || !(tIn <= tOut))
        return false;
    // Step 2: the solve variable: centred on the chord, scaled by a power of two.
    const double tMid = 0.5 * tIn + 0.5 * tOut;
    const double half = std::max(tOut - tMid, tMid - tIn);
    const double h = half > 0.0 ? std::ldexp(1.0, std::ilogb(half) + 1) : 1.0;
    // Step 3: G along the chord, from the middle point relative to the box centre.
    const Vec3 q = pointOnLine(o, d, tMid) - data->centre;
    c.poly = data->g.along(q, h * d);
    c.tMid = tMid, c.scale = h;
    c.uLo = (tIn - tMid) / h, c.uHi = (tOut - tMid) / h;
    c.tIn = tIn, c.tOut = tOut, c.faceIn = faceIn, c.faceOut = faceOut;
    return true;
}

double AlgebraicSurface::chordErrorBound(const Vec3& q, const Vec3& hd, double u) const {
    // Each coefficient of the chord polynomial is a sum of products of G's coefficients and
    // the components of q and hd, formed by nested Horner in at most ~4 roundings per degree
    // (plus G's own rounding from F): gamma(4n + 4) times the same sum taken over magnitudes,
    // which is |G| at |q| + |u| |hd|, bounds its error at u.
    const Vec3 at = glm::abs(q) + std::abs(u) * glm::abs(hd);
    return tol::gamma(4 * data->g.degree() + 4) * data->magnitude(at);
}

PolynomialDD AlgebraicSurface::chordDD(const Vec3& o, const Vec3& d, const Chord& c) const {
    // q = o - centre + tMid d per axis, in double-double (o - centre and tMid d are exact as
    // hi + lo); h d is exact (h a power of two).
    DoubleDouble q[3];
    for (int a = 0; a < 3; ++a) {
        const Sum2 oc = twoSum(o[a], -data->centre[a]);
        const Sum2 td = twoProduct(c.tMid, d[a]);
        q[a] = DoubleDouble(oc.hi, oc.lo) + DoubleDouble(td.hi, td.lo);
    }
    return data->g.alongDD(q, c.scale * d);
}

int AlgebraicSurface::crossingTimes(const Vec3& o, const Vec3& d, const Chord& c,
                                    const double* roots, int n, double* t) const {
    for (int i = 0; i < n; ++i) t[i] = c.tMid + roots[i] * c.scale;
    if (polisher == Polisher::None || tolerance > 0.0 || n == 0) return 0;
    const Vec3 q = pointOnLine(o, d, c.tMid) - data->centre;
    const Vec3 hd = c.scale * d;
    PolynomialDD dd;
    bool formed = false;
    int polished = 0;
    // The chord's coefficient rounding bound at the chord's far end bounds it at every root
    // (|G| of magnitudes grows with |u|): one trivariate evaluation per ray, not per root.
    const double chordBound =
        polisher == Polisher::Auto
            ? chordErrorBound(q, hd, std::max(std::abs(c.uLo), std::abs(c.uHi)))
            : 0.0;
    for (int i = 0; i < n; ++i) {
        if (isTangency(roots, n, i)) continue;
        // Step 1 (Auto): the cheap condition test. The double root is off by at most the
        // evaluation's and the chord coefficients' rounding over |p'|, times h in t.
        if (polisher == Polisher::Auto) {
            double bound, v, dv;
            c.poly.eval(roots[i], &bound);
            c.poly.evalWithDerivative(roots[i], v, dv);
            const double err = (bound + chordBound) * c.scale;
            if (!(err > tol::kPolishConditionUlps * ulpOf(t[i]) * std::abs(dv))) continue;
        }
        // Step 2: the polish, on the chord polynomial formed once per ray in double-double.
        if (!formed) dd = chordDD(o, d, c), formed = true;
        double lo, hi;
        rootBracket(roots, n, i, c.uLo, c.uHi, &lo, &hi);
        const DoubleDouble u = polishRootWith(polisher, dd, roots, n, i, lo, hi);
        // Step 3: t = tMid + u h, rounded once (u h is exact: h is a power of two).
        t[i] = (DoubleDouble(c.tMid) + DoubleDouble(u.hi * c.scale, u.lo * c.scale)).value();
        ++polished;
    }
    return polished;
}

void AlgebraicSurface::spans(const Vec3& o, const Vec3& d, LocalSpans& out) const {
    Chord c;
    if (!chord(o, d, c)) return;
    // Step 1: the roots of G on the chord (tangencies listed twice), and their times, polished
    // on the chord polynomial in double-double.
    double roots[Polynomial::kMaxDegree], times[Polynomial::kMaxDegree];
    const int n = solve(c.poly, c.uLo, c.uHi, roots, solver, tolerance, Polisher::None);
    crossingTimes(o, d, c, roots, n, times);
    // Step 2: breakpoints: chord ends and distinct roots strictly inside.
    double u[Polynomial::kMaxDegree + 2], t[Polynomial::kMaxDegree + 2];
    int m = 0;
    u[m++] = c.uLo;
    for (int i = 0; i < n; ++i)
        if (roots[i] > u[m - 1] && roots[i] < c.uHi) t[m] = times[i], u[m++] = roots[i];
    u[m++] = c.uHi;
    // Step 3: each piece is inside or out by the sign of G at its middle (a tangency leaves
    // the same sign on both sides, so it merges pieces instead of cutting them); inside
    // pieces that touch form one span.
    auto toT = [&](int i) { return i == 0 ? c.tIn : i == m - 1 ? c.tOut : t[i]; };
    auto face = [&](int i) { return i == 0 ? c.faceIn : i == m - 1 ? c.faceOut : kSurfaceFace; };
    bool inside[Polynomial::kMaxDegree + 1];
    for (int i = 0; i + 1 < m; ++i) inside[i] = c.poly(0.5 * u[i] + 0.5 * u[i + 1]) <= 0.0;
    // Step 3b: a piece between two roots whose neighbours agree takes their side unless G has
    // a sign there that the chord's rounding cannot have made (a split tangency otherwise).
    const Vec3 q = pointOnLine(o, d, c.tMid) - data->centre;
    for (int i = 1; i + 2 < m; ++i) {
        if (inside[i] == inside[i - 1] || inside[i + 1] != inside[i - 1]) continue;
        bool resolved = false;
        for (double w : {0.5, 0.25, 0.75}) {
            const double x = (1.0 - w) * u[i] + w * u[i + 1];
            double bound;
            const double v = c.poly.eval(x, &bound);
            resolved = resolved || std::abs(v) > bound + chordErrorBound(q, c.scale * d, x);
        }
        if (!resolved) inside[i] = inside[i - 1];
    }
    int open = -1;  // breakpoint index where the current span began
    for (int i = 0; i + 1 < m; ++i) {
        const bool in = inside[i];
        if (in && open < 0) open = i;
        if (!in && open >= 0) {
            if (out.count < LocalSpans::kCapacity) out.add(toT(open), face(open), toT(i), face(i));
            open = -1;
        }
    }
    if (open >= 0 && out.count < LocalSpans::kCapacity)
        out.add(toT(open), face(open), toT(m - 1), face(m - 1));
}

bool AlgebraicSurface::inside(const Vec3& p) const {
    if (!data || data->invalid) return false;
    const Bounds3& b = data->box;
    if (p.x < b.lo.x || p.x > b.hi.x || p.y < b.lo.y || p.y > b.hi.y || p.z < b.lo.z ||
        p.z > b.hi.z)
        return false;
    return data->g(p - data->centre) <= 0.0;
}

Vec3 AlgebraicSurface::normal(const Vec3& p, uint16_t face) const {
    if (face < 6) {
        Vec3 n(0.0);
        n[face / 2] = (face & 1) ? 1.0 : -1.0;
        return n;
    }
    if (!data || data->invalid) return Vec3(0.0, 0.0, 1.0);
    // Step 1: the analytic gradient, normalized after scaling by its largest component (so
    // neither tiny nor huge gradients over- or underflow in the length).
    const Vec3 q = p - data->centre;
    Vec3 g(data->gradient[0](q), data->gradient[1](q), data->gradient[2](q));
    const double big = std::max({std::abs(g.x), std::abs(g.y), std::abs(g.z)});
    if (big > 0.0 && std::isfinite(big)) {
        g /= big;
        return g / glm::length(g);
    }
    // Step 2: a critical point: the direction from the box centre, else +z.
    const double l = glm::length(q);
    return l > 0.0 && std::isfinite(l) ? q / l : Vec3(0.0, 0.0, 1.0);
}

}  // namespace csg
