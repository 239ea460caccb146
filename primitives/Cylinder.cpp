// Notation: t is the parameter of the line o + t d. The solid is the slab 0 <= z <= h cut by
// the quadric f(p) = x^2 + y^2 - (r1 + k z)^2 <= 0, k = (r2 - r1) / h: a cylinder when k == 0,
// otherwise a double cone whose apex lies outside the open slab, so inside the slab only the
// right nappe remains. s = t - tBase is the parameter from a base point b = o + tBase d
// chosen near the axis and inside the slab, so every quantity is of the size of the solid.
#include "primitives/Cylinder.h"

#include <algorithm>
#include <cmath>

#include "primitives/base/Fma.h"
#include "primitives/solvers/LinePoint.h"
#include "primitives/solvers/Quadratic.h"

namespace csg {

namespace {

constexpr uint16_t kLateral = 0, kBottom = 1, kTop = 2;

// A closed interval of s and the faces bounding it; empty when lo > hi.
struct Piece {
    double lo, hi;
    uint16_t faceLo, faceHi;
};

}  // namespace

Bounds3 Cylinder::bounds() const {
    const double r = std::max(r1, r2);
    return {Vec3(-r, -r, 0.0), Vec3(r, r, height)};
}

Bounds3 Cylinder::boundsUnder(const Mat4& m) const {
    // The image is the convex hull of two ellipses (the end discs), so its box is the hull of
    // their boxes. A disc c + r (cos a u + sin a v) reaches c_i +- r |(u_i, v_i)| on axis i.
    const Vec3 c0 = transformPoint(m, Vec3(0.0));
    const Vec3 c1 = transformPoint(m, Vec3(0.0, 0.0, height));
    Vec3 e;
    for (int i = 0; i < 3; ++i) e[i] = std::hypot(m[0][i], m[1][i]);
    return hull(Bounds3{c0 - r1 * e, c0 + r1 * e}, Bounds3{c1 - r2 * e, c1 + r2 * e});
}

void Cylinder::spans(const Vec3& o, const Vec3& d, LocalSpans& out) const {
    if (!(height > 0.0)) return;  // a flat cylinder has no volume (and would break the clamp)
    // Step 1: the slab as a t interval bounded by the caps. A line parallel to the caps (or so
    // nearly that t overflows) is inside the slab everywhere or nowhere.
    double tLo = -kInfinity, tHi = kInfinity;
    uint16_t capLo = kClipFace, capHi = kClipFace;
    const double tBottom = -o.z / d.z, tTop = (height - o.z) / d.z;
    const bool slabBounded = d.z != 0.0 && std::isfinite(tBottom) && std::isfinite(tTop);
    if (slabBounded) {
        const bool up = d.z > 0.0;
        tLo = up ? tBottom : tTop, capLo = up ? kBottom : kTop;
        tHi = up ? tTop : tBottom, capHi = up ? kTop : kBottom;
    } else if (o.z < 0.0 || o.z > height) {
        return;
    }

    // Step 2: the base point: the point of the line nearest the axis, clamped into the slab,
    // or the slab's middle for a line parallel to the axis. A line with no usable direction
    // is a point, which is no span.
    const double dxy2 = d.x * d.x + d.y * d.y;
    double tBase = dxy2 > 0.0 ? -(o.x * d.x + o.y * d.y) / dxy2 : 0.5 * tLo + 0.5 * tHi;
    if (slabBounded) tBase = std::clamp(tBase, tLo, tHi);
    if (!std::isfinite(tBase)) return;
    const Vec3 b = pointOnLine(o, d, tBase);

    // Step 3: f(s) = A s^2 + 2 B s + C along the line from b. A is formed with fma so a line
    // parallel to a generator gets A == 0 (the linear case below) whenever dxy2 and kdz are
    // exact, as for the axis-plane generators of exactly representable cones.
    const double k = (r2 - r1) / height;
    const double kdz = k * d.z;
    const double rb = r1 + k * b.z;  // the quadric's radius at b's height
    const double A = fusedMultiplyAdd(-kdz, kdz, dxy2);
    const double B = b.x * d.x + b.y * d.y - rb * kdz;
    const double C = b.x * b.x + b.y * b.y - rb * rb;

    // Step 4: the pieces of the line where f <= 0: one interval when A > 0, the outside of
    // the roots when A < 0 (the line crosses both nappes), a half-line when A == 0.
    Piece pieces[2];
    int count = 0;
    const Piece everywhere{-kInfinity, kInfinity, kClipFace, kClipFace};
    if (A == 0.0) {
        if (B == 0.0) {
            if (C > 0.0) return;
            pieces[count++] = everywhere;
        } else {
            const double root = -C / (2.0 * B);
            pieces[count++] = B > 0.0 ? Piece{-kInfinity, root, kClipFace, kLateral}
                                      : Piece{root, kInfinity, kLateral, kClipFace};
        }
    } else {
        double s0, s1;
        if (solveQuadratic(A, 2.0 * B, C, s0, s1) < 2) {
            if (A > 0.0) return;
            pieces[count++] = everywhere;
        } else if (A > 0.0) {
            pieces[count++] = {s0, s1, kLateral, kLateral};
        } else {
            pieces[count++] = {-kInfinity, s0, kClipFace, kLateral};
            pieces[count++] = {s1, kInfinity, kLateral, kClipFace};
        }
    }

    // Step 5: clip each piece to the slab and keep the hull. Exactly, the slab meets one
    // nappe only, so two pieces survive only by rounding at an apex on a cap.
    const double sLo = tLo - tBase, sHi = tHi - tBase;
    double sIn = kInfinity, sOut = -kInfinity;
    uint16_t faceIn = kClipFace, faceOut = kClipFace;
    for (int i = 0; i < count; ++i) {
        const Piece& p = pieces[i];
        const double lo = std::max(p.lo, sLo), hi = std::min(p.hi, sHi);
        if (lo > hi) continue;
        if (lo < sIn) sIn = lo, faceIn = p.lo > sLo ? p.faceLo : capLo;
        if (hi > sOut) sOut = hi, faceOut = p.hi < sHi ? p.faceHi : capHi;
    }
    if (sIn > sOut) return;

    // Step 6: back to t. Both ends are finite here (an unbounded slab only occurs with A > 0);
    // the check guards a d so tiny that the sum overflows.
    const double tIn = tBase + sIn, tOut = tBase + sOut;
    if (!std::isfinite(tIn) || !std::isfinite(tOut)) return;
    out.add(tIn, faceIn, tOut, faceOut);
}

bool Cylinder::inside(const Vec3& p) const {
    if (p.z < 0.0 || p.z > height) return false;
    // Interpolating from r1 with z / h <= 1 never overshoots r2, so r >= 0 on the slab.
    const double r = r1 + (r2 - r1) * (p.z / height);
    return p.x * p.x + p.y * p.y <= r * r;
}

Vec3 Cylinder::normal(const Vec3& p, uint16_t face) const {
    if (face == kBottom) return Vec3(0.0, 0.0, -1.0);
    if (face == kTop) return Vec3(0.0, 0.0, 1.0);
    // Lateral: the gradient of sqrt(x^2 + y^2) - r(z), scaled by h so a flat cone (h much
    // smaller than the radii) does not overflow. On the axis only an apex can be on the
    // surface; its normal is the axis pointing away from the base.
    const double rho = std::hypot(p.x, p.y);
    if (!(rho > 0.0)) return Vec3(0.0, 0.0, r2 <= r1 ? 1.0 : -1.0);
    return glm::normalize(Vec3(height * p.x / rho, height * p.y / rho, r1 - r2));
}

}  // namespace csg
