// Notation: a segment's parameter is u in [0, 1] along a line, or the angle turned from its
// start, in [0, |sweep|], along an arc. eps is tol::kBoundaryPointRel of the shape's size: two
// points closer than eps are one, and a crossing within eps of a segment's end is that end
// (the very doubles), so that the pieces of crossing segments meet exactly.
#include "csg/derived/Boundary2D.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>

#include "csg/derived/Flatten2D.h"
#include "primitives/base/Tolerances.h"

namespace csg {

namespace {

constexpr double kTurn = 2.0 * kPi;

double cross(Vec2 a, Vec2 b) {
    return a.x * b.y - a.y * b.x;
}

Vec2 unitAt(double angle) {
    return {std::cos(angle), std::sin(angle)};
}

// The angle turned from an arc's start to the direction phi, along the arc, in [0, 2 pi).
double turned(const BoundaryPiece& arc, double phi) {
    double d = arc.sweep >= 0.0 ? phi - arc.angle0 : arc.angle0 - phi;
    d = std::fmod(d, kTurn);
    return d < 0.0 ? d + kTurn : d;
}

}  // namespace

// A circular Segment2 is c + a cos th + b sin th with a, b orthogonal and of one length
// (Outline.h): its angle about c is angle(a) + th, or angle(a) - th when b turns clockwise.
BoundaryPiece boundaryPieceOf(const Segment2& s) {
    BoundaryPiece p;
    p.a = s.start();
    p.b = s.finish();
    if (s.kind == Segment2::Kind::Line) return p;
    p.kind = BoundaryPiece::Kind::Arc;
    p.center = s.p[1];
    p.radius = 0.5 * (glm::length(s.p[2]) + glm::length(s.p[3]));
    const double turn = cross(s.p[2], s.p[3]) >= 0.0 ? 1.0 : -1.0;
    p.angle0 = std::atan2(s.p[2].y, s.p[2].x) + turn * s.th0;
    p.sweep = turn * (s.th1 - s.th0);
    return p;
}

Segment2 segmentOf(const BoundaryPiece& p) {
    if (p.kind == BoundaryPiece::Kind::Line) return Segment2::line(p.a, p.b);
    // Clockwise arcs run their angle down: th = -angle on the axes (r, 0), (0, -r).
    const double turn = p.sweep >= 0.0 ? 1.0 : -1.0;
    Segment2 s = Segment2::arc(p.center, Vec2(p.radius, 0.0), Vec2(0.0, turn * p.radius),
                               turn * p.angle0, turn * p.angle0 + std::abs(p.sweep));
    s.p[0] = p.a;
    s.end = p.b;
    return s;
}

namespace {

Bounds2 boxOf(const BoundaryPiece& p) {
    Bounds2 box;
    if (p.kind == BoundaryPiece::Kind::Line) {
        box.add(p.a);
        box.add(p.b);
    } else {
        box.add(p.center - Vec2(p.radius));
        box.add(p.center + Vec2(p.radius));
    }
    return box;
}

struct Cut {
    double param;
    Vec2 point;
};

// Splits segments where they meet (see the notation above).
class Splitter {
public:
    Splitter(std::vector<BoundaryPiece> segments, double eps)
        : segs_(std::move(segments)), cuts_(segs_.size()), eps_(eps) {}

    void run() {
        std::vector<Bounds2> boxes(segs_.size());
        for (size_t i = 0; i < segs_.size(); ++i) boxes[i] = boxOf(segs_[i]);
        std::vector<uint32_t> order(segs_.size());
        std::iota(order.begin(), order.end(), 0u);
        std::sort(order.begin(), order.end(),
                  [&](uint32_t x, uint32_t y) { return boxes[x].lo.x < boxes[y].lo.x; });
        // Sweep along x: only segments whose boxes overlap (widened by eps) can meet.
        for (size_t k = 0; k < order.size(); ++k) {
            const uint32_t i = order[k];
            for (size_t l = k + 1; l < order.size(); ++l) {
                const uint32_t j = order[l];
                if (boxes[j].lo.x > boxes[i].hi.x + eps_) break;
                if (boxes[j].lo.y > boxes[i].hi.y + eps_ || boxes[j].hi.y < boxes[i].lo.y - eps_)
                    continue;
                meet(i, j);
            }
        }
    }

