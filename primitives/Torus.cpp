// Notation: t is the parameter of the line o + t d; u = d / |d| and s = |d| (t - tBase) is the
// distance along the line from a base point b = o + tBase d, the point of the line nearest
// the centre. F(p) = (|p|^2 + R^2 - r^2)^2 - 4 R^2 (x^2 + y^2), the torus quartic, is <= 0
// exactly inside; along the line it is a quartic in s with leading coefficient 1. G(s) =
// (rho - R)^2 + z^2 - r^2, the tube form, has the same real roots (F = G times a positive
// factor) and is what Solver::Auto solves.
#include "primitives/Torus.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "primitives/base/Fma.h"
#include "primitives/solvers/ErrorFree.h"
#include "primitives/solvers/LinePoint.h"
#include "primitives/solvers/Polish.h"
#include "primitives/solvers/Roots.h"

namespace csg {
namespace {

// Distance from the z axis. Not std::hypot, whose careful scaling showed in a torus render's
// instructions (bench/README.md, torus section): the points solved here lie within a few torus
// sizes of the centre, and a point so far away that x^2 + y^2 overflows gets rho = inf, which
// still classifies it as outside.
double radial(double x, double y) {
    return std::sqrt(x * x + y * y);
}

// The tube form along the line b + s u (|u| = 1), G(s) = (rho - R)^2 + z^2 - r^2: it has the
// quartic's real roots and is negative exactly inside, and it is evaluated from the point
// itself, without the monomial expansion's loss of r^2 against R^2. With c = b.x u.y - b.y u.x
// (constant along the line), G'' = 2 (1 - R c^2 / rho^3): G is convex where rho^3 > R c^2 and
// concave on the one interval around the line's nearest approach to the axis where
// rho^3 < R c^2, so its critical points, one at most per piece, cut the line into monotone
// pieces that hold one root each. The one evaluator of G (at(), and scaledAt() for Newton's
// steps): the tube path, and the quartic path's polish and sliver test. Built once per ray by
// spans(), whose cheap test reads a, c and s0 too.
struct TubeLine {
    Vec3 b, u;
    double R, r;
    double a;        // u.x^2 + u.y^2
    double cross;    // c = b.x u.y - b.y u.x
    double cross2;   // c^2
    double nearest;  // s0 = -(b.x u.x + b.y u.y) / a: the nearest approach to the axis (a > 0)

    TubeLine(const Vec3& base, const Vec3& unit, double majorRadius, double minorRadius)
        : b(base),
          u(unit),
          R(majorRadius),
          r(minorRadius),
          a(unit.x * unit.x + unit.y * unit.y),
          cross(base.x * unit.y - base.y * unit.x),
          cross2(cross * cross),
          nearest(a > 0.0 ? -(base.x * unit.x + base.y * unit.y) / a : 0.0) {}

    // G and its derivatives at s. side != 0 asks for the one-sided limit of G' at the point
    // where a line across the axis meets it (rho = 0, a kink of rho): from larger s (+1) or
    // smaller (-1); G'' is not defined there and is not asked for.
    struct At {
        double g, dg, ddg;
        double err;  // a bound on the rounding error of g (unit: length^2)
    };
    // Always inlined: a call (the At returned through memory, the line reloaded) costs as much
    // as the evaluation, and at() is most of the tube path's work.
    [[gnu::always_inline]] At at(double s, double side = 0.0) const {
        const Vec3 p = b + s * u;
        const double rho = radial(p.x, p.y);
        const double dr = rho - R;
        const double az = std::abs(p.z);
        const double drho = side != 0.0 ? side * std::sqrt(a)
                            : rho > 0.0 ? (p.x * u.x + p.y * u.y) / rho
                                        : 0.0;
        At v;
        v.g = dr * dr + (p.z - r) * (p.z + r);
        v.dg = 2.0 * (dr * drho + p.z * u.z);
        v.ddg = 2.0 * (1.0 - R * cross2 / (rho * rho * rho));
        v.err = roundingBound(rho, dr, az);
        return v;
    }

    // A bound on the rounding error of G at a point at distance rho from the axis (dr = rho -
    // R) and height +-az. p is off by an ulp of |p| <= rho + |z| per component (|s| <= |p| as b
    // is the line's point nearest the centre), rho by ~2 more ulps of rho, which move G by |grad
    // G| = 2 sqrt(dr^2 + z^2) times that; the products and sums add a few ulps of their terms.
    // 4 ulps of the sum of those magnitudes covers them.
    double roundingBound(double rho, double dr, double az) const {
        return 4.0 * tol::kUlp *
               ((std::abs(dr) + az) * (2.0 * rho + R + az) + dr * dr + (az + r) * (az + r));
    }

