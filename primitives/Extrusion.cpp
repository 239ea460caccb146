#include "primitives/Extrusion.h"

#include <algorithm>
#include <cmath>

#include "primitives/SpanCapacity.h"
#include "primitives/solvers/Quadratic.h"
#include "primitives/solvers/Solve.h"

namespace csg {

namespace {

using Entry = LocalSpans::Entry;

// Per-thread scratch, grown once and reused by every line (no allocation per ray).
thread_local std::vector<Crossing2> tlCrossings;
thread_local std::vector<Entry> tlSpans, tlWedge, tlMerged;

struct Candidate {
    double t;
    uint32_t segment;
};
thread_local std::vector<Candidate> tlCandidates;

uint16_t sideFace(uint32_t segment) {
    return uint16_t(Extrusion::kFirstSideFace + segment % Extrusion::kSideFaceIds);
}

// The spans, ascending in s, of the line (o2 + s d2, zo + s zd) in the straight prism
// outline x [zlo, zhi] (an infinite bound has no face).
void straightPrism(const Outline& outline, Vec2 o2, Vec2 d2, double zo, double zd, double zlo,
                   double zhi, std::vector<Entry>& spans) {
    spans.clear();
    double sLo = -kInfinity, sHi = kInfinity;
    uint16_t fLo = kClipFace, fHi = kClipFace;
    if (zd == 0.0) {
        if (!(zo >= zlo && zo <= zhi)) return;
    } else {
        double a = (zlo - zo) / zd, b = (zhi - zo) / zd;
        uint16_t fa = std::isfinite(zlo) ? Extrusion::kBottomFace : kClipFace;
        uint16_t fb = std::isfinite(zhi) ? Extrusion::kTopFace : kClipFace;
        if (zd < 0.0) std::swap(a, b), std::swap(fa, fb);
        sLo = a, fLo = fa, sHi = b, fHi = fb;
    }
    if (d2.x == 0.0 && d2.y == 0.0) {  // along the prism's axis
        if (outline.inside(o2)) spans.push_back({sLo, sHi, fLo, fHi});
        return;
    }
    std::vector<Crossing2>& c = tlCrossings;
    c.clear();
    outline.crossings(o2, d2, c);
    std::sort(c.begin(), c.end(), [](const Crossing2& a, const Crossing2& b) { return a.t < b.t; });
    int winding = 0;
    double start = 0.0;
    uint32_t startSegment = 0;
    for (const Crossing2& x : c) {
        const bool before = outline.filled(winding);
        winding += x.winding;
        const bool after = outline.filled(winding);
        if (!before && after) {
            start = x.t, startSegment = x.segment;
        } else if (before && !after) {
            double lo = start, hi = x.t;
            uint16_t fIn = sideFace(startSegment), fOut = sideFace(x.segment);
            if (lo < sLo) lo = sLo, fIn = fLo;
            if (hi > sHi) hi = sHi, fOut = fHi;
            if (lo <= hi) spans.push_back({lo, hi, fIn, fOut});
        }
    }
}

// The spans of the half-plane n . p >= 0 along o + t d (one span, possibly unbounded).
bool halfPlaneSpan(Vec2 n, Vec2 o, Vec2 d, uint16_t face, Entry& span) {
    const double g0 = glm::dot(n, o), g1 = glm::dot(n, d);
    span = {-kInfinity, kInfinity, kClipFace, kClipFace};
    if (g1 == 0.0) return g0 >= 0.0;
    const double t = -g0 / g1;
    if (g1 > 0.0)
        span.tIn = t, span.faceIn = face;
    else
        span.tOut = t, span.faceOut = face;
    return true;
}

// a and b intersected (both ascending and disjoint).
void intersectSpans(const std::vector<Entry>& a, const std::vector<Entry>& b,
                    std::vector<Entry>& out) {
    out.clear();
    size_t i = 0, j = 0;
    while (i < a.size() && j < b.size()) {
        const Entry& x = a[i];
        const Entry& y = b[j];
        const Entry& in = x.tIn >= y.tIn ? x : y;
        const Entry& outEnd = x.tOut <= y.tOut ? x : y;
        if (in.tIn <= outEnd.tOut) out.push_back({in.tIn, outEnd.tOut, in.faceIn, outEnd.faceOut});
        if (x.tOut < y.tOut)
            ++i;
        else
            ++j;
    }
}

Polynomial product(const Polynomial& a, const Polynomial& b) {
    Polynomial p = Polynomial::ofDegree(a.degree() + b.degree());
    for (int i = 0; i <= p.degree(); ++i) p[i] = 0.0;
    for (int i = 0; i <= a.degree(); ++i)
        for (int j = 0; j <= b.degree(); ++j) p[i + j] += a[i] * b[j];
    return p;
}

Polynomial sum(const Polynomial& a, const Polynomial& b, double bFactor = 1.0) {
    Polynomial p = Polynomial::ofDegree(std::max(a.degree(), b.degree()));
    for (int i = 0; i <= p.degree(); ++i)
        p[i] = (i <= a.degree() ? a[i] : 0.0) + bFactor * (i <= b.degree() ? b[i] : 0.0);
    return p;
}

// One coordinate (0: x, 1: y) of a Bezier segment in the power basis of its parameter u.
Polynomial bezierCoordinate(const Segment2& s, int axis) {
    const double p0 = s.p[0][axis], p1 = s.p[1][axis], p2 = s.p[2][axis];
    if (s.kind == Segment2::Kind::Quadratic)
        return Polynomial{p0, 2.0 * (p1 - p0), p0 - 2.0 * p1 + p2};
    const double p3 = s.p[3][axis];
    return Polynomial{p0, 3.0 * (p1 - p0), 3.0 * (p0 - 2.0 * p1 + p2),
                      p3 - 3.0 * p2 + 3.0 * p1 - p0};
}

// How far from a segment a candidate's image may lie and still be kept: a candidate too many
// costs one more midpoint test, one too few a wrong span.
constexpr double kCandidateSlackRel = 1e-6;

}  // namespace

Extrusion Extrusion::plane(std::shared_ptr<const Outline> outline, const char* shape) {
    if (!outline->indexed()) {
        auto indexed = std::make_shared<Outline>(*outline);
        indexed->buildIndex();
        outline = std::move(indexed);
    }
    Extrusion e;
    e.box = outline->bounds();
    e.outline = std::move(outline);
    e.shape = shape;
    return e;
}

Extrusion Extrusion::linear(double bottom, double top, Vec2 topScale, double twistDegrees) const {
    Extrusion e = *this;
    e.kind = Kind::Linear;
    e.z0 = bottom, e.z1 = top, e.scale = topScale, e.twist = twistDegrees;
    e.twisted.reset();
    if (twistDegrees != 0.0 || topScale.x != topScale.y) e.twisted = TwistedOutline::of(*outline);
    return e;
}

TwistMap Extrusion::twistMap() const {
    return {z0, z1, twist * kPi / 180.0, scale};
}

Extrusion Extrusion::rotated(double degrees) const {
    Extrusion e = *this;
    e.kind = Kind::Rotate;
    e.z0 = -kInfinity, e.z1 = kInfinity, e.scale = Vec2(1.0), e.twist = 0.0;
    e.twisted.reset();
    e.angle = degrees;
    return e;
}

const char* Extrusion::invalidReason() const {
    if (!outline) return "an extrusion needs an outline";
    switch (kind) {
        case Kind::Plane:
            return nullptr;
        case Kind::Linear:
            return std::isfinite(z0) && std::isfinite(z1) && z0 < z1 && std::isfinite(scale.x) &&
                           std::isfinite(scale.y) && scale.x >= 0.0 && scale.y >= 0.0 &&
                           std::isfinite(twist)
                       ? nullptr
                       : "linear_extrude needs a finite height > 0, scales >= 0 and a finite "
                         "twist";
        case Kind::Rotate:
            return angle > 0.0 && angle <= 360.0 ? nullptr
                                                 : "rotate_extrude needs an angle in (0, 360]";
    }
    return nullptr;
}

Bounds3 Extrusion::bounds() const {
    if (box.empty()) return Bounds3{Vec3(0.0), Vec3(0.0)};
    switch (kind) {
        case Kind::Plane:
            return {Vec3(box.lo, -kInfinity), Vec3(box.hi, kInfinity)};
        case Kind::Linear: {
            if (twist != 0.0) {
                // Sections turn about the axis: the cylinder that holds them all.
                const double r = twistMap().boundingRadius(box);
                return {Vec3(-r, -r, z0), Vec3(r, r, z1)};
            }
            // Sections are the outline scaled about the origin by factors between 1 and scale.
            const Vec2 lo = glm::min(box.lo, box.lo * scale), hi = glm::max(box.hi, box.hi * scale);
            return {Vec3(lo, z0), Vec3(hi, z1)};
        }
        case Kind::Rotate: {
            const double r = std::max(std::abs(box.lo.x), std::abs(box.hi.x));
            return {Vec3(-r, -r, box.lo.y), Vec3(r, r, box.hi.y)};
        }
    }
    return {};
}

void Extrusion::spans(const Vec3& o, const Vec3& d, LocalSpans& out) const {
    if (!outline || box.empty()) return;
    if (kind == Kind::Rotate)
        revolvedSpans(o, d, out);
    else if (kind == Kind::Linear && twisted)
        twistSpans(o, d, out);
    else if (kind == Kind::Linear && scale.x != 1.0)
        frustumSpans(o, d, out);
    else
        prismSpans(o, d, out);
}

void Extrusion::prismSpans(const Vec3& o, const Vec3& d, LocalSpans& out) const {
    straightPrism(*outline, Vec2(o), Vec2(d), o.z, d.z, z0, z1, tlSpans);
    addWithinCapacity(tlSpans, out);
}

void Extrusion::twistSpans(const Vec3& o, const Vec3& d, LocalSpans& out) const {
    const TwistMap map = twistMap();
    if (d.z != 0.0) {
        out.cutAtTo = twistedSpans(*outline, *twisted, map, o, d, out.from - out.margin,
                                   out.to + out.margin, tlSpans);
        addWithinCapacity(tlSpans, out);
        return;
    }
    // A level line meets one section, the outline under an affine map: the line's image under
    // that map crosses the outline as a prism's line does.
    if (!(o.z >= z0 && o.z <= z1) || (d.x == 0.0 && d.y == 0.0)) return;
    const double s = (o.z - z0) / (z1 - z0);
    const double sx = 1.0 + (scale.x - 1.0) * s, sy = 1.0 + (scale.y - 1.0) * s;
    if (!(sx > 0.0 && sy > 0.0)) return;
    const double phi = map.twist * s, c = std::cos(phi), sn = std::sin(phi);
    const glm::dmat2 m = glm::dmat2(c, sn, -sn, c) * glm::dmat2(1.0 / sx, 0.0, 0.0, 1.0 / sy);
    straightPrism(*outline, m * Vec2(o), m * Vec2(d), 0.0, 0.0, 0.0, 0.0, tlSpans);
    addWithinCapacity(tlSpans, out);
}

void Extrusion::frustumSpans(const Vec3& o, const Vec3& d, LocalSpans& out) const {
    const double h = z1 - z0;
    const double k = scale.x;  // uniform here
    const double kappa = (k - 1.0) / h;
    // The map is singular where s(z) = 0 (an apex): an origin near there moves along the line
    // to the mid-plane, where s(z) = (1 + k)/2 (with d.z = 0 the line stays at its height,
    // which the prism test below accepts or not). An origin elsewhere stays: the caller put it
    // close to the solid, where the rounding is smallest.
    const double sMid = 0.5 * (1.0 + k);
    double tm = 0.0;
    Vec3 om = o;
    if (d.z != 0.0 && !(1.0 + kappa * (o.z - z0) > 0.5 * sMid)) {
        tm = (0.5 * (z0 + z1) - o.z) / d.z;
        om = o + tm * d;
    }
    const double zeta = om.z - z0;
    const double wo = 1.0 + kappa * zeta;  // s at the origin used
    if (!(wo > 0.0)) return;
    const double wd = kappa * d.z;
    // The mapped line q(s) = om'/wo + s (d' - om' wd/wo), s = t / w(t).
    const double ratio = wd / wo;
    const Vec2 o2 = Vec2(om) / wo, d2 = Vec2(d) - Vec2(om) * ratio;
    const double zo = zeta / wo, zd = d.z - zeta * ratio;
    const double top = k > 0.0 ? h / k : kInfinity;
    straightPrism(*outline, o2, d2, zo, zd, 0.0, top, tlSpans);
    // Back to t: t = tm + s wo / (1 - s wd), on the branch where w > 0.
    const double sValidLo = wd < 0.0 ? 1.0 / wd : -kInfinity;
    const double sValidHi = wd > 0.0 ? 1.0 / wd : kInfinity;
    const auto toT = [&](double s) {
        if (std::isinf(s)) return wd != 0.0 ? tm - wo / wd : s;
        return tm + s * wo / (1.0 - s * wd);
    };
    std::vector<Entry>& mapped = tlMerged;
    mapped.clear();
    for (const Entry& e : tlSpans) {
        const double sIn = std::max(e.tIn, sValidLo), sOut = std::min(e.tOut, sValidHi);
        if (!(sIn <= sOut)) continue;
        mapped.push_back({toT(sIn), toT(sOut), sIn == e.tIn ? e.faceIn : kClipFace,
                          sOut == e.tOut ? e.faceOut : kClipFace});
    }
    addWithinCapacity(mapped, out);
}

void Extrusion::revolvedSpans(const Vec3& o, const Vec3& d, LocalSpans& out) const {
    double tlo = -kInfinity, thi = kInfinity;
    if (!clipToBox(SlabRay(o, d), bounds(), tlo, thi)) return;
    // Crossings on the box's own faces (a tube's tangent points) must survive rounding.
    const double margin =
        kCandidateSlackRel * (thi - tlo) + 1e-12 * (std::abs(tlo) + std::abs(thi));
    tlo -= margin, thi += margin;
    const Outline& profile = *outline;
    const double slack = kCandidateSlackRel * std::max(1.0, glm::length(box.hi - box.lo));
    // r(t)^2 = A t^2 + B t + C.
    const double A = d.x * d.x + d.y * d.y, B = 2.0 * (o.x * d.x + o.y * d.y),
                 C = o.x * o.x + o.y * o.y;
    const auto imageAt = [&](double t) {
        return Vec2(std::sqrt(std::max(0.0, (A * t + B) * t + C)), o.z + t * d.z);
    };
    std::vector<Candidate>& cand = tlCandidates;
    cand.clear();
    const auto keep = [&](double t, uint32_t i) {
        if (t >= tlo && t <= thi) cand.push_back({t, i});
    };
    double roots[Polynomial::kMaxDegree];
    const Polynomial r2{C, B, A};
    // A profile curve (x(u), z(u)), u in [0, 1], in its own parameter: where the line reaches
    // the curve's height z(u) its radius is sqrt(A tau^2 + B tau + C) with tau = (z(u) - o.z)
    // / d.z, a polynomial in u of twice the curve's degree. The range is widened a little so
    // that a line through a vertex is not lost between its two segments.
    const auto curveCandidates = [&](const Polynomial& x, const Polynomial& z, uint32_t i) {
        constexpr double lo = -kCandidateSlackRel, hi = 1.0 + kCandidateSlackRel;
        if (d.z != 0.0) {
            const Polynomial tau = sum(z, Polynomial{-o.z}).scaled(1.0 / d.z);
            const Polynomial h =
                sum(product(x, x),
                    sum(sum(product(tau, tau).scaled(A), tau.scaled(B)), Polynomial{C}), -1.0)
                    .trimmed();
            if (h.degree() == 0) return;
            const int found = solve(h, lo, hi, roots);
            for (int j = 0; j < found; ++j) keep(tau(roots[j]), i);
            return;
        }
        // A level line: where the curve reaches the line's height, r(u) gives two t,
        // symmetric about the line's point nearest the axis.
        const Polynomial level = sum(z, Polynomial{-o.z}).trimmed();
        if (level.degree() == 0) return;
        const int found = solve(level, lo, hi, roots);
        const double tc = -B / (2.0 * A), rmin2 = C - B * B / (4.0 * A);
        for (int j = 0; j < found; ++j) {
            const double r = x(roots[j]);
            const double half = std::sqrt(std::max(0.0, (r * r - rmin2) / A));
            keep(tc - half, i);
            keep(tc + half, i);
        }
    };
    // The line's image over [tlo, thi] lies in a box of the (r, z) half-plane; only segments
    // whose boxes meet it can be crossed.
    Bounds2 image;
    image.add(imageAt(tlo));
    image.add(imageAt(thi));
    if (A > 0.0) image.add(imageAt(std::clamp(-B / (2.0 * A), tlo, thi)));  // nearest the axis
    image.lo -= Vec2(slack), image.hi += Vec2(slack);
    profile.forSegmentsIn(image, [&](uint32_t i) {
        const Segment2& s = profile.segments[i];
        switch (s.kind) {
            case Segment2::Kind::Line: {
                const Vec2 a = s.p[0], e = s.p[1] - s.p[0];
                const Vec2 n(e.y, -e.x);
                if (std::abs(n.x) < std::abs(n.y)) {
                    // More level than steep: n_r is small and squaring below would lose the
                    // crossing (a level edge is a disc, n_r = 0); its own parameter is sound.
                    curveCandidates(Polynomial{a.x, e.x}, Polynomial{a.y, e.y}, i);
                    break;
                }
                // n . (r, z) = k, so n_r r = L(t) = L0 + L1 t; squared: a quadratic in t.
                const double k = glm::dot(n, a);
                const double l0 = k - n.y * o.z, l1 = -n.y * d.z, nr2 = n.x * n.x;
                double t0, t1;
                const int found = solveQuadratic(nr2 * A - l1 * l1, nr2 * B - 2.0 * l0 * l1,
                                                 nr2 * C - l0 * l0, t0, t1);
                const double ee = glm::dot(e, e);
                for (int j = 0; j < found; ++j) {
                    const double t = j == 0 ? t0 : t1;
                    const Vec2 q = imageAt(t);
                    const double u = ee > 0.0 ? glm::dot(q - a, e) / ee : 0.0;
                    if (u < -kCandidateSlackRel || u > 1.0 + kCandidateSlackRel) continue;
                    if (glm::distance(q, a + e * std::clamp(u, 0.0, 1.0)) > slack) continue;
                    keep(t, i);
                }
                break;
            }
            case Segment2::Kind::Arc: {
                // |P (q - c)| = 1 with q = (r, z): U(t) + r V(t) = 0, squared U^2 - r^2 V^2.
                const glm::dmat2 axes(s.p[2], s.p[3]);
                if (glm::determinant(axes) == 0.0) break;
                const glm::dmat2 P = glm::inverse(axes);
                const glm::dmat2 Q = glm::transpose(P) * P;
                const double qrr = Q[0][0], qrz = Q[1][0], qzz = Q[1][1];
                const double cr = s.p[1].x;
                const Polynomial zeta{o.z - s.p[1].y, d.z};
                const Polynomial U =
                    sum(sum(r2.scaled(qrr), product(zeta, zeta).scaled(qzz)),
                        sum(zeta.scaled(-2.0 * qrz * cr), Polynomial{qrr * cr * cr - 1.0}));
                const Polynomial V = sum(zeta.scaled(2.0 * qrz), Polynomial{-2.0 * qrr * cr});
                const Polynomial quartic =
                    sum(product(U, U), product(r2, product(V, V)), -1.0).trimmed();
                if (quartic.degree() == 0) break;
                const int found = solve(quartic, tlo, thi, roots);
                for (int j = 0; j < found; ++j) {
                    const Vec2 q = imageAt(roots[j]);
                    const Vec2 w = P * (q - s.p[1]);
                    if (std::abs(glm::length(w) - 1.0) > 1e3 * kCandidateSlackRel) continue;
                    const double u = profile.nearestParameter(i, q);
                    if (glm::distance(s.at(u), q) > slack) continue;
                    keep(roots[j], i);
                }
                break;
            }
            case Segment2::Kind::Quadratic:
            case Segment2::Kind::Cubic:
                curveCandidates(bezierCoordinate(s, 0), bezierCoordinate(s, 1), i);
                break;
        }
    });
    std::sort(cand.begin(), cand.end(),
              [](const Candidate& a, const Candidate& b) { return a.t < b.t; });
    // Each gap between consecutive candidates is inside or outside as its midpoint is.
    std::vector<Entry>& spansHere = tlSpans;
    spansHere.clear();
    for (size_t j = 0; j + 1 < cand.size(); ++j) {
        const double a = cand[j].t, b = cand[j + 1].t;
        if (!(a < b) || !profile.inside(imageAt(0.5 * (a + b)))) continue;
        if (!spansHere.empty() && spansHere.back().tOut == a)
            spansHere.back().tOut = b, spansHere.back().faceOut = sideFace(cand[j + 1].segment);
        else
            spansHere.push_back({a, b, sideFace(cand[j].segment), sideFace(cand[j + 1].segment)});
    }
    if (angle >= 360.0) {
        addWithinCapacity(spansHere, out);
        return;
    }
    // The wedge 0 <= azimuth <= angle: two half-planes through the axis, intersected (a
    // convex wedge) or united.
    const double rad = angle * kPi / 180.0;
    Entry h1, h2;
    const bool has1 = halfPlaneSpan(Vec2(0.0, 1.0), Vec2(o), Vec2(d), kWedgeStartFace, h1);
    const bool has2 =
        halfPlaneSpan(Vec2(std::sin(rad), -std::cos(rad)), Vec2(o), Vec2(d), kWedgeEndFace, h2);
    std::vector<Entry>& wedge = tlWedge;
    wedge.clear();
    if (angle <= 180.0) {
        if (has1 && has2) {
            const Entry& in = h1.tIn >= h2.tIn ? h1 : h2;
            const Entry& ex = h1.tOut <= h2.tOut ? h1 : h2;
            if (in.tIn <= ex.tOut) wedge.push_back({in.tIn, ex.tOut, in.faceIn, ex.faceOut});
        }
    } else if (has1 && has2) {
        const Entry& first = h1.tIn <= h2.tIn ? h1 : h2;
        const Entry& second = h1.tIn <= h2.tIn ? h2 : h1;
        if (second.tIn <= first.tOut) {
            const Entry& ex = first.tOut >= second.tOut ? first : second;
            wedge.push_back({first.tIn, ex.tOut, first.faceIn, ex.faceOut});
        } else {
            wedge.push_back(first);
            wedge.push_back(second);
        }
    } else if (has1 || has2) {
        wedge.push_back(has1 ? h1 : h2);
    }
    intersectSpans(spansHere, wedge, tlMerged);
    addWithinCapacity(tlMerged, out);
}

bool Extrusion::inside(const Vec3& p) const {
    if (!outline || box.empty()) return false;
    switch (kind) {
        case Kind::Plane:
            return outline->inside(Vec2(p));
        case Kind::Linear: {
            if (twisted) {
                Vec2 q;
                return twistMap().profilePoint(p, q) && outline->inside(q);
            }
            if (!(p.z >= z0 && p.z <= z1)) return false;
            const double s = 1.0 + (scale.x - 1.0) * (p.z - z0) / (z1 - z0);
            if (s <= 0.0) return false;  // the apex
            return outline->inside(Vec2(p) / s);
        }
        case Kind::Rotate: {
            if (angle < 360.0) {
                const double rad = angle * kPi / 180.0;
                const bool above = p.y >= 0.0;
                const bool before = std::sin(rad) * p.x - std::cos(rad) * p.y >= 0.0;
                if (angle <= 180.0 ? !(above && before) : !(above || before)) return false;
            }
            return outline->inside(Vec2(std::hypot(p.x, p.y), p.z));
        }
    }
    return false;
}

uint32_t Extrusion::segmentOf(uint16_t face, Vec2 q) const {
    const uint32_t first = face - kFirstSideFace;
    const uint32_t n = uint32_t(outline->segments.size());
    if (n <= kSideFaceIds) return std::min(first, n - 1);
    uint32_t best = first;
    double bestDist = kInfinity;
    for (uint32_t i = first; i < n; i += kSideFaceIds) {
        const double u = outline->nearestParameter(i, q);
        const double dist = glm::distance(outline->segments[i].at(u), q);
        if (dist < bestDist) bestDist = dist, best = i;
    }
    return best;
}

Vec3 Extrusion::normal(const Vec3& p, uint16_t face) const {
    if (!outline || outline->segments.empty()) return Vec3(0.0, 0.0, 1.0);
    switch (face) {
        case kBottomFace:
            return Vec3(0.0, 0.0, -1.0);
        case kTopFace:
            return Vec3(0.0, 0.0, 1.0);
        case kWedgeStartFace:
            return Vec3(0.0, -1.0, 0.0);
        case kWedgeEndFace: {
            const double rad = angle * kPi / 180.0;
            return Vec3(-std::sin(rad), std::cos(rad), 0.0);
        }
        default:
            break;
    }
    if (face == kClipFace) return Vec3(0.0, 0.0, 1.0);
    if (kind == Kind::Rotate) {
        const double r = std::hypot(p.x, p.y);
        const Vec2 q(r, p.z);
        const Vec2 n = outline->outwardNormal(segmentOf(face, q), q);
        if (r < 1e-300) return Vec3(0.0, 0.0, n.y >= 0.0 ? 1.0 : -1.0);
        return glm::normalize(Vec3(n.x * p.x / r, n.x * p.y / r, n.y));
    }
    if (kind == Kind::Linear && twisted) {
        const TwistMap map = twistMap();
        const Vec2 q = map.nearestProfilePoint(p);
        return map.normal(p, outline->outwardNormal(segmentOf(face, q), q));
    }
    if (kind == Kind::Linear && scale.x != 1.0) {
        // grad g(xy / s(z)) is parallel to (n, -kappa n . q) with q = xy / s.
        const double kappa = (scale.x - 1.0) / (z1 - z0);
        const double s = std::max(1.0 + kappa * (p.z - z0), 1e-300);
        const Vec2 q = Vec2(p) / s;
        const Vec2 n = outline->outwardNormal(segmentOf(face, q), q);
        return glm::normalize(Vec3(n, -kappa * glm::dot(n, q)));
    }
    const Vec2 q(p);
    return Vec3(outline->outwardNormal(segmentOf(face, q), q), 0.0);
}

void Extrusion::describe(JsonWriter& json) const {
    static constexpr const char* kKinds[] = {"2d", "linear_extrude", "rotate_extrude"};
    json.key("kind").value(kKinds[int(kind)]).key("shape").value(shape);
    json.key("segments").value(uint64_t(outline ? outline->segments.size() : 0));
    if (accuracy) json.key("accuracy").value(accuracy);
    if (kind == Kind::Linear) {
        json.key("z0").value(z0).key("z1").value(z1).key("scale");
        if (scale.x == scale.y)
            json.value(scale.x);
        else
            json.vec(scale, 2);
        if (twist != 0.0) json.key("twist").value(twist);
    }
    if (kind == Kind::Rotate) json.key("angle").value(angle);
}

}  // namespace csg