    // The pieces between consecutive cuts of every segment.
    std::vector<BoundaryPiece> pieces() {
        std::vector<BoundaryPiece> out;
        for (size_t i = 0; i < segs_.size(); ++i) split(i, out);
        return out;
    }

private:
    using Kind = BoundaryPiece::Kind;

    void meet(uint32_t i, uint32_t j) {
        const Kind ki = segs_[i].kind, kj = segs_[j].kind;
        if (ki == Kind::Line && kj == Kind::Line) return lineLine(i, j);
        if (ki == Kind::Line) return lineArc(i, j);
        if (kj == Kind::Line) return lineArc(j, i);
        arcArc(i, j);
    }

    // x moved onto an end of segment i or j within eps (i's first).
    Vec2 snap(uint32_t i, uint32_t j, Vec2 x) const {
        for (const Vec2& q : {segs_[i].a, segs_[i].b, segs_[j].a, segs_[j].b})
            if (glm::distance(x, q) <= eps_) return q;
        return x;
    }

    // The parameter of a point on (or within eps of) an arc, if it lies on the arc.
    bool onArc(const BoundaryPiece& arc, Vec2 x, double& param) const {
        const double tolerance = eps_ / arc.radius;
        const double off = turned(arc, std::atan2(x.y - arc.center.y, x.x - arc.center.x));
        const double span = std::abs(arc.sweep);
        if (off <= span + tolerance) {
            param = std::min(off, span);
            return true;
        }
        if (off >= kTurn - tolerance) {
            param = 0.0;
            return true;
        }
        return false;
    }

    // A whole circle's start is no vertex: it is cut there like anywhere else.
    bool wholeCircle(const BoundaryPiece& s) const {
        return s.kind == Kind::Arc && s.a == s.b && std::abs(s.sweep) >= kTurn * (1 - 1e-12);
    }

    // Segment i is cut at x, unless x is one of its ends.
    void cut(uint32_t i, Vec2 x) {
        const BoundaryPiece& s = segs_[i];
        if (!wholeCircle(s) && (glm::distance(x, s.a) <= eps_ || glm::distance(x, s.b) <= eps_))
            return;
        double param;
        if (s.kind == Kind::Line) {
            const Vec2 d = s.b - s.a;
            param = std::clamp(glm::dot(x - s.a, d) / glm::dot(d, d), 0.0, 1.0);
        } else if (!onArc(s, x, param)) {
            return;
        }
        cuts_[i].push_back({param, x});
    }

    void both(uint32_t i, uint32_t j, Vec2 x) {
        x = snap(i, j, x);
        cut(i, x);
        cut(j, x);
    }

    void lineLine(uint32_t i, uint32_t j) {
        const BoundaryPiece &s = segs_[i], &t = segs_[j];
        const Vec2 d1 = s.b - s.a, d2 = t.b - t.a;
        const double l1 = glm::length(d1), l2 = glm::length(d2);
        if (l1 == 0.0 || l2 == 0.0) return;
        const double den = cross(d1, d2);
        if (std::abs(den) <= 1e-12 * l1 * l2) {
            // Parallel: on one line, each is cut at the other's ends that lie inside it.
            if (std::abs(cross(d1, t.a - s.a)) / l1 > eps_) return;
            for (const Vec2& q : {t.a, t.b}) onLine(i, q);
            for (const Vec2& q : {s.a, s.b}) onLine(j, q);
            return;
        }
        const double u = cross(t.a - s.a, d2) / den, v = cross(t.a - s.a, d1) / den;
        const double tu = eps_ / l1, tv = eps_ / l2;
        if (u < -tu || u > 1.0 + tu || v < -tv || v > 1.0 + tv) return;
        both(i, j, s.a + d1 * u);
    }

    // Cuts line i at q when q lies on it, strictly between its ends.
    void onLine(uint32_t i, Vec2 q) {
        const BoundaryPiece& s = segs_[i];
        const Vec2 d = s.b - s.a;
        const double u = glm::dot(q - s.a, d) / glm::dot(d, d);
        if (u > 0.0 && u < 1.0 && std::abs(cross(d, q - s.a)) / glm::length(d) <= eps_) cut(i, q);
    }

