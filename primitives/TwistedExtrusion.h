// linear_extrude with twist and a scale per axis (primitives/Extrusion.h, kind Linear): the
// spans of a line through the exact solid, its point test and its normals.
//
// Notation. The solid spans z0 <= z <= z1, h = z1 - z0; a point's height fraction is
// s = (z - z0) / h. Its section at s is S(s) R(-theta s) P, OpenSCAD's layer (OPENSCAD.md
// section 3): P the outline's region, R the counter-clockwise rotation (so a positive twist
// theta turns clockwise seen from +z), S(s) = diag(sigma_x, sigma_y) with
// sigma_a(s) = 1 + (scale_a - 1) s >= 0. So a point is inside iff its profile point
//   q = R(theta s) (x / sigma_x, y / sigma_y)
// is in P. Along the line o + t d, tau = t - tm counts from the middle of the line's chord
// through the solid's bounds, and q(tau) = P(tau) / w(tau) in homogeneous coordinates:
//   P = R(phi) v,   phi = theta s,   v = (x sigma_y, y sigma_x),   w = sigma_x sigma_y
// (v = (x, y) and w = sigma when the scale is uniform). phi, x, y and sigma are affine in tau,
// so v and w are quadratics and P is a quadratic turned by a uniformly turning rotation: no
// division, smooth through sigma = 0 (scale 0 makes an apex or an edge at the top).
//
// Crossings. Segment i of the outline lies on a carrier curve F_i = 0 (primitives/
// SegmentCarrier.h: its line, ellipse, parabola or implicit cubic), so the line meets the
// surface that segment sweeps where G_i(tau) = F_i(P(tau), w(tau)) = 0, a transcendental
// function (for an edge: A(tau) cos phi + B(tau) sin phi - C(tau), A, B, C quadratics).
// Its roots in the chord (the line inside the slab and the annulus that holds every section)
// are isolated by
// subdivision with proven enclosures:
//   - the chord is cut into first pieces over which phi turns by at most
//     TwistedOutline::pieceAngle (about a segment's extent over the outer radius, within
//     tol::kSweepMinPieceAngle and tol::kSweepPieceAngle); a piece [m - r, m + r] gets enclosures
//     of P, w and their derivatives from interval arithmetic at m (outward rounding, libm's cos and
//     sin within their documented error, the carrier's coefficients enclosing the exact ones) and
//     Taylor bounds over the piece from the closed-form derivatives
//       P' = R(phi)(k J v + v'),  P'' = R(phi)(-k^2 v + 2 k J v' + v''),  k = dphi/dtau,
//     and P''' likewise (v''' = 0);
//   - a piece is dropped only when it provably holds no crossing of the segment: the enclosure
//     of G excludes 0, or the enclosure of q misses the segment's box;
//   - a piece whose enclosure of G' excludes 0 holds at most one root, and exactly one when
//     G has provably opposite signs at its ends: Newton's method, safeguarded by bisection,
//     polishes it inside that bracket (it is kept when its point lies in the segment's box
//     widened by tol::kSweepCandidateSlackRel). An end where G's sign cannot be proven is a
//     root to within rounding and becomes a candidate itself;
//   - a piece whose enclosure of G'' excludes 0 (G convex or concave: the line passes a
//     segment's curve, entering and leaving it) turns at most once, at u: the tangent at u
//     bounds G from one side, which may prove the piece empty, and when G(u) has the proven
//     sign opposite to the curvature's, each side of u holds exactly one root or none, as its
//     end's sign says;
//   - any other piece is split (at u while shallow), until it is decided, G's enclosure over
//     it is rounding noise, or tol::kSweepMaxDepth / tol::kSweepMaxPieces is reached: then
//     both its ends become candidates (a tangency or a cluster, exact to the piece's width).
// Without twist and with sx != sy a straight edge's G is a quadratic in tau: solved exactly.
//
// The guarantee (for the segments' doubles, the map's doubles and the line o + t d as given):
// every crossing of a side surface in the chord, i.e. every root of a G_i whose profile point
// is on segment i, has a candidate within a bracket of rounding width: a polished root is
// inside the piece where G's sign was proven on both sides of it, and within G's evaluation
// noise of the computed zero; a piece left undecided gives both its ends. Pieces are dropped
// only on proofs (no NaN bound proves anything), and a polished root is dropped only when its
// point lies outside the segment's box by more than the slack (10^6 times its error). So
// region membership is constant on every gap between consecutive candidates except within
// those brackets of its ends. The candidates, with the chord's ends (the bottom and top faces,
// or the annulus that holds every section, outside the solid), are sorted, and each gap is
// classified by the outline's own point test (Outline::inside) at its midpoint, as the Rotate
// kind does: a spurious, double or repeated candidate only adds a gap classified like its
// neighbours, and only a gap no longer than its end brackets (a sliver at a tangency) can be
// classified wrongly. Nothing is allocated per line (thread-local scratch), no NaN reaches a
// span end (candidates are chord points) and the work per line is bounded by the piece limits.
//
// Faces: as Extrusion.h (bottom, top, kFirstSideFace + segment).
#pragma once

