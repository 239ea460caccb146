// Notation (TwistedExtrusion.h): tau = t - tm, the line's image P(tau) / w(tau) in the profile
// plane, G = F(P, w) for one segment's carrier F. A piece is [a, b] of the chord, m its
// midpoint and r its half-width rounded up; a Frame holds P, w, v and their derivatives at one
// tau, in doubles (point evaluation) or intervals (enclosures).
#include "primitives/TwistedExtrusion.h"

#include <algorithm>
#include <cmath>

#include "primitives/Extrusion.h"
#include "primitives/base/Tolerances.h"
#include "primitives/solvers/Quadratic.h"

namespace csg {

namespace {

using Entry = LocalSpans::Entry;

struct Candidate {
    double tau;
    uint16_t face;
};
struct Piece {
    double a, b;
    int depth;
};

// Per-thread scratch, grown once and reused by every line (no allocation per ray).
thread_local std::vector<Candidate> tlCandidates;
thread_local std::vector<Piece> tlPieces;

uint16_t sideFace(uint32_t segment) {
    return uint16_t(Extrusion::kFirstSideFace + segment % Extrusion::kSideFaceIds);
}

Interval exactly(double v) {
    return pointInterval(v);
}

// The scalar operations the frame needs, for doubles and for intervals (csg::sqr of an
// interval is found by its argument's namespace).
double sqr(double x) {
    return x * x;
}
double cosOf(double x) {
    return std::cos(x);
}
double sinOf(double x) {
    return std::sin(x);
}
Interval cosOf(Interval x) {
    return enclosedCos(x);
}
Interval sinOf(Interval x) {
    return enclosedSin(x);
}
template <class T>
T affineAt(double a, double b, double tau);
template <>
double affineAt<double>(double a, double b, double tau) {
    return a + b * tau;
}
template <>
Interval affineAt<Interval>(double a, double b, double tau) {
    return exactly(a) + exactly(b) * tau;
}

// phi(tau) = phi0 + k tau, sigma_x(tau) = sx0 + sx1 tau, sigma_y likewise; v'' / 2 =
// (v2x, v2y) and w'' / 2 = w2 (zero when the scale is uniform, v and w being affine then).
template <class T>
struct LineConstants {
    T phi0, k, sx0, sx1, sy0, sy1;
    T v2x, v2y, w2;
};

// The line's image: x(tau) = ox + dx tau, y likewise, and the constants above both as
// enclosures of the exact values and as their nearest doubles.
struct ImageLine {
    double ox, oy, dx, dy;
    bool twisted, uniform;
    LineConstants<Interval> enclosed;
    LineConstants<double> nearest;
    // Bounds for the pieces, rounded up: |k| and the L1 norm of v''.
    double kAbs, ddvAbs;
    double pieceAngle;  // TwistedOutline::pieceAngle