    void lineArc(uint32_t i, uint32_t j) {
        const BoundaryPiece &s = segs_[i], &c = segs_[j];
        const Vec2 d = s.b - s.a;
        const double len = glm::length(d);
        if (len == 0.0) return;
        const Vec2 dir = d / len;
        const Vec2 w = c.center - s.a;
        const double along = glm::dot(w, dir), dist = std::abs(cross(dir, w));
        if (dist > c.radius + eps_) return;
        // Within eps of tangent: one crossing at the foot of the centre.
        const double half =
            dist >= c.radius - eps_ ? 0.0 : std::sqrt((c.radius - dist) * (c.radius + dist));
        for (double sign : {-1.0, 1.0}) {
            const double at = along + sign * half;
            if (at < -eps_ || at > len + eps_) continue;
            const Vec2 x = s.a + dir * at;
            double param;
            if (onArc(c, x, param)) both(i, j, x);
            if (half == 0.0) break;
        }
    }

    void arcArc(uint32_t i, uint32_t j) {
        const BoundaryPiece &p = segs_[i], &q = segs_[j];
        const Vec2 between = q.center - p.center;
        const double dist = glm::length(between);
        if (dist <= eps_) {
            // One circle: each arc is cut at the other's ends that lie on it.
            if (std::abs(p.radius - q.radius) > eps_) return;
            for (const Vec2& x : {q.a, q.b}) cut(i, x);
            for (const Vec2& x : {p.a, p.b}) cut(j, x);
            return;
        }
        if (dist > p.radius + q.radius + eps_ || dist < std::abs(p.radius - q.radius) - eps_)
            return;
        const Vec2 e = between / dist, n(-e.y, e.x);
        const double along = (dist * dist + p.radius * p.radius - q.radius * q.radius) / (2 * dist);
        const bool tangent =
            dist >= p.radius + q.radius - eps_ || dist <= std::abs(p.radius - q.radius) + eps_;
        const double half =
            tangent ? 0.0 : std::sqrt(std::max(0.0, p.radius * p.radius - along * along));
        for (double sign : {-1.0, 1.0}) {
            const Vec2 x = p.center + e * along + n * (sign * half);
            double pp, qp;
            if (onArc(p, x, pp) && onArc(q, x, qp)) both(i, j, x);
            if (half == 0.0) break;
        }
    }

    // The piece of segment s from parameter p0 at x0 to p1 at x1.
    static BoundaryPiece part(const BoundaryPiece& s, double p0, Vec2 x0, double p1, Vec2 x1) {
        BoundaryPiece piece = s;
        piece.a = x0;
        piece.b = x1;
        if (s.kind == Kind::Arc) {
            const double turn = s.sweep >= 0.0 ? 1.0 : -1.0;
            piece.angle0 = s.angle0 + turn * p0;
            piece.sweep = turn * (p1 - p0);
        }
        return piece;
    }

    void split(size_t i, std::vector<BoundaryPiece>& out) {
        const BoundaryPiece& s = segs_[i];
        std::vector<Cut>& cuts = cuts_[i];
        std::sort(cuts.begin(), cuts.end(),
                  [](const Cut& x, const Cut& y) { return x.param < y.param; });
        std::vector<Cut> kept;
        for (const Cut& c : cuts)
            if (kept.empty() || glm::distance(c.point, kept.back().point) > eps_) kept.push_back(c);
        const double end = s.kind == Kind::Line ? 1.0 : std::abs(s.sweep);
        if (kept.empty()) {
            out.push_back(s);
            return;
        }
        if (wholeCircle(s)) {
            // The circle's start is no vertex: its pieces run from cut to cut.
            if (kept.size() > 1 && glm::distance(kept.front().point, kept.back().point) <= eps_)
                kept.pop_back();
            for (size_t k = 0; k + 1 < kept.size(); ++k)
                out.push_back(
                    part(s, kept[k].param, kept[k].point, kept[k + 1].param, kept[k + 1].point));
            out.push_back(part(s, kept.back().param, kept.back().point, kept.front().param + kTurn,
                               kept.front().point));
            return;
        }
        double p0 = 0.0;
        Vec2 x0 = s.a;
        for (const Cut& c : kept) {
            out.push_back(part(s, p0, x0, c.param, c.point));
            p0 = c.param, x0 = c.point;
        }
        out.push_back(part(s, p0, x0, end, s.b));
    }