    // What Newton's step on G reads, without at()'s division by rho: G, and G' times rho
    // (the step g / G' is g rho / (G' rho)), so that each step's chain of dependent operations
    // holds one division, not two. G' itself (dg()) is formed once, where the steps end.
    struct Scaled {
        double g;
        double dgRho;  // G' rho = 2 ((rho - R) (p . u)_xy + z u.z rho)
        double rho;
        double dgAxis;  // G' where rho = 0: 2 z u.z, as at() takes it there
        double err;
        double dg() const { return rho > 0.0 ? dgRho / rho : dgAxis; }
    };
    [[gnu::always_inline]] Scaled scaledAt(double s) const {
        const Vec3 p = b + s * u;
        const double rho = radial(p.x, p.y);
        const double dr = rho - R;
        Scaled v;
        v.g = dr * dr + (p.z - r) * (p.z + r);
        v.dgRho = 2.0 * (dr * (p.x * u.x + p.y * u.y) + p.z * u.z * rho);
        v.rho = rho;
        v.dgAxis = 2.0 * p.z * u.z;
        v.err = roundingBound(rho, dr, std::abs(p.z));
        return v;
    }

    // Whether sigma G(s) > err at s (sigma = +1: clearly outside, -1: clearly inside), so that
    // a value within rounding of zero is neither.
    bool beyondRounding(double s, double sigma) const {
        const At v = at(s);
        return sigma * v.g > v.err;
    }