    template <class T>
    const LineConstants<T>& constants() const;
};
template <>
const LineConstants<Interval>& ImageLine::constants<Interval>() const {
    return enclosed;
}
template <>
const LineConstants<double>& ImageLine::constants<double>() const {
    return nearest;
}

// The image at one tau: the homogeneous point Z = (P, w) and its first two derivatives.
template <class T>
struct Frame {
    T px, py, w;        // Z
    T dpx, dpy, dw;     // Z'
    T ddpx, ddpy, ddw;  // Z''
    T vx, vy;           // v
    T dvx, dvy;         // v'
};

template <class T>
Frame<T> frameAt(const ImageLine& line, double tau) {
    const LineConstants<T>& c = line.constants<T>();
    const T x = affineAt<T>(line.ox, line.dx, tau), y = affineAt<T>(line.oy, line.dy, tau);
    const T sx = c.sx0 + c.sx1 * tau;
    Frame<T> f;
    if (line.uniform) {
        f.vx = x, f.vy = y, f.w = sx;
        f.dvx = affineAt<T>(line.dx, 0.0, 0.0), f.dvy = affineAt<T>(line.dy, 0.0, 0.0);
        f.dw = c.sx1;
    } else {
        const T sy = c.sy0 + c.sy1 * tau;
        f.vx = x * sy, f.vy = y * sx, f.w = sx * sy;
        f.dvx = line.dx * sy + x * c.sy1;
        f.dvy = line.dy * sx + y * c.sx1;
        f.dw = c.sx1 * sy + sx * c.sy1;
    }
    const T ddvx = 2.0 * c.v2x, ddvy = 2.0 * c.v2y;
    f.ddw = 2.0 * c.w2;
    if (!line.twisted) {
        f.px = f.vx, f.py = f.vy, f.dpx = f.dvx, f.dpy = f.dvy, f.ddpx = ddvx, f.ddpy = ddvy;
        return f;
    }
    const T phi = c.phi0 + c.k * tau;
    const T cs = cosOf(phi), sn = sinOf(phi);
    // P = R v, P' = R (k J v + v'), P'' = R (-k^2 v + 2 k J v' + v''), J the quarter turn
    // (x, y) -> (-y, x).
    const T ux = f.dvx - c.k * f.vy, uy = f.dvy + c.k * f.vx;
    const T k2 = sqr(c.k), k2x = 2.0 * c.k;
    const T qx = ddvx - k2 * f.vx - k2x * f.dvy, qy = ddvy - k2 * f.vy + k2x * f.dvx;
    f.px = cs * f.vx - sn * f.vy;
    f.py = sn * f.vx + cs * f.vy;
    f.dpx = cs * ux - sn * uy;
    f.dpy = sn * ux + cs * uy;
    f.ddpx = cs * qx - sn * qy;
    f.ddpy = sn * qx + cs * qy;
    return f;
}

// Enclosures of Z and its first two derivatives over the piece [m - r, m + r], from the frame
// at m and bounds on the next derivative: |P'| <= |k| |v| + |v'|, |P''| <= k^2 |v| +
// 2 |k| |v'| + |v''| and |P'''| <= |k|^3 |v| + 3 k^2 |v'| + 3 |k| |v''| (v''' = 0), with |v|
// and |v'| bounded over the piece by Taylor's formula (v is a quadratic), all in L1 norms,
// which bound the Euclidean ones; w is a quadratic, enclosed exactly.
struct PieceBox {
    Interval px, py, w, dpx, dpy, dw, ddpx, ddpy, ddw;
};
PieceBox pieceBox(const ImageLine& line, const Frame<Interval>& f, double r) {
    const Interval rr = exactly(r);
    const Interval vAbs = exactly(f.vx.magnitude()) + exactly(f.vy.magnitude());
    const Interval dvAbs = exactly(f.dvx.magnitude()) + exactly(f.dvy.magnitude());
    const Interval ddv = exactly(line.ddvAbs), k = exactly(line.kAbs);
    const Interval vMax = vAbs + rr * dvAbs + 0.5 * (sqr(rr) * ddv);
    const Interval dvMax = dvAbs + rr * ddv;
    const double p1 = (rr * (k * vMax + dvMax)).hi;
    const double p2 = (rr * (sqr(k) * vMax + 2.0 * (k * dvMax) + ddv)).hi;
    const double p3 = (rr * (sqr(k) * k * vMax + 3.0 * (sqr(k) * dvMax) + 3.0 * (k * ddv))).hi;
    const Interval& w2 = line.enclosed.w2;
    PieceBox b;
    b.px = f.px + plusMinus(p1);
    b.py = f.py + plusMinus(p1);
    b.dpx = f.dpx + plusMinus(p2);
    b.dpy = f.dpy + plusMinus(p2);
    b.ddpx = f.ddpx + plusMinus(p3);
    b.ddpy = f.ddpy + plusMinus(p3);
    // w(m + e) = w(m) + e w'(m) + e^2 w2, exactly.
    b.w = f.w + plusMinus(r) * f.dw + Interval{0.0, up(r * r)} * w2;
    b.dw = f.dw + plusMinus(r) * (2.0 * w2);
    b.ddw = f.ddw;
    return b;
}

// Whether the profile points P / w, w > 0, of a box may lie in the segment's box (a NaN bound
// says they may).
bool mayMeetBox(const PieceBox& b, const Bounds2& box) {
    return overlaps(b.px, b.w * Interval{box.lo.x, box.hi.x}) &&
           overlaps(b.py, b.w * Interval{box.lo.y, box.hi.y});
}

// G, G' and G'' from a frame (G' = grad F . Z', G'' = grad F . Z'' + Z'^T Hess(F) Z').
template <class T>
T valueOf(const SegmentCarrier& c, const Frame<T>& f) {
    return carrierValue(c, f.px, f.py, f.w);
}
template <class T>
T slopeOf(const SegmentCarrier& c, const Frame<T>& f) {
    T g[3];
    carrierGradient(c, f.px, f.py, f.w, g);
    return g[0] * f.dpx + g[1] * f.dpy + g[2] * f.dw;
}
template <class T>
T curvatureOf(const SegmentCarrier& c, const Frame<T>& f, const T g[3]) {
    return g[0] * f.ddpx + g[1] * f.ddpy + g[2] * f.ddw +
           carrierCurvature(c, f.px, f.py, f.w, f.dpx, f.dpy, f.dw);
}

// A piece and what every segment's test reads of it: the frame at its midpoint and the
// enclosures over it (segment-independent, so the first pieces' are computed once per line).
struct PieceData {
    double a, b, r;
    Frame<Interval> mid;
    PieceBox box;
};
PieceData pieceData(const ImageLine& line, double a, double b) {
    PieceData p;
    p.a = a, p.b = b;
    const double m = a + 0.5 * (b - a);
    p.r = up(std::max(m - a, b - m));
    p.mid = frameAt<Interval>(line, m);
    p.box = pieceBox(line, p.mid, p.r);
    return p;
}

// The root in [a, b], where G has the proven sign signA at a and the opposite at b, and no
// other root: Newton steps, each replaced by bisection when it leaves the bracket, until a step
// or the bracket is below the resolution of t.
double polish(const SegmentCarrier& c, const ImageLine& line, double a, double b, int signA,
              double tm) {
    const double resolution =
        tol::kSweepRootStepUlps * tol::kUlp * (std::abs(tm) + std::max(std::abs(a), std::abs(b)));
    double x = a + 0.5 * (b - a);
    for (int i = 0; i < tol::kSweepNewtonIterations; ++i) {
        const Frame<double> f = frameAt<double>(line, x);
        const double g = valueOf(c, f);
        if (g == 0.0) return x;
        if ((g > 0.0) == (signA > 0))
            a = x;
        else
            b = x;
        double next = x - g / slopeOf(c, f);
        if (!(next > a && next < b)) next = a + 0.5 * (b - a);
        if (std::abs(next - x) <= resolution || b - a <= resolution) return next;
        x = next;
    }
    return x;
}

// Where G' vanishes in [a, b] when G'' keeps one sign there (so G' is monotone): Newton on G',
// safeguarded by bisection on its sign, a few steps. Only a split point: any value in (a, b)
// is correct, a near one saves work.
double turningPoint(const SegmentCarrier& c, const ImageLine& line, double a, double b) {
    const auto slopeAt = [&](double x, double* curvature) {
        const Frame<double> f = frameAt<double>(line, x);
        double g[3];
        carrierGradient(c, f.px, f.py, f.w, g);
        if (curvature) *curvature = curvatureOf(c, f, g);
        return g[0] * f.dpx + g[1] * f.dpy + g[2] * f.dw;
    };
    const double sa = slopeAt(a, nullptr), sb = slopeAt(b, nullptr);
    if (!((sa < 0.0 && sb > 0.0) || (sa > 0.0 && sb < 0.0))) return a + 0.5 * (b - a);
    const bool rising = sb > 0.0;
    double x = a + (b - a) * (sa / (sa - sb));
    for (int i = 0; i < tol::kSweepTurnIterations; ++i) {
        double curvature;
        const double s = slopeAt(x, &curvature);
        if ((s > 0.0) == rising)
            b = x;
        else
            a = x;
        double next = x - s / curvature;
        if (!(next > a && next < b)) next = a + 0.5 * (b - a);
        x = next;
    }
    return x;
}

// Adds tau as a candidate of segment i when its profile point lies in the keep box.
void keepIfOnSegment(const ImageLine& line, double tau, const Bounds2& keep, uint32_t i,
                     std::vector<Candidate>& out) {
    const Frame<double> f = frameAt<double>(line, tau);
    if (!(f.w > 0.0)) return;
    const Vec2 q(f.px / f.w, f.py / f.w);
    if (q.x >= keep.lo.x && q.x <= keep.hi.x && q.y >= keep.lo.y && q.y <= keep.hi.y)
        out.push_back({tau, sideFace(i)});
}

// One segment's crossings in [a, b] where G has at most one root: a proven sign change
// brackets exactly one, which is polished; an end of unprovable sign is a root to within
// rounding; equal proven signs mean none.
void bracketed(const SegmentCarrier& c, const Bounds2& keep, uint32_t i, const ImageLine& line,
               double a, double b, int sa, int sb, double tm, std::vector<Candidate>& out) {
    if (sa * sb < 0) {
        keepIfOnSegment(line, polish(c, line, a, b, sa, tm), keep, i, out);
        return;
    }
    if (sa == 0) out.push_back({a, sideFace(i)});
    if (sb == 0) out.push_back({b, sideFace(i)});
}

// One segment against one piece (header): returns where to split the piece, or NaN when it is
// decided. Crossings found are appended to out. endA and endB are the frames at the piece's
// ends when known.
double examine(const SegmentCarrier& c, const Bounds2& keep, uint32_t i, const ImageLine& line,
               const PieceData& p, int depth, const Frame<Interval>* endA,
               const Frame<Interval>* endB, double tm, std::vector<Candidate>& out) {
    constexpr double kDecided = std::numeric_limits<double>::quiet_NaN();
    // Step 1: the image misses the segment's box, or G stays off 0 (mean value form, and the
    // direct enclosure over the box): no crossing of this segment here.
    if (!mayMeetBox(p.box, c.box)) return kDecided;
    const Interval gm = valueOf(c, p.mid);
    Interval grad[3];
    carrierGradient(c, p.box.px, p.box.py, p.box.w, grad);
    const Interval slope = grad[0] * p.box.dpx + grad[1] * p.box.dpy + grad[2] * p.box.dw;
    if (provenSign(gm + plusMinus(p.r) * slope) != 0) return kDecided;
    if (provenSign(carrierValue(c, p.box.px, p.box.py, p.box.w)) != 0) return kDecided;
    const auto signAt = [&](const Frame<Interval>* known, double tau) {
        return provenSign(valueOf(c, known ? *known : frameAt<Interval>(line, tau)));
    };
    // Step 2: G monotone: at most one root.
    if (provenSign(slope) != 0) {
        bracketed(c, keep, i, line, p.a, p.b, signAt(endA, p.a), signAt(endB, p.b), tm, out);
        return kDecided;
    }
    // Step 3: G convex (bend +1) or concave (-1) over the piece: G' is monotone, so G turns at
    // most once, at u, and its tangent at u bounds it from below (above). When G(u) has the
    // sign -bend, each side of u holds exactly one root if its end has the sign bend, and none
    // if its end has -bend (G keeps -bend between two such points).
    const Interval curvature =
        grad[0] * p.box.ddpx + grad[1] * p.box.ddpy + grad[2] * p.box.ddw +
        carrierCurvature(c, p.box.px, p.box.py, p.box.w, p.box.dpx, p.box.dpy, p.box.dw);
    const int bend = provenSign(curvature);
    const double u = bend != 0 ? turningPoint(c, line, p.a, p.b) : p.a + 0.5 * (p.b - p.a);
    if (bend != 0 && u > p.a && u < p.b) {
        const Frame<Interval> fu = frameAt<Interval>(line, u);
        const Interval gu = valueOf(c, fu), su = slopeOf(c, fu);
        const Interval atA = gu + (exactly(p.a) - u) * su, atB = gu + (exactly(p.b) - u) * su;
        if (provenSign(atA) == bend && provenSign(atB) == bend) return kDecided;
        if (provenSign(gu) == -bend) {
            bracketed(c, keep, i, line, p.a, u, signAt(endA, p.a), -bend, tm, out);
            bracketed(c, keep, i, line, u, p.b, -bend, signAt(endB, p.b), tm, out);
            return kDecided;
        }
    }
    // Step 4: undecided. Split (at the turn when there is one), unless G's enclosure is
    // rounding noise (the width of its value at m is as large as the slope's contribution, so
    // splitting cannot exclude more), the depth bound is reached or the piece has no interior
    // double: then the piece is a cluster, its ends candidates.
    const double m = p.a + 0.5 * (p.b - p.a);
    const double at = depth < tol::kSweepTurnSplitDepth && u > p.a && u < p.b ? u : m;
    if (depth < tol::kSweepMaxDepth && p.r * slope.magnitude() > gm.hi - gm.lo && at > p.a &&
        at < p.b)
        return at;
    out.push_back({p.a, sideFace(i)});
    out.push_back({p.b, sideFace(i)});
    return kDecided;
}

// The first pieces of a line's chord, shared by all segments: each piece's data and the
// indices of the frames at its ends.
struct FirstPiece {
    PieceData data;
    uint32_t endA, endB;
};
thread_local std::vector<Frame<Interval>> tlEnds;
thread_local std::vector<FirstPiece> tlFirst;

// Appends the first pieces of [ta, tb], over which phi turns by at most
// TwistedOutline::pieceAngle each (while there are at most tol::kSweepMaxFirstPieces).
void addFirstPieces(const ImageLine& line, double ta, double tb) {
    const double turns = line.kAbs * (tb - ta) / line.pieceAngle;
    const int n = std::isfinite(turns)
                      ? int(std::clamp(std::ceil(turns), 1.0, double(tol::kSweepMaxFirstPieces)))
                      : tol::kSweepMaxFirstPieces;
    double a = ta;
    tlEnds.push_back(frameAt<Interval>(line, ta));
    for (int j = 1; j <= n; ++j) {
        const double b = j == n ? tb : ta + (tb - ta) * (double(j) / n);
        tlEnds.push_back(frameAt<Interval>(line, b));
        const uint32_t end = uint32_t(tlEnds.size() - 1);
        tlFirst.push_back({pieceData(line, a, b), end - 1, end});
        a = b;
    }
}

// The crossings of segment i's swept surface over the first pieces, by subdivision (header).
void isolate(const SegmentCarrier& c, const Bounds2& keep, uint32_t i, const ImageLine& line,
             double tm, std::vector<Candidate>& out) {
    std::vector<Piece>& stack = tlPieces;
    int budget = tol::kSweepMaxPieces;
    for (const FirstPiece& piece : tlFirst) {
        const PieceData& first = piece.data;
        const double split =
            examine(c, keep, i, line, first, 0, &tlEnds[piece.endA], &tlEnds[piece.endB], tm, out);
        if (std::isnan(split)) continue;
        // Parts, depth first, the lower first so that crossings come out ascending.
        stack.clear();
        stack.push_back({split, first.b, 1});
        stack.push_back({first.a, split, 1});
        while (!stack.empty()) {
            const Piece p = stack.back();
            stack.pop_back();
            if (--budget < 0) {
                out.push_back({p.a, sideFace(i)});
                out.push_back({p.b, sideFace(i)});
                continue;
            }
            const PieceData data = pieceData(line, p.a, p.b);
            const double at = examine(c, keep, i, line, data, p.depth, nullptr, nullptr, tm, out);
            if (std::isnan(at)) continue;
            stack.push_back({at, p.b, p.depth + 1});
            stack.push_back({p.a, at, p.depth + 1});
        }
    }
}

// Without twist and with sx != sy, a line's G = a v_x + b v_y + c w is a quadratic in tau.
void straightCrossings(const SegmentCarrier& c, const Bounds2& keep, uint32_t i,
                       const ImageLine& line, double ta, double tb, std::vector<Candidate>& out) {
    const LineConstants<double>& k = line.nearest;
    const double a = c.mid[0], b = c.mid[1], cw = c.mid[2];
    const double vx[3] = {line.ox * k.sy0, line.ox * k.sy1 + line.dx * k.sy0, line.dx * k.sy1};
    const double vy[3] = {line.oy * k.sx0, line.oy * k.sx1 + line.dy * k.sx0, line.dy * k.sx1};
    const double w[3] = {k.sx0 * k.sy0, k.sx0 * k.sy1 + k.sx1 * k.sy0, k.sx1 * k.sy1};
    double q[3];
    for (int j = 0; j < 3; ++j) q[j] = a * vx[j] + b * vy[j] + cw * w[j];
    double r0, r1;
    const int n = solveQuadratic(q[2], q[1], q[0], r0, r1);
    for (int j = 0; j < n; ++j) {
        const double tau = j == 0 ? r0 : r1;
        if (tau >= ta && tau <= tb) keepIfOnSegment(line, tau, keep, i, out);
    }
}

// Whether the profile point of a frame is in the region (a degenerate section holds nothing).
bool insideAt(const Frame<double>& f, const Outline& outline) {
    if (!(f.w > 0.0)) return false;
    return outline.inside(Vec2(f.px / f.w, f.py / f.w));
}

// R(twist s) (p.x / sx, p.y / sy).
Vec2 turned(double twist, double s, double sx, double sy, const Vec3& p) {
    const Vec2 w(p.x / sx, p.y / sy);
    if (twist == 0.0) return w;
    const double phi = twist * s, c = std::cos(phi), sn = std::sin(phi);
    return Vec2(c * w.x - sn * w.y, sn * w.x + c * w.y);
}

}  // namespace

bool TwistMap::profilePoint(const Vec3& p, Vec2& q) const {
    if (!(p.z >= z0 && p.z <= z1)) return false;
    const double s = (p.z - z0) / (z1 - z0);
    const double sx = 1.0 + (scale.x - 1.0) * s, sy = 1.0 + (scale.y - 1.0) * s;
    if (!(sx > 0.0 && sy > 0.0)) return false;
    q = turned(twist, s, sx, sy, p);
    return true;
}

Vec2 TwistMap::nearestProfilePoint(const Vec3& p) const {
    const double s = std::clamp((p.z - z0) / (z1 - z0), 0.0, 1.0);
    const double sx = std::max(1.0 + (scale.x - 1.0) * s, 1e-300);
    const double sy = std::max(1.0 + (scale.y - 1.0) * s, 1e-300);
    return turned(twist, s, sx, sy, p);
}

Vec3 TwistMap::normal(const Vec3& p, Vec2 n2) const {
    // q = R(phi) w, w = (x / sigma_x, y / sigma_y): dq/dx = R (1 / sigma_x, 0), dq/dy =
    // R (0, 1 / sigma_y), dq/dz = R (phi' J w + dw/dz), so with m = R^T n2 the gradient is
    // (m.x / sigma_x, m.y / sigma_y, m . (phi' J w + dw/dz)).
    const double h = z1 - z0;
    const double s = std::clamp((p.z - z0) / h, 0.0, 1.0);
    const double sx = std::max(1.0 + (scale.x - 1.0) * s, 1e-300);
    const double sy = std::max(1.0 + (scale.y - 1.0) * s, 1e-300);
    const double phi = twist * s, c = std::cos(phi), sn = std::sin(phi);
    const Vec2 m(c * n2.x + sn * n2.y, -sn * n2.x + c * n2.y);
    const Vec2 w(p.x / sx, p.y / sy);
    const double dphi = twist / h;
    const Vec2 dw(-w.x * (scale.x - 1.0) / (h * sx), -w.y * (scale.y - 1.0) / (h * sy));
    const Vec3 g(m.x / sx, m.y / sy, glm::dot(m, dphi * Vec2(-w.y, w.x) + dw));
    const double len = glm::length(g);
    if (!(len > 0.0) || !std::isfinite(len)) return Vec3(0.0, 0.0, 1.0);
    return g / len;
}

double TwistMap::boundingRadius(const Bounds2& box) const {
    double r = 0.0;
    for (const Vec2 corner : {box.lo, box.hi, Vec2(box.lo.x, box.hi.y), Vec2(box.hi.x, box.lo.y)})
        r = std::max(r, std::hypot(corner.x, corner.y));
    return r * std::max({1.0, scale.x, scale.y}) * (1.0 + tol::kSweepBoundsMarginRel);
}

std::shared_ptr<const TwistedOutline> TwistedOutline::of(const Outline& outline) {
    auto prepared = std::make_shared<TwistedOutline>();
    prepared->carriers.reserve(outline.segments.size());
    for (const Segment2& s : outline.segments) {
        SegmentCarrier c = SegmentCarrier::of(s);
        // The exact box is widened outward by rounding's reach (an ellipse's box comes from
        // hypot, within an ulp); the keep box further by the candidate slack.
        if (!c.box.empty()) {
            c.box.lo = Vec2(down(down(c.box.lo.x)), down(down(c.box.lo.y)));
            c.box.hi = Vec2(up(up(c.box.hi.x)), up(up(c.box.hi.y)));
        }
        Bounds2 keep = c.box;
        if (!keep.empty()) {
            const Vec2 size = keep.hi - keep.lo;
            const double reach = std::max({std::abs(keep.lo.x), std::abs(keep.lo.y),
                                           std::abs(keep.hi.x), std::abs(keep.hi.y)});
            const double slack = tol::kSweepCandidateSlackRel * (std::max(size.x, size.y) + reach);
            keep.lo -= Vec2(slack), keep.hi += Vec2(slack);
        }
        prepared->straight = prepared->straight && c.kind != SegmentCarrier::Kind::Ellipse &&
                             c.kind != SegmentCarrier::Kind::Parabola &&
                             c.kind != SegmentCarrier::Kind::Cubic;
        prepared->carriers.push_back(c);
        prepared->keepBoxes.push_back(keep);
    }
    // The radii of the region's box: its farthest corner, and its distance from the origin
    // (0 when it holds the origin), rounded outward.
    const Bounds2 box = outline.bounds();
    if (!box.empty()) {
        for (const Vec2 corner :
             {box.lo, box.hi, Vec2(box.lo.x, box.hi.y), Vec2(box.hi.x, box.lo.y)})
            prepared->outerRadius =
                std::max(prepared->outerRadius, up(std::hypot(corner.x, corner.y)));
        const Vec2 nearest = glm::clamp(Vec2(0.0), box.lo, box.hi);
        prepared->innerRadius = down(std::hypot(nearest.x, nearest.y));
    }
    // The first pieces' angle: a piece's image sweeps about one segment's extent at the outer
    // radius (the median segment's), so that a segment meets few pieces and splits them little.
    std::vector<double> extents;
    for (const SegmentCarrier& c : prepared->carriers)
        if (!c.box.empty())
            extents.push_back(std::max(c.box.hi.x - c.box.lo.x, c.box.hi.y - c.box.lo.y));
    if (!extents.empty() && prepared->outerRadius > 0.0) {
        const auto median = extents.begin() + std::ptrdiff_t(extents.size() / 2);
        std::nth_element(extents.begin(), median, extents.end());
        prepared->pieceAngle = std::clamp(*median / prepared->outerRadius, tol::kSweepMinPieceAngle,
                                          tol::kSweepPieceAngle);
    }
    return prepared;
}

bool twistedSpans(const Outline& outline, const TwistedOutline& prepared, const TwistMap& map,
                  const Vec3& o, const Vec3& d, double lo, double hi, std::vector<Entry>& out) {
    out.clear();
    if (d.z == 0.0) return false;
    const double h = map.z1 - map.z0;

    // Step 1: the chord, the slab cut by the annulus of the sections' radii and by the stretch
    // read (from o, which the caller has put near the solid, so that a nearly level line's
    // far-off slab ends cost no precision), and tau from its middle.
    double ta = (map.z0 - o.z) / d.z, tb = (map.z1 - o.z) / d.z;
    uint16_t fa = Extrusion::kBottomFace, fb = Extrusion::kTopFace;
    if (d.z < 0.0) std::swap(ta, tb), std::swap(fa, fb);
    if (lo > ta) ta = lo, fa = kClipFace;
    const bool cutAtHi = hi < tb;
    if (cutAtHi) tb = hi, fb = kClipFace;
    const double outer = prepared.outerRadius * std::max({1.0, map.scale.x, map.scale.y}) *
                         (1.0 + tol::kSweepBoundsMarginRel);
    const double inner = prepared.innerRadius * std::min({1.0, map.scale.x, map.scale.y}) *
                         (1.0 - tol::kSweepBoundsMarginRel);
    const double A = d.x * d.x + d.y * d.y, B = 2.0 * (o.x * d.x + o.y * d.y),
                 C = o.x * o.x + o.y * o.y;
    double hole0 = kInfinity, hole1 = -kInfinity;  // the line inside the inner cylinder
    if (A == 0.0) {
        if (C > outer * outer || C < inner * inner) return cutAtHi;
    } else {
        double c0, c1;
        if (solveQuadratic(A, B, C - outer * outer, c0, c1) < 2) return cutAtHi;
        if (c0 > ta) ta = c0, fa = kClipFace;
        if (c1 < tb) tb = c1, fb = kClipFace;
        if (inner > 0.0 && solveQuadratic(A, B, C - inner * inner, c0, c1) == 2)
            hole0 = std::max(c0, ta), hole1 = std::min(c1, tb);
    }
    if (!(ta < tb)) return cutAtHi;
    const double tm = ta + 0.5 * (tb - ta);
    const Vec3 om = o + tm * d;
    ta -= tm, tb -= tm;
    const bool hole = hole0 < hole1;
    if (hole) hole0 -= tm, hole1 -= tm;

    // Step 2: the image line's constants, enclosed and nearest.
    ImageLine line;
    line.ox = om.x, line.oy = om.y, line.dx = d.x, line.dy = d.y;
    line.twisted = map.twist != 0.0;
    line.uniform = map.uniform();
    const Interval zeta0 = exactly(om.z) - map.z0;
    const Interval ex = exactly(map.scale.x) - 1.0, ey = exactly(map.scale.y) - 1.0;
    LineConstants<Interval>& e = line.enclosed;
    e.phi0 = map.twist * zeta0 / h;
    e.k = exactly(map.twist) * d.z / h;
    e.sx0 = 1.0 + ex * zeta0 / h;
    e.sx1 = ex * d.z / h;
    e.sy0 = 1.0 + ey * zeta0 / h;
    e.sy1 = ey * d.z / h;
    if (line.uniform) {
        e.v2x = e.v2y = e.w2 = Interval{0.0, 0.0};
    } else {
        e.v2x = d.x * e.sy1;
        e.v2y = d.y * e.sx1;
        e.w2 = e.sx1 * e.sy1;
    }
    const auto nearest = [](Interval v) { return v.lo + 0.5 * (v.hi - v.lo); };
    line.nearest = {nearest(e.phi0), nearest(e.k),   nearest(e.sx0), nearest(e.sx1), nearest(e.sy0),
                    nearest(e.sy1),  nearest(e.v2x), nearest(e.v2y), nearest(e.w2)};
    line.kAbs = line.twisted ? e.k.magnitude() : 0.0;
    line.pieceAngle = prepared.pieceAngle;
    line.ddvAbs = (2.0 * (exactly(e.v2x.magnitude()) + e.v2y.magnitude())).hi;

    // Step 3: the candidates: the chord's ends and every segment's crossings.
    std::vector<Candidate>& cand = tlCandidates;
    cand.clear();
    cand.push_back({ta, fa});
    cand.push_back({tb, fb});
    // Without twist, straight edges are quadratics: the pieces are for the curved ones.
    const bool quadraticLines = !line.twisted && !line.uniform;
    tlEnds.clear();
    tlFirst.clear();
    if (hole) {
        // The solid lies outside the inner cylinder: its ends are candidates (the gap between
        // them is outside), and the pieces lie on either side of it.
        cand.push_back({hole0, kClipFace});
        cand.push_back({hole1, kClipFace});
    }
    if (!quadraticLines || !prepared.straight) {
        if (!hole) {
            addFirstPieces(line, ta, tb);
        } else {
            if (ta < hole0) addFirstPieces(line, ta, hole0);
            if (hole1 < tb) addFirstPieces(line, hole1, tb);
        }
    }
    for (uint32_t i = 0; i < prepared.carriers.size(); ++i) {
        const SegmentCarrier& c = prepared.carriers[i];
        if (c.kind == SegmentCarrier::Kind::None) continue;
        if (quadraticLines && c.kind == SegmentCarrier::Kind::Line)
            straightCrossings(c, prepared.keepBoxes[i], i, line, ta, tb, cand);
        else
            isolate(c, prepared.keepBoxes[i], i, line, tm, cand);
    }
    std::sort(cand.begin(), cand.end(),
              [](const Candidate& x, const Candidate& y) { return x.tau < y.tau; });

    // Step 4: each gap between consecutive candidates inside the chord is inside or outside
    // as its midpoint is.
    for (size_t j = 0; j + 1 < cand.size(); ++j) {
        const double a = cand[j].tau, b = cand[j + 1].tau;
        if (!(a < b) || a < ta || b > tb) continue;
        if (!insideAt(frameAt<double>(line, a + 0.5 * (b - a)), outline)) continue;
        const double tIn = tm + a, tOut = tm + b;
        if (!out.empty() && out.back().tOut == tIn)
            out.back().tOut = tOut, out.back().faceOut = cand[j + 1].face;
        else
            out.push_back({tIn, tOut, cand[j].face, cand[j + 1].face});
    }
    return cutAtHi;
}

}  // namespace csg