    std::vector<BoundaryPiece> segs_;
    std::vector<std::vector<Cut>> cuts_;
    double eps_;
};

bool samePiece(const BoundaryPiece& p, const BoundaryPiece& q, double eps) {
    if (p.kind != q.kind || p.a != q.a || p.b != q.b) return false;
    if (p.kind == BoundaryPiece::Kind::Line) return true;
    return glm::distance(p.center, q.center) <= eps && std::abs(p.radius - q.radius) <= eps &&
           (p.sweep > 0.0) == (q.sweep > 0.0);
}

}  // namespace

Vec2 BoundaryPiece::at(double u) const {
    if (u <= 0.0) return a;
    if (u >= 1.0) return b;
    if (kind == Kind::Line) return a + (b - a) * u;
    return center + unitAt(angle0 + sweep * u) * radius;
}

Vec2 BoundaryPiece::direction(double u) const {
    if (kind == Kind::Line) return glm::normalize(b - a);
    const Vec2 e = unitAt(angle0 + sweep * std::clamp(u, 0.0, 1.0));
    return sweep >= 0.0 ? Vec2(-e.y, e.x) : Vec2(e.y, -e.x);
}

double BoundaryPiece::length() const {
    return kind == Kind::Line ? glm::distance(a, b) : radius * std::abs(sweep);
}

BoundaryPiece BoundaryPiece::reversed() const {
    BoundaryPiece r = *this;
    std::swap(r.a, r.b);
    if (kind == Kind::Arc) {
        r.angle0 = angle0 + sweep;
        r.sweep = -sweep;
    }
    return r;
}

Bounds2 BoundaryPiece::bounds() const {
    Bounds2 box;
    box.add(a);
    box.add(b);
    if (kind != Kind::Arc) return box;
    constexpr double kQuarter = 0.5 * kPi;
    const double lo = std::min(angle0, angle0 + sweep), hi = std::max(angle0, angle0 + sweep);
    for (double k = std::ceil(lo / kQuarter); k * kQuarter <= hi; k += 1.0)
        box.add(center + radius * unitAt(k * kQuarter));
    return box;
}

Region2D::Region2D(const Node& shape) {
    // The size first: the flattening tolerance is relative to it.
    root_ = add(shape, glm::dmat2(1.0), Vec2(0.0));
    double size = 1.0;
    for (const Bounds2& b : boxes_)
        if (!b.empty())
            size = std::max(
                {size, std::abs(b.lo.x), std::abs(b.lo.y), std::abs(b.hi.x), std::abs(b.hi.y)});
    size_ = size;
    const double tolerance = tol::kFlattenRel * size;
    for (size_t k = 0; k < outlines_.size(); ++k) {
        Outline flat;
        flat.rule = outlines_[k].rule;
        for (const Segment2& s : outlines_[k].segments)
            approximated_ |= appendLinesAndCircles(s, tolerance, flat.segments);
        outlines_[k] = std::move(flat);
        boxes_[k] = outlines_[k].bounds();
    }
    strips_.resize(outlines_.size());
    for (size_t k = 0; k < outlines_.size(); ++k) buildStrips(k);
}

void Region2D::buildStrips(size_t leaf) {
    const Outline& outline = outlines_[leaf];
    const Bounds2& box = boxes_[leaf];
    Strips& s = strips_[leaf];
    const size_t count = std::clamp<size_t>(outline.segments.size() / 8, 1, 256);
    s.y0 = box.empty() ? 0.0 : box.lo.y;
    s.height = box.empty() ? 1.0 : std::max((box.hi.y - box.lo.y) / double(count), 1e-300);
    s.strips.assign(count, Outline{});
    for (Outline& strip : s.strips) strip.rule = outline.rule;
    for (const Segment2& seg : outline.segments) {
        Bounds2 b;
        if (seg.kind == Segment2::Kind::Line) {
            b.add(seg.p[0]);
            b.add(seg.p[1]);
        } else {
            Outline one;
            one.segments.push_back(seg);
            b = one.bounds();
        }
        const auto first = size_t(std::clamp((b.lo.y - s.y0) / s.height, 0.0, double(count - 1)));
        const auto last = size_t(std::clamp((b.hi.y - s.y0) / s.height, 0.0, double(count - 1)));
        for (size_t k = first; k <= last; ++k) s.strips[k].segments.push_back(seg);
    }
}

int32_t Region2D::add(const Node& node, const glm::dmat2& parentM, Vec2 parentShift) {
    const Mat4& local = node.parentFromNode;
    const glm::dmat2 m = parentM * glm::dmat2(local[0][0], local[0][1], local[1][0], local[1][1]);
    const Vec2 shift = parentM * Vec2(local[3][0], local[3][1]) + parentShift;
    Item item;
    item.op = node.op;
    if (node.op == Op::Leaf) {
        const auto* e = std::get_if<Extrusion>(&node.primitive);
        outlines_.push_back(e && e->outline ? e->outline->mapped(m, shift) : Outline{});
        boxes_.push_back(outlines_.back().bounds());
        item.outline = int32_t(outlines_.size() - 1);
    } else {
        item.left = node.left ? add(*node.left, m, shift) : -1;
        item.right = node.right ? add(*node.right, m, shift) : -1;
    }
    items_.push_back(item);
    return int32_t(items_.size() - 1);
}

bool Region2D::inside(Vec2 p) const {
    return root_ >= 0 && inside(root_, p);
}

bool Region2D::inside(int32_t index, Vec2 p) const {
    if (index < 0) return false;  // an empty operand
    const Item& item = items_[size_t(index)];
    switch (item.op) {
        case Op::Leaf: {
            const Bounds2& box = boxes_[size_t(item.outline)];
            if (p.x < box.lo.x || p.x > box.hi.x || p.y < box.lo.y || p.y > box.hi.y) return false;
            const Strips& s = strips_[size_t(item.outline)];
            const double k = std::clamp((p.y - s.y0) / s.height, 0.0, double(s.strips.size() - 1));
            return s.strips[size_t(k)].inside(p);
        }
        case Op::Union:
            return inside(item.left, p) || inside(item.right, p);
        case Op::Intersection:
            return inside(item.left, p) && inside(item.right, p);
        case Op::Difference:
            return inside(item.left, p) && !inside(item.right, p);
    }
    return false;
}

Boundary2D boundaryOf(const Region2D& region) {
    Boundary2D result;
    result.approximated = region.approximated();
    const double eps = tol::kBoundaryPointRel * region.size();
    std::vector<BoundaryPiece> segments;
    for (const Outline& o : region.outlines())
        for (const Segment2& s : o.segments) {
            BoundaryPiece p = boundaryPieceOf(s);
            if (p.length() > 0.0) segments.push_back(p);
        }
    Splitter splitter(std::move(segments), eps);
    splitter.run();
    std::vector<BoundaryPiece> kept;
    for (const BoundaryPiece& p : splitter.pieces()) {
        const double length = p.length();
        if (!(length > 0.0)) continue;
        // The shape on each side of the piece's middle.
        double step = std::min(tol::kBoundarySideRel * region.size(), 0.05 * length);
        if (p.kind == BoundaryPiece::Kind::Arc) step = std::min(step, 0.5 * p.radius);
        const Vec2 m = p.at(0.5), t = p.direction(0.5), left(-t.y, t.x);
        const bool inLeft = region.inside(m + left * step),
                   inRight = region.inside(m - left * step);
        if (inLeft == inRight) continue;
        kept.push_back(inLeft ? p : p.reversed());
    }
    // Coincident pieces are the same doubles (see the top of Boundary2D.h): keep one of each.
    std::sort(kept.begin(), kept.end(), [](const BoundaryPiece& p, const BoundaryPiece& q) {
        if (p.a.x != q.a.x) return p.a.x < q.a.x;
        if (p.a.y != q.a.y) return p.a.y < q.a.y;
        if (p.b.x != q.b.x) return p.b.x < q.b.x;
        return p.b.y < q.b.y;
    });
    for (size_t i = 0; i < kept.size(); ++i) {
        bool duplicate = false;
        for (size_t j = result.pieces.size(); j-- > 0;) {
            const BoundaryPiece& q = result.pieces[j];
            if (q.a != kept[i].a || q.b != kept[i].b) break;
            if (samePiece(q, kept[i], eps)) duplicate = true;
        }
        if (!duplicate) result.pieces.push_back(kept[i]);
    }
    return result;
}

size_t cornerPartner(const std::vector<BoundaryPiece>& pieces, Vec2 in,
                     const std::vector<size_t>& outs) {
    size_t best = 0;
    double bestAngle = kInfinity;
    for (size_t k = 0; k < outs.size(); ++k) {
        const Vec2 out = pieces[outs[k]].direction(0.0);
        double alpha = std::atan2(cross(out, -in), glm::dot(out, -in));
        if (alpha <= 0.0) alpha += kTurn;
        if (alpha < bestAngle) bestAngle = alpha, best = k;
    }
    return best;
}

namespace {

// q appended to p when both are pieces of one line or one circle, turning the same way (p
// ends where q starts).
bool merge(BoundaryPiece& p, const BoundaryPiece& q, double eps) {
    if (p.kind != q.kind) return false;
    if (p.kind == BoundaryPiece::Kind::Line) {
        const Vec2 d = q.b - p.a;
        const double length = glm::length(d);
        if (!(length > 0.0) || glm::dot(p.b - p.a, q.b - q.a) <= 0.0) return false;
        if (std::abs(cross(d, p.b - p.a)) > eps * length) return false;
        p.b = q.b;
        return true;
    }
    if (glm::length(p.center - q.center) > eps || std::abs(p.radius - q.radius) > eps ||
        (p.sweep > 0.0) != (q.sweep > 0.0) ||
        std::abs(p.sweep + q.sweep) > kTurn + tol::kArcSweepSlack)
        return false;
    p.sweep += q.sweep;
    p.b = q.b;
    if (std::abs(p.sweep) >=
        kTurn - tol::kArcSweepSlack) {  // the circle closed: a whole turn, no vertex
        p.sweep = std::copysign(kTurn, p.sweep);
        p.b = p.a;
    }
    return true;
}

// The contour with its mergeable neighbours merged (the last and the first too).
Contour2D merged(const Contour2D& pieces, double eps) {
    Contour2D out;
    for (const BoundaryPiece& p : pieces)
        if (out.empty() || !merge(out.back(), p, eps)) out.push_back(p);
    while (out.size() > 1) {
        BoundaryPiece last = out.back();
        if (!merge(last, out.front(), eps)) break;
        out.front() = last;
        out.pop_back();
    }
    return out;
}

}  // namespace

std::optional<std::vector<Contour2D>> contoursOf(const Boundary2D& boundary) {
    const std::vector<BoundaryPiece>& pieces = boundary.pieces;
    double size = 1.0;
    for (const BoundaryPiece& p : pieces)
        for (const Vec2 v : {p.a, p.b, p.center})
            size = std::max({size, std::abs(v.x), std::abs(v.y)});
    const double eps = tol::kBoundaryPointRel * size;

    std::vector<Contour2D> contours;
    std::map<std::pair<double, double>, std::vector<size_t>> starting;  // unused pieces by start
    for (size_t i = 0; i < pieces.size(); ++i) {
        if (pieces[i].a == pieces[i].b)
            contours.push_back({pieces[i]});  // a whole circle
        else
            starting[{pieces[i].a.x, pieces[i].a.y}].push_back(i);
    }
    while (!starting.empty()) {
        auto first = starting.begin();
        const size_t start = first->second.front();
        first->second.erase(first->second.begin());
        if (first->second.empty()) starting.erase(first);
        Contour2D contour{pieces[start]};
        for (;;) {
            const BoundaryPiece& last = contour.back();
            const auto at = starting.find({last.b.x, last.b.y});
            std::vector<size_t> outs = at == starting.end() ? std::vector<size_t>{} : at->second;
            const bool closing = last.b == pieces[start].a;
            if (closing) outs.push_back(start);
            if (outs.empty()) return std::nullopt;
            const size_t next = outs[cornerPartner(pieces, last.direction(1.0), outs)];
            if (next == start) break;
            contour.push_back(pieces[next]);
            std::erase(at->second, next);
            if (at->second.empty()) starting.erase(at);
        }
        contours.push_back(merged(contour, eps));
    }
    return contours;
}

}  // namespace csg