    // On a piece [lo, hi] where H = sigma G is convex (sigma = +1 on a convex piece of G, -1 on
    // the concave one), H >= 0 at both ends, H' < 0 at lo and > 0 at hi (h*, d* are H and H'
    // there): a point x where H < -err (vx: G there), true, so that G changes sign on both sides of
    // x; false when H is within rounding of >= 0 throughout. Proven either way as early as
    // possible: the tangents at the bracket's ends bound a convex H from below, and Newton on H'
    // moves towards its minimum, where the two meet.
    bool findDip(double sigma, double lo, double hlo, double dlo, double hi, double hhi, double dhi,
                 double converged, double& x, At& vx) const {
        x = std::numeric_limits<double>::quiet_NaN();
        for (int i = 0; i < 100; ++i) {
            const double xt = (hhi - hlo + dlo * lo - dhi * hi) / (dlo - dhi);
            if (hlo + dlo * (xt - lo) > 0.0) return false;
            if (!(x > lo && x < hi)) x = xt > lo && xt < hi ? xt : 0.5 * lo + 0.5 * hi;
            if (!(x > lo && x < hi)) return false;  // the bracket is two adjacent doubles
            const At v = at(x);
            const double h = sigma * v.g, dh = sigma * v.dg, ddh = sigma * v.ddg;
            if (h < -v.err) {
                vx = v;
                return true;
            }
            if (dh == 0.0) return false;  // the minimum itself
            if (dh < 0.0)
                lo = x, hlo = h, dlo = dh;
            else
                hi = x, hhi = h, dhi = dh;
            const double next = x - dh / ddh;
            if (std::abs(next - x) <= converged) return false;  // at the minimum
            x = next;
        }
        return false;
    }
};

// A point where the line's monotone pieces of G meet, with the sign G is taken to have there.
struct Break {
    double s;
    TubeLine::At v;
    bool negative;
};

// The zero of g + dg h + ddg h^2 / 2 nearest s (h = 0) when it lies in (lo, hi), else NaN.
double taylorRoot(double s, const TubeLine::At& v, double lo, double hi) {
    const double disc = v.dg * v.dg - 2.0 * v.g * v.ddg;
    if (!(disc >= 0.0) || v.dg == 0.0) return std::numeric_limits<double>::quiet_NaN();
    // The smaller-magnitude root, without cancellation.
    const double x = s - 2.0 * v.g / (v.dg + std::copysign(std::sqrt(disc), v.dg));
    return x > lo && x < hi ? x : std::numeric_limits<double>::quiet_NaN();
}

// The zero of G between lo and hi (lo < hi), where G rises (rising) or falls through zero and
// has no other zero: Newton steps from x, replaced by bisection when they would leave the
// shrinking bracket; done once a step is at most `converged` (quadratic convergence makes the
// next error far smaller) or the bracket is two adjacent doubles. Also returns G' where the
// last step started (for Step 6's test of a grazing crossing).
struct TubeRoot {
    double s;
    double dg;
    double err;  // the rounding bound of G where the last step started
};
TubeRoot crossing(const TubeLine& line, double lo, double hi, double x, bool rising,
                  double converged) {
    TubeLine::Scaled v{};
    for (int i = 0; i < 100; ++i) {
        v = line.scaledAt(x);
        if (v.g == 0.0) return {x, v.dg(), v.err};
        if ((v.g < 0.0) == rising)
            lo = x;
        else
            hi = x;
        double next = v.dgRho != 0.0 ? x - v.g * v.rho / v.dgRho : lo;
        // A step this small is the last one (it may round onto the bracket's end).
        if (std::abs(next - x) <= converged) return {std::clamp(next, lo, hi), v.dg(), v.err};
        if (!(next > lo && next < hi)) next = 0.5 * lo + 0.5 * hi;
        if (next <= lo || next >= hi) return {x, v.dg(), v.err};
        x = next;
    }
    return {x, v.dg(), v.err};
}

// Newton on G from a root s of the quartic while |G| drops, kept within [lo, hi]: G has the
// quartic's roots (F = G times a factor that is positive for R > r) without the monomial
// expansion's loss of r^2 against R^2 (a thin torus).
double polish(const TubeLine& line, double s, double lo, double hi) {
    TubeLine::At v = line.at(s);
    for (int i = 0; i < 4 && v.g != 0.0 && v.dg != 0.0; ++i) {
        const double next = s - v.g / v.dg;
        if (!(next >= lo && next <= hi)) break;
        const TubeLine::At nv = line.at(next);
        if (!(std::abs(nv.g) < std::abs(v.g))) break;
        s = next, v = nv;
    }
    return s;
}

// G at the point o + (tBase + sigma) d of the caller's own line, to a few ulps of G itself
// rather than of r^2: the point's coordinates, rho - R and the squares are carried as hi + lo
// sums. TubeLine::at forms p = b + s u in double, and b is itself rounded, so its G is off by
// ~ulp(|p|) r, which moves a crossing by that over |G'|: at a near-tangent crossing (the line
// meets the tube at a grazing angle, |G'| = 2 r cos) that was ~12 ulps of t. NaN where rho = 0.
// Out of line: called for a few percent of crossings.
[[gnu::noinline]] double accurateG(const Vec3& o, const Vec3& d, double tBase, double sigma,
                                   double R, double r) {
    double hi[3], lo[3];
    for (int i = 0; i < 3; ++i) {
        const Sum2 base = twoProduct(tBase, d[i]), step = twoProduct(sigma, d[i]);
        const Sum2 near = twoSum(o[i], base.hi);
        const Sum2 p = twoSum(near.hi, step.hi);
        hi[i] = p.hi;
        lo[i] = p.lo + near.lo + base.lo + step.lo;
    }
    // rho^2 = x^2 + y^2, then rho and its low part from the square root's residual.
    const Sum2 xx = twoProduct(hi[0], hi[0]), yy = twoProduct(hi[1], hi[1]);
    const Sum2 rho2 = twoSum(xx.hi, yy.hi);
    const double rho2Lo = rho2.lo + xx.lo + yy.lo + 2.0 * (hi[0] * lo[0] + hi[1] * lo[1]);
    const double rho = std::sqrt(rho2.hi);
    if (!(rho > 0.0)) return std::numeric_limits<double>::quiet_NaN();
    const double rhoLo = (fusedMultiplyAdd(-rho, rho, rho2.hi) + rho2Lo) / (2.0 * rho);
    // G = (rho - R)^2 + z^2 - r^2.
    const Sum2 dr = twoSum(rho, -R);
    const double drLo = dr.lo + rhoLo;
    const Sum2 dr2 = twoProduct(dr.hi, dr.hi), zz = twoProduct(hi[2], hi[2]);
    const Sum2 rr = twoProduct(r, r);
    const Sum2 g1 = twoSum(dr2.hi, zz.hi);
    const Sum2 g2 = twoSum(g1.hi, -rr.hi);
    return g2.hi +
           (g2.lo + g1.lo + dr2.lo + zz.lo - rr.lo + 2.0 * dr.hi * drLo + 2.0 * hi[2] * lo[2]);
}

}  // namespace

PolynomialDD Torus::quarticDD(const Vec3& o, const Vec3& d, double tBase) const {
    // Step 1: the base point p0 = o + tBase d per axis in double-double (exact products).
    DoubleDouble p0[3];
    for (int i = 0; i < 3; ++i) {
        const Sum2 td = twoProduct(tBase, d[i]);
        p0[i] = DoubleDouble(o[i]) + DoubleDouble(td.hi, td.lo);
    }
    const DoubleDouble dx = d.x, dy = d.y, dz = d.z, R = majorRadius, r = minorRadius;
    // Step 2: q(sigma) = |p0 + sigma d|^2 + R^2 - r^2 and h(sigma) = x^2 + y^2, then
    // F = q^2 - 4 R^2 h.
    const DoubleDouble hLine[3] = {p0[0] * p0[0] + p0[1] * p0[1],
                                   DoubleDouble(2.0) * (p0[0] * dx + p0[1] * dy),
                                   dx * dx + dy * dy};
    const DoubleDouble q[3] = {hLine[0] + p0[2] * p0[2] + R * R - r * r,
                               hLine[1] + DoubleDouble(2.0) * (p0[2] * dz), hLine[2] + dz * dz};
    const DoubleDouble fourR2 = DoubleDouble(4.0) * R * R;
    PolynomialDD f;
    f.degree = 4;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) f.c[i + j] = f.c[i + j] + q[i] * q[j];
    for (int i = 0; i < 3; ++i) f.c[i] = f.c[i] - fourR2 * hLine[i];
    return f;
}