#include <memory>
#include <vector>

#include "primitives/LocalSpans.h"
#include "primitives/Outline.h"
#include "primitives/SegmentCarrier.h"
#include "primitives/base/Tolerances.h"

namespace csg {

// The solid's map from space to the profile plane (see above).
struct TwistMap {
    double z0 = 0.0, z1 = 1.0;
    double twist = 0.0;  // theta: radians over the height, positive clockwise seen from +z
    Vec2 scale{1.0};     // the top's scale per axis, >= 0

    bool uniform() const { return scale.x == scale.y; }
    // The profile point q of p; false when p's section is degenerate (a scale factor <= 0)
    // or p lies outside the slab.
    bool profilePoint(const Vec3& p, Vec2& q) const;
    // The same with s clamped to [0, 1] and the scale factors kept positive: for a point on
    // the surface (a normal's), which rounding may put just outside the slab or at an apex.
    Vec2 nearestProfilePoint(const Vec3& p) const;
    // The outward unit normal at p of the surface swept by a segment whose outward profile
    // normal at p's profile point is n2: the gradient of F(q(p)) is J^T grad F, J = dq/dp.
    Vec3 normal(const Vec3& p, Vec2 n2) const;
    // The radius of a cylinder about z that holds every section of a region within box.
    double boundingRadius(const Bounds2& box) const;
};

// An outline prepared for twisted extrusion: each segment's carrier, and the box in which a
// crossing's profile point must lie to be kept (the segment's, widened by the slack).
struct TwistedOutline {
    std::vector<SegmentCarrier> carriers;
    std::vector<Bounds2> keepBoxes;
    // Every point q of the region has innerRadius <= |q| <= outerRadius: a section's points
    // lie in the annulus these radii span, scaled by the smallest and largest scale factor.
    double innerRadius = 0.0, outerRadius = 0.0;
    // Whether every segment is carried by a line (or by nothing).
    bool straight = true;
    // The most a first piece of a line turns (radians): tol::kSweepPieceAngle, or less when
    // the segments are small against the outer radius (see of()).
    double pieceAngle = tol::kSweepPieceAngle;
    static std::shared_ptr<const TwistedOutline> of(const Outline& outline);
};

// The spans, ascending in t, of the line o + t d (d.z != 0) through the solid of outline under
// map, read only within [lo, hi]: a span that reaches past either end is cut there (kClipFace).
// The solve's cost grows with the chord it covers (a line across 1 500 degrees of twist in
// Debian's example020), and a measuring line reads a short stretch of it. Replaces out's
// contents; returns whether anything past hi was left out.
bool twistedSpans(const Outline& outline, const TwistedOutline& prepared, const TwistMap& map,
                  const Vec3& o, const Vec3& d, double lo, double hi,
                  std::vector<LocalSpans::Entry>& out);

}  // namespace csg
