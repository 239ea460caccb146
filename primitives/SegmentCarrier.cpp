#include "primitives/SegmentCarrier.h"

#include <cmath>

#include "primitives/base/Tolerances.h"

namespace csg {

namespace {

using Kind = SegmentCarrier::Kind;

Interval exactly(double v) {
    return pointInterval(v);
}

// det[X Y W; p.x p.y 1; q.x q.y 1] times factor: the line through p and q (zero at both).
void setLineForm(SegmentCarrier& c, int k, Vec2 p, Vec2 q, double factor = 1.0) {
    c.coef[3 * k] = factor * (exactly(p.y) - q.y);
    c.coef[3 * k + 1] = factor * (exactly(q.x) - p.x);
    c.coef[3 * k + 2] = factor * (exactly(p.x) * q.y - exactly(q.x) * p.y);
}

// The line through c with direction e: cross(e, q - c).
void setDirectionForm(SegmentCarrier& c, int k, Vec2 centre, Vec2 e) {
    c.coef[3 * k] = exactly(-e.y);
    c.coef[3 * k + 1] = exactly(e.x);
    c.coef[3 * k + 2] = exactly(e.y) * centre.x - exactly(e.x) * centre.y;
}

void addToBox(SegmentCarrier& c, const Vec2* points, int n) {
    for (int i = 0; i < n; ++i) c.box.add(points[i]);
}

// For a Bezier's control points: the farthest two, and whether every point lies within
// tol::kFlatCurveRel of their extent from the line through them (then so does the curve).
struct Flatness {
    int i = 0, j = 0;
    double extent = 0.0;
    bool flat = true;
};
Flatness flatness(const Vec2* points, int n) {
    Flatness f;
    for (int a = 0; a < n; ++a)
        for (int b = a + 1; b < n; ++b)
            if (const double l = glm::distance(points[a], points[b]); l > f.extent)
                f.extent = l, f.i = a, f.j = b;
    if (f.extent == 0.0) return f;
    const Vec2 e = points[f.j] - points[f.i];
    for (int a = 0; a < n; ++a) {
        const Vec2 w = points[a] - points[f.i];
        const double distance = std::abs(e.x * w.y - e.y * w.x) / f.extent;
        if (distance > tol::kFlatCurveRel * f.extent) f.flat = false;
    }
    return f;
}

void setParabola(SegmentCarrier& c, Vec2 p0, Vec2 p1, Vec2 p2) {
    c.kind = Kind::Parabola;
    setLineForm(c, 0, p1, p2);  // L0: the area opposite p0
    setLineForm(c, 1, p2, p0);
    setLineForm(c, 2, p0, p1);
}

// An arc's box: its ends and the extremes along x and y that its angles reach (coordinate k
// is centre_k + h_k cos(th - th_k), h_k = |(a_k, b_k)|, highest at th_k = atan2(b_k, a_k)),
// widened by tol::kArcBoxGuardRel. Pieces of one circle (a boundary cut where other shapes
// meet it) then claim only their own part of the plane, not the whole circle's box each.
Bounds2 arcBox(const Segment2& s) {
    const Vec2 centre = s.p[1], a = s.p[2], b = s.p[3];
    const Vec2 half(std::hypot(a.x, b.x), std::hypot(a.y, b.y));
    Bounds2 box;
    if (s.th1 - s.th0 >= 2.0 * kPi) {
        box.add(centre - half);
        box.add(centre + half);
        return box;
    }
    box.add(s.start());
    box.add(s.finish());
    for (int k = 0; k < 2; ++k) {
        const double highest = std::atan2(b[k], a[k]);
        for (const double extreme : {highest, highest + kPi}) {
            // The first angle >= th0 at which the extreme recurs.
            const double th = extreme + 2.0 * kPi * std::ceil((s.th0 - extreme) / (2.0 * kPi));
            if (th > s.th1) continue;
            Vec2 p = s.start();
            p[k] = centre[k] + (extreme == highest ? half[k] : -half[k]);
            box.add(p);
        }
    }
    const double guard = tol::kArcBoxGuardRel * (std::max(std::abs(centre.x), std::abs(centre.y)) +
                                                 std::max(half.x, half.y));
    box.lo -= Vec2(guard);
    box.hi += Vec2(guard);
    return box;
}

}  // namespace

SegmentCarrier SegmentCarrier::of(const Segment2& s) {
    SegmentCarrier c;
    switch (s.kind) {
        case Segment2::Kind::Line:
            if (s.p[0] == s.p[1]) break;
            c.kind = Kind::Line;
            setLineForm(c, 0, s.p[0], s.p[1]);
            addToBox(c, s.p, 2);
            break;
        case Segment2::Kind::Arc: {
            const Vec2 centre = s.p[1], a = s.p[2], b = s.p[3];
            c.box = arcBox(s);
            const Interval det = exactly(a.x) * b.y - exactly(b.x) * a.y;
            const double la = glm::length(a), lb = glm::length(b);
            if (la == 0.0 && lb == 0.0) break;
            if (det.magnitude() <= tol::kFlatCurveRel * la * lb || det.containsZero()) {
                // Collapsed onto a line through the centre, along its longer axis.
                c.kind = Kind::Line;
                setDirectionForm(c, 0, centre, la >= lb ? a : b);
                break;
            }
            // adj(A) (q - centre) with A = [a b]: its length is |det| on the ellipse.
            c.kind = Kind::Ellipse;
            c.coef[0] = exactly(b.y);
            c.coef[1] = exactly(-b.x);
            c.coef[2] = exactly(b.x) * centre.y - exactly(b.y) * centre.x;
            c.coef[3] = exactly(-a.y);
            c.coef[4] = exactly(a.x);
            c.coef[5] = exactly(a.y) * centre.x - exactly(a.x) * centre.y;
            c.coef[6] = sqr(det);
            break;
        }
        case Segment2::Kind::Quadratic:
        case Segment2::Kind::Cubic: {
            const int n = s.kind == Segment2::Kind::Quadratic ? 3 : 4;
            addToBox(c, s.p, n);
            const Flatness f = flatness(s.p, n);
            if (f.extent == 0.0) break;
            if (f.flat) {
                c.kind = Kind::Line;
                setLineForm(c, 0, s.p[f.i], s.p[f.j]);
                break;
            }
            if (n == 3) {
                setParabola(c, s.p[0], s.p[1], s.p[2]);
                break;
            }
            const Vec2 lead = s.p[3] - 3.0 * s.p[2] + 3.0 * s.p[1] - s.p[0];
            if (glm::length(lead) <= tol::kFlatCurveRel * f.extent) {
                // A raised quadratic: its middle control point from both inner ones.
                setParabola(c, s.p[0], (3.0 * (s.p[1] + s.p[2]) - s.p[0] - s.p[3]) / 4.0, s.p[3]);
                break;
            }
            // Sederberg's forms l_ij = C(3,i) C(3,j) det[X Y W; P_i; P_j], in the order the
            // Bezout matrix reads them (SegmentCarrier.h).
            c.kind = Kind::Cubic;
            setLineForm(c, 0, s.p[1], s.p[0], 3.0);  // l10
            setLineForm(c, 1, s.p[2], s.p[0], 3.0);  // l20
            setLineForm(c, 2, s.p[3], s.p[0], 1.0);  // l30
            setLineForm(c, 3, s.p[2], s.p[1], 9.0);  // l21
            setLineForm(c, 4, s.p[3], s.p[1], 3.0);  // l31
            setLineForm(c, 5, s.p[3], s.p[2], 3.0);  // l32
            break;
        }
    }
    for (size_t i = 0; i < c.coef.size(); ++i)
        c.mid[i] = c.coef[i].lo + 0.5 * (c.coef[i].hi - c.coef[i].lo);
    return c;
}

}  // namespace csg