Polynomial Torus::quarticAlong(const Vec3& b, const Vec3& u) const {
    const double R = majorRadius, r = minorRadius;
    // F(b + s u) with |u| = 1: let q(s) = |b + s u|^2 + R^2 - r^2 = s^2 + 2 e s + g and
    // h(s) = x^2 + y^2 = a s^2 + 2 f s + k; F = q^2 - 4 R^2 h.
    const double e = glm::dot(b, u);
    const double a = u.x * u.x + u.y * u.y;
    const double f = b.x * u.x + b.y * u.y;
    const double rho = radial(b.x, b.y);
    const double g = glm::dot(b, b) + (R - r) * (R + r);
    // The constant term F(b) = ((rho - R)^2 + z^2 - r^2) ((rho + R)^2 + z^2 - r^2), factored so
    // that the first factor, small near the surface, is formed without cancellation.
    const double nearFactor = (rho - R) * (rho - R) + (b.z - r) * (b.z + r);
    const double farFactor = (rho + R) * (rho + R) + (b.z - r) * (b.z + r);
    const double R2 = R * R;
    return Polynomial{nearFactor * farFactor, 4.0 * (e * g - 2.0 * R2 * f),
                      4.0 * e * e + 2.0 * g - 4.0 * R2 * a, 4.0 * e, 1.0};
}

