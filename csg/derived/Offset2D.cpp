// Notation: d = |distance|; the band's side of a piece is its right (outward, the shape lies on
// the left) when distance > 0 and its left when distance < 0; n is the unit normal towards
// that side. At a vertex v, t1 is the direction in which the incoming piece arrives and t2 the
// one in which the outgoing piece leaves; alpha, in (0, 2 pi], is the shape's angle there
// (from t2 counter-clockwise to -t1): below pi a convex corner, above pi a reflex one.
#include "csg/derived/Offset2D.h"

#include <algorithm>
#include <cmath>
#include <map>

namespace csg {

namespace {

constexpr double kTurn = 2.0 * kPi;

double cross(Vec2 a, Vec2 b) {
    return a.x * b.y - a.y * b.x;
}

// Clipper's miter limit as OpenSCAD sets it (1e6): below 2 / limit^2 of 1 + n1 . n2 the miter
// point is too far and Clipper squares the corner off instead (ClipperOffset::OffsetPoint).
constexpr double kMiterLimit = 1e6;
constexpr double kMiterFloor = 2.0 / (kMiterLimit * kMiterLimit);

// Closed counter-clockwise curves, gathered into nonzero outlines of about kChunkSegments
// segments each: a ray tests every segment of an outline it meets, so one outline of
// thousands would cost every ray through the band thousands of tests, where the BVH over
// a union of small ones leaves it the few chunks near its path. Curves are added in the
// boundary's order (sorted by their start points), so a chunk stays compact.
constexpr size_t kChunkSegments = 32;

class Band {
public:
    Band() { out_.rule = FillRule::NonZero; }

    // The polygon through points, turned counter-clockwise; nothing if it has no area.
    void polygon(std::vector<Vec2> points) {
        nextCurve();
        double area = 0.0;
        for (size_t i = 0; i < points.size(); ++i)
            area += cross(points[i], points[(i + 1) % points.size()]);
        if (!(std::abs(area) > 0.0)) return;
        if (area < 0.0) std::reverse(points.begin(), points.end());
        for (size_t i = 0; i < points.size(); ++i)
            out_.segments.push_back(Segment2::line(points[i], points[(i + 1) % points.size()]));
    }

    void disc(Vec2 c, double r) {
        nextCurve();
        out_.segments.push_back(Segment2::circle(c, r));
    }

    // {c + s e(theta): theta in [from, from + width], s in [inner, outer]}, inner >= 0.
    void sector(Vec2 c, double inner, double outer, double from, double width) {
        if (!(outer > inner) || !(width > 0.0)) return;
        nextCurve();
        if (width >= kTurn) {
            disc(c, outer);
            if (inner > 0.0)  // the hole, clockwise
                out_.segments.push_back(Segment2::arc(c, {inner, 0.0}, {0.0, -inner}, 0.0, kTurn));
            return;
        }
        const Segment2 outerArc = Segment2::arc(c, {outer, 0.0}, {0.0, outer}, from, from + width);
        out_.segments.push_back(outerArc);
        if (inner > 0.0) {
            // Clockwise back from from + width to from: c + inner (cos th, -sin th).
            const Segment2 innerArc = Segment2::arc(c, {inner, 0.0}, {0.0, -inner}, -(from + width),
                                                    -(from + width) + width);
            out_.segments.push_back(Segment2::line(outerArc.finish(), innerArc.start()));
            out_.segments.push_back(innerArc);
            out_.segments.push_back(Segment2::line(innerArc.finish(), outerArc.start()));
        } else {
            out_.segments.push_back(Segment2::line(outerArc.finish(), c));
            out_.segments.push_back(Segment2::line(c, outerArc.start()));
        }
    }

    std::vector<Outline> take() {
        if (!out_.segments.empty()) chunks_.push_back(std::move(out_));
        return std::move(chunks_);
    }

private:
    // A new closed curve begins: a new chunk if this one is full.
    void nextCurve() {
        if (out_.segments.size() < kChunkSegments) return;
        chunks_.push_back(std::move(out_));
        out_ = Outline{};
        out_.rule = FillRule::NonZero;
    }