namespace {

// Where the line starts (`from`, in s), and G there once it has been evaluated: the start of a
// ray that leaves a surface lies on it, and both tests of such a ray read G there.
struct LineStart {
    double s;
    TubeLine::At v{};
    bool known = false;
};

// Whether a line that starts where G is v meets nothing past that start (a ray leaving the
// torus, or moving away from it), given that rho grows from there (the start lies past the
// line's nearest approach to the axis): G is clearly positive there (beyond its rounding
// bound), not falling, and convex (G'' > 2 tol::kTubeConvexRel: beyond the concave piece's
// reach by more than rounding), as it then stays, G'' growing with rho. A convex G that is not
// falling does not fall later, so no span lies past `from`, and LocalSpans lets those before
// it be left out: the answer without Steps 2-6 (a shadow or reflected ray that leaves the
// outer half of a torus away from its axis skips the cube root for the concave piece).
bool leavesForGood(const TubeLine::At& v) {
    return v.g > v.err && v.dg >= 0.0 && v.ddg > 2.0 * tol::kTubeConvexRel;
}

// Steps 3-6 of spans() on the line b + s u, |u| = 1 (built once by spans()), inside [sLo, sHi]
// (the bounds), for t = tBase + s / len: the tube form's monotone pieces (Solver::Auto), or the
// quartic by the solver asked for.
void tubeSpans(const Torus& torus, const Vec3& o, const Vec3& d, const TubeLine& line,
               const LineStart& lineStart, double sLo, double sHi, double tBase, double len,
               LocalSpans& out) {
    const double R = torus.majorRadius, r = torus.minorRadius;
    const double a = line.a;

    // Step 3: the pieces of convexity. The line comes closest to the axis at s0, at distance
    // m = |c| / sqrt(a); G is concave where rho^3 < R c^2, i.e. |s - s0| < w, which needs
    // m^3 < R c^2, i.e. |c| < R a^(3/2) (c = 0, a line across the axis, is a kink: w = 0).
    double s0 = 0.0, w = -1.0;
    if (a > 0.0 && std::abs(line.cross) < R * a * std::sqrt(a)) {
        const double m2 = line.cross2 / a;
        const double rhoI = std::cbrt(R * line.cross2);
        s0 = line.nearest;
        w = std::sqrt(std::max(0.0, rhoI * rhoI - m2) / a);
    }

    // A line that starts inside its range, outside the tube there beyond rounding and where G
    // is convex (a ray leaving the surface it starts on, moved off it): the range starts at
    // `from`, as the caller clips away what lies before it. On a convex piece G either rises
    // from `from`, crossing nothing before the piece ends, or falls, lying higher behind, so
    // every crossing found there is ahead of it. On the concave piece G may rise from `from`
    // and fall through zero further on, and Newton started beside a crossing just behind
    // `from` (the surface the ray leaves) would settle there.
    const double fromS = lineStart.s;
    TubeLine::At atFrom = lineStart.v;
    const bool fromInRange = fromS > sLo && fromS < sHi;
    bool startsAtFrom = false;
    if (fromInRange) {
        if (!lineStart.known) atFrom = line.at(fromS);
        startsAtFrom = atFrom.g > atFrom.err && !(std::abs(fromS - s0) <= w);
        if (startsAtFrom) sLo = fromS;
    }

    double cuts[4];
    int nCuts = 0;
    cuts[nCuts++] = sLo;
    if (w >= 0.0)
        for (const double c : {s0 - w, s0 + w})
            if (c > cuts[nCuts - 1] && c < sHi) cuts[nCuts++] = c;
    cuts[nCuts++] = sHi;
    // The side a cut's G' is taken from: only the kink of a line across the axis has two.
    const auto sideAt = [&](double s, double side) { return w == 0.0 && s == s0 ? side : 0.0; };

    // Step 4: the signs. G is taken positive at the range's ends (outside the bounds) and by
    // its value at the cuts between pieces, except that a cut with no trustworthy sign keeps
    // its neighbour's: a crossing near it is then found once, never as a sliver on both sides.
    // Inside a piece where G is convex and positive at both ends, it is negative somewhere
    // (two crossings) only if G' changes sign and a dip below -err is found (findDip); on the
    // concave piece, negative at both ends, likewise for a bump above err. So a minimum within
    // rounding of zero is a tangency from outside (no span), a maximum within it one from
    // inside (no gap), the rule quarticSpans applies to the split double roots of a tangent
    // line. Elsewhere a convex piece lies below its chord and a concave one above it, so the
    // ends' signs decide.
    Break breaks[8];
    int nBreaks = 0;
    TubeLine::At vp = startsAtFrom ? atFrom : line.at(sLo, sideAt(sLo, 1.0));
    breaks[nBreaks++] = {sLo, vp, false};
    const double convergedStep = tol::kTubeNewtonStep * r;
    for (int k = 0; k + 1 < nCuts; ++k) {
        const double p = cuts[k], q = cuts[k + 1];
        const bool concave = w >= 0.0 && std::abs(0.5 * p + 0.5 * q - s0) < w;
        const bool last = k + 2 == nCuts;
        const bool pNegative = breaks[nBreaks - 1].negative;
        // The last piece, convex, rising from outside: no crossing, whatever G is at its end
        // (so its value there is never read; the start's stands in).
        if (last && !concave && !pNegative && vp.dg >= 0.0) {
            breaks[nBreaks++] = {q, vp, false};
            break;
        }
        const TubeLine::At vq = line.at(q, sideAt(q, -1.0));
        const bool qNegative = last ? false : std::abs(vq.g) <= vq.err ? pNegative : vq.g < 0.0;
        const double sigma = concave ? -1.0 : 1.0;
        if (pNegative == concave && qNegative == concave && sigma * vp.dg < 0.0 &&
            sigma * vq.dg > 0.0) {
            double x;
            TubeLine::At vx;
            if (line.findDip(sigma, p, sigma * vp.g, sigma * vp.dg, q, sigma * vq.g, sigma * vq.dg,
                             convergedStep, x, vx))
                breaks[nBreaks++] = {x, vx, !concave};
        }
        breaks[nBreaks++] = {q, vq, qNegative};
        vp = sideAt(q, 1.0) != 0.0 ? line.at(q, 1.0) : vq;
    }

    // Step 5: one crossing in each monotone piece whose ends' signs differ; the first break
    // is outside and so is the last, so crossings alternate entering and leaving. No crossing
    // is solved in a piece that ends before out.from - out.margin, where the caller clips
    // (its place holds the piece's start, also before it: a reflected or refracted ray's tube
    // behind it); with out.firstOnly, none after the first span that reaches past `from` by
    // more than out.margin, and not that span's exit when it is the first span past `from`, its
    // entry lies that far past `from` and the start of its exit piece that far past the entry:
    // the start stands for the exit (LocalSpans), as closest() reads only the entry and any()
    // only that the span is there (a ray that starts inside a span is answered with where it
    // ends, and the caller may fuse it with the next across a sliver of a gap). That start is
    // inside (a dip, or a cut that is or is taken negative), and the exit is solved within the
    // piece, so it lies at or past it.
    double ends[4], times[4];  // sigma = t - tBase, and t itself (polished or tBase + sigma)
    int m = 0;
    const double polishBelow = 2.0 * r * tol::kTubeGrazingCos;
    // The crossings solved (not the placeholders of clipped pieces), for Step 7.
    double crossings[4], sigmaLo[4], sigmaHi[4];
    int crossingEnd[4], nCrossings = 0;
    bool wanted[4] = {};
    for (int k = 0; k + 1 < nBreaks && m < 4; ++k) {
        const Break& lo = breaks[k];
        const Break& hi = breaks[k + 1];
        if (lo.negative == hi.negative) continue;
        if (out.firstOnly && m % 2 == 0 && m > 0 &&
            tBase + ends[m - 1] - std::max(tBase + ends[m - 2], out.from) > out.margin)
            break;
        if (out.firstOnly && m % 2 == 1 && tBase + ends[m - 1] > out.from + out.margin &&
            (m == 1 || times[m - 2] < out.from) &&
            tBase + lo.s / len - (tBase + ends[m - 1]) > out.margin) {
            ends[m] = lo.s / len, times[m] = tBase + ends[m];
            ++m;
            break;
        }
        if (tBase + hi.s / len < out.from - out.margin) {
            ends[m] = lo.s / len, times[m] = tBase + ends[m];
            ++m;
            continue;
        }
        // A piece that holds `from` and where G has its end's sign, beyond rounding, has its
        // one crossing before `from`, where the caller clips it away as it would the solved
        // one: the piece's start holds its place (a ray refracted into the tube, whose entry
        // lies behind it, or one leaving the tube where G is concave, which the range does not
        // start at).
        if (fromS > lo.s && fromS < hi.s && tBase + lo.s / len < out.from) {
            const TubeLine::At& v = atFrom;  // the piece lies in the range, so from does
            if (std::abs(v.g) > v.err && (v.g < 0.0) == hi.negative) {
                ends[m] = lo.s / len, times[m] = tBase + ends[m];
                ++m;
                continue;
            }
        }
        // Start from the root of G's Taylor quadratic at the end nearer zero (G'' is known
        // there), else from the secant through the ends' values, else from the middle.
        const Break& near = std::abs(lo.v.g) < std::abs(hi.v.g) ? lo : hi;
        double start = taylorRoot(near.s, near.v, lo.s, hi.s);
        if (!(start > lo.s && start < hi.s) && (lo.v.g < 0.0) != (hi.v.g < 0.0))
            start = lo.s + (hi.s - lo.s) * (lo.v.g / (lo.v.g - hi.v.g));
        if (!(start > lo.s && start < hi.s)) start = 0.5 * lo.s + 0.5 * hi.s;
        const TubeRoot root = crossing(line, lo.s, hi.s, start, lo.negative, convergedStep);
        ends[m] = root.s / len;
        // Step 6: where the line meets the tube at a grazing angle (|G'| = 2 r cos at the
        // crossing), one Newton step on the accurate G, in sigma = t - tBase (G' from
        // crossing's last step; its relative error only scales this step's own small size).
        if (std::abs(root.dg) < polishBelow) {
            const double g = accurateG(o, d, tBase, ends[m], R, r);
            const double dg = root.dg * len;
            if (std::isfinite(g) && dg != 0.0) {
                const double next = ends[m] - g / dg;
                if (next * len > lo.s && next * len < hi.s) ends[m] = next;
            }
        }
        // Step 7 (Auto): where the tube form's rounding bound over |G'| may exceed half an ulp
        // of t, one Newton step on the accurate G (double-double inside), t = tBase + sigma -
        // G / G' summed in double-double and rounded once: the crossing's error is then the
        // step's own, ~(G / G')^2 G'' / G', far below an ulp. The other polishers: Step 8.
        times[m] = tBase + ends[m];
        if (torus.polisher == Polisher::Auto &&
            root.err > tol::kPolishConditionUlps * ulpOf(times[m]) * std::abs(root.dg) * len) {
            const double g = accurateG(o, d, tBase, ends[m], R, r);
            const double dg = root.dg * len;
            const double next = ends[m] - g / dg;
            if (std::isfinite(g) && dg != 0.0 && next * len > lo.s && next * len < hi.s)
                times[m] = (DoubleDouble(tBase) + DoubleDouble(ends[m]) - g / dg).value();
        }
        wanted[m] = torus.polisher != Polisher::Auto && torus.polisher != Polisher::None;
        sigmaLo[m] = lo.s / len, sigmaHi[m] = hi.s / len;
        crossings[nCrossings] = ends[m], crossingEnd[nCrossings++] = m;
        ++m;
    }
    // Step 8: Newton, Laguerre or Bairstow (Polish.h; Bairstow takes the neighbouring crossing
    // as the quadratic factor's other root) on every crossing, on the quartic of the line's
    // doubles formed in double-double; t = tBase + sigma rounded once.
    if (torus.polisher != Polisher::Auto && torus.polisher != Polisher::None) {
        PolynomialDD quartic;
        bool formed = false;
        for (int j = 0; j < nCrossings; ++j) {
            const int e = crossingEnd[j];
            if (!wanted[e]) continue;
            if (!formed) quartic = torus.quarticDD(o, d, tBase), formed = true;
            const DoubleDouble x = polishRootWith(torus.polisher, quartic, crossings, nCrossings, j,
                                                  sigmaLo[e], sigmaHi[e]);
            times[e] = (DoubleDouble(tBase) + x).value();
        }
    }
    for (int i = 0; i + 1 < m; i += 2) out.add(times[i], 0, times[i + 1], 0);
}

void quarticSpans(const Torus& torus, const Vec3& o, const Vec3& d, const TubeLine& line,
                  double sLo, double sHi, double tBase, double len, LocalSpans& out) {
    // The quartic's roots in range; F > 0 at both ends of the range (outside), so
    // the solid is between roots 0-1 and 2-3. An odd count (a root lost to rounding) is
    // judged by F between the roots instead.
    const Polynomial quartic = torus.quarticAlong(line.b, line.u);
    double roots[4];
    const int n = solve(quartic, sLo, sHi, roots, torus.solver, 0.0, Polisher::None);
    for (int i = 0; i < n; ++i) {
        if (isTangency(roots, n, i)) continue;
        const double lo = i > 0 ? 0.5 * (roots[i - 1] + roots[i]) : sLo;
        const double hi = i + 1 < n ? 0.5 * (roots[i] + roots[i + 1]) : sHi;
        roots[i] = polish(line, roots[i], lo, hi);
    }
    // The roots' times: polished on the quartic of the line's doubles in double-double (Polish.h;
    // Auto where the tube form's rounding bound over |G'| may exceed half an ulp of t), else
    // tBase + s / len.
    double times[4], sigma[4];
    for (int i = 0; i < n; ++i) times[i] = tBase + roots[i] / len, sigma[i] = roots[i] / len;
    if (torus.polisher != Polisher::None) {
        PolynomialDD dd;
        bool formed = false;
        for (int i = 0; i < n; ++i) {
            if (isTangency(roots, n, i)) continue;
            const TubeLine::At v = line.at(roots[i]);
            if (torus.polisher == Polisher::Auto &&
                !(v.err > tol::kPolishConditionUlps * ulpOf(times[i]) * std::abs(v.dg) * len))
                continue;
            double lo, hi;
            if (!formed) dd = torus.quarticDD(o, d, tBase), formed = true;
            rootBracket(sigma, n, i, sLo / len, sHi / len, &lo, &hi);
            times[i] =
                (DoubleDouble(tBase) + polishRootWith(torus.polisher, dd, sigma, n, i, lo, hi))
                    .value();
        }
    }
    if (n % 2 == 0) {
        // The quartic's coefficient rounding splits a tangent line's double root into
        // two close roots as often as into a complex pair. A span whose middle is not inside
        // by more than the tube form's rounding error is such a split (dropped), and so is a
        // gap between spans whose middle is not outside by more (the spans are joined). ends
        // holds indices into roots.
        int ends[4];
        int m = 0;
        for (int i = 0; i + 1 < n; i += 2) {
            if (roots[i] != roots[i + 1] &&
                !line.beyondRounding(0.5 * roots[i] + 0.5 * roots[i + 1], -1.0))
                continue;
            if (m > 0 && !line.beyondRounding(0.5 * roots[ends[m - 1]] + 0.5 * roots[i], 1.0)) {
                ends[m - 1] = i + 1;
                continue;
            }
            ends[m++] = i, ends[m++] = i + 1;
        }
        for (int i = 0; i + 1 < m; i += 2) out.add(times[ends[i]], 0, times[ends[i + 1]], 0);
        return;
    }
    for (int i = 0; i + 1 < n; ++i)
        if (quartic(0.5 * roots[i] + 0.5 * roots[i + 1]) < 0.0)
            out.add(times[i], 0, times[i + 1], 0);
}

}  // namespace

void Torus::spans(const Vec3& o, const Vec3& d, LocalSpans& out) const {
    const double R = majorRadius, r = minorRadius;
    const double len = glm::length(d);
    if (!(len > 0.0) || !std::isfinite(len)) return;
    const Vec3 u = d / len;

    // Step 1: move to the point of the line nearest the centre, so every coefficient is of
    // the size of the torus (the caller's shift to the bounds entry already did most of it).
    const double tBase = -glm::dot(o, d) / (len * len);
    const Vec3 b = pointOnLine(o, d, tBase);

    const TubeLine line(b, u, R, r);
    const double a = line.a;
    LineStart start{(out.from - tBase) * len};
    if (solver == Solver::Auto && a > 0.0 && std::isfinite(start.s) && start.s > line.nearest) {
        start.v = line.at(start.s);
        start.known = true;
        if (leavesForGood(start.v)) return;
    }

    // Step 2: the cheap test: the line against the slab |z| <= r and the cylinder
    // x^2 + y^2 <= (R + r)^2, as an s range; empty means a miss without the quartic.
    double sLo = -kInfinity, sHi = kInfinity;
    if (u.z != 0.0) {
        const double s0 = (-r - b.z) / u.z, s1 = (r - b.z) / u.z;
        sLo = std::min(s0, s1), sHi = std::max(s0, s1);
    } else if (std::abs(b.z) > r) {
        return;
    }
    if (a > 0.0) {
        // The line's horizontal projection passes the axis at distance m = |c| / sqrt(a),
        // c = b.x u.y - b.y u.x, nearest at s0 = -(b.x u.x + b.y u.y) / a, and is within R + r
        // of it for |s - s0| <= sqrt(((R + r)^2 - m^2) / a): no quadratic to solve.
        const double outer = R + r;
        const double m = std::abs(line.cross) / std::sqrt(a);
        if (!(m <= outer)) return;
        const double half = std::sqrt((outer - m) * (outer + m) / a);
        sLo = std::max(sLo, line.nearest - half), sHi = std::min(sHi, line.nearest + half);
    } else if (radial(b.x, b.y) > R + r) {
        return;
    }
    if (!(sLo <= sHi)) return;
    // Widen so that roots on the range's ends (the torus touches the slab and the cylinder)
    // are not lost to the quartic's rounding.
    const double widen = tol::kTorusRangeMargin * (R + r);
    sLo -= widen, sHi += widen;

    if (solver == Solver::Auto)
        tubeSpans(*this, o, d, line, start, sLo, sHi, tBase, len, out);
    else
        quarticSpans(*this, o, d, line, sLo, sHi, tBase, len, out);
}

bool Torus::inside(const Vec3& p) const {
    const double rho = radial(p.x, p.y);
    const double dr = rho - majorRadius;
    return dr * dr + p.z * p.z <= minorRadius * minorRadius;
}

// The direction from the tube's core circle to p: (x (rho - R) / rho, y (rho - R) / rho, z), of
// length l = sqrt((rho - R)^2 + z^2). rho - R is formed directly, exact where rho is near R
// (the core's nearest point subtracted from p would cancel there), and the one quotient
// (rho - R) / (rho l) scales both horizontal components: two divisions instead of five.
Vec3 Torus::normal(const Vec3& p, uint16_t) const {
    const double rho = radial(p.x, p.y);
    if (!(rho > 0.0)) return Vec3(0.0, 0.0, 1.0);
    const double dr = rho - majorRadius;
    const double l = std::sqrt(dr * dr + p.z * p.z);
    if (!(l > 0.0)) return Vec3(0.0, 0.0, 1.0);
    const double horizontal = dr / (rho * l);
    return Vec3(p.x * horizontal, p.y * horizontal, p.z / l);
}

}  // namespace csg