    Outline out_;
    std::vector<Outline> chunks_;
};

// The normal of piece p at u towards the band's side.
Vec2 sideNormal(const BoundaryPiece& p, double u, bool outward) {
    const Vec2 t = p.direction(u);
    return outward ? Vec2(t.y, -t.x) : Vec2(-t.y, t.x);
}

// What the piece sweeps along its normal over d (see Offset2D.h).
void sweepPiece(Band& band, const BoundaryPiece& p, double d, bool outward) {
    if (p.kind == BoundaryPiece::Kind::Line) {
        const Vec2 n = sideNormal(p, 0.0, outward) * d;
        band.polygon({p.a, p.b, p.b + n, p.a + n});
        return;
    }
    // The band's side is away from the centre when it is the outside of the circle: the right
    // of a counter-clockwise arc, the left of a clockwise one.
    const bool away = outward == (p.sweep > 0.0);
    const double from = p.sweep > 0.0 ? p.angle0 : p.angle0 + p.sweep;
    const double width = std::abs(p.sweep);
    if (away) {
        band.sector(p.center, p.radius, p.radius + d, from, width);
    } else if (d <= p.radius) {
        band.sector(p.center, p.radius - d, p.radius, from, width);
    } else {
        // Past the centre the normals carry on into the opposite directions.
        band.sector(p.center, 0.0, p.radius, from, width);
        band.sector(p.center, 0.0, d - p.radius, from + kPi, width);
    }
}

struct Joint {
    std::vector<size_t> in, out;  // pieces ending and starting here
};

using PointKey = std::pair<double, double>;

// The miter or chamfer at vertex v between an incoming piece (direction t1 there) and an
// outgoing one (t2), if the band turns round it.
void corner(Band& band, Vec2 v, Vec2 t1, Vec2 t2, double d, bool outward, OffsetJoin join) {
    const Vec2 u = -t1;
    double alpha = std::atan2(cross(t2, u), glm::dot(t2, u));
    if (alpha <= 0.0) alpha += kTurn;
    // The band wraps convex corners when it grows and reflex ones when it shrinks.
    const double slack = 1e-12;
    if (outward ? alpha >= kPi - slack : alpha <= kPi + slack) return;
    const Vec2 n1 = outward ? Vec2(t1.y, -t1.x) : Vec2(-t1.y, t1.x);
    const Vec2 n2 = outward ? Vec2(t2.y, -t2.x) : Vec2(-t2.y, t2.x);
    const double r = 1.0 + glm::dot(n1, n2);
    if (join == OffsetJoin::Miter && r >= kMiterFloor) {
        band.polygon({v, v + n1 * d, v + (n1 + n2) * (d / r), v + n2 * d});
        return;
    }
    // Clipper's square join: the moved edges carried on by d tan(a / 4), a = the angle
    // between the normals, meet the line perpendicular to the bisector at distance d.
    const double a = std::acos(std::clamp(glm::dot(n1, n2), -1.0, 1.0));
    const double along = d * std::tan(a / 4.0);
    band.polygon({v, v + n1 * d, v + n1 * d + t1 * along, v + n2 * d - t2 * along, v + n2 * d});
}

}  // namespace

std::vector<Outline> offsetBand(const Boundary2D& boundary, double distance, OffsetJoin join) {
    Band band;
    if (!(distance != 0.0) || !std::isfinite(distance)) return band.take();
    const double d = std::abs(distance);
    const bool outward = distance > 0.0;
    for (const BoundaryPiece& p : boundary.pieces) sweepPiece(band, p, d, outward);

    std::map<PointKey, Joint> joints;
    for (size_t i = 0; i < boundary.pieces.size(); ++i) {
        const BoundaryPiece& p = boundary.pieces[i];
        if (p.a == p.b) continue;  // a whole circle has no vertex
        joints[{p.b.x, p.b.y}].in.push_back(i);
        joints[{p.a.x, p.a.y}].out.push_back(i);
    }
    for (auto& [key, joint] : joints) {
        const Vec2 v(key.first, key.second);
        if (join == OffsetJoin::Round) {
            band.disc(v, d);
            continue;
        }
        // Each incoming piece pairs with the outgoing one that bounds the same corner.
        std::vector<size_t> outs = joint.out;
        for (size_t in : joint.in) {
            if (outs.empty()) break;
            const Vec2 t1 = boundary.pieces[in].direction(1.0);
            const size_t best = cornerPartner(boundary.pieces, t1, outs);
            corner(band, v, t1, boundary.pieces[outs[best]].direction(0.0), d, outward, join);
            outs.erase(outs.begin() + std::ptrdiff_t(best));
        }
    }
    return band.take();
}

}  // namespace csg
