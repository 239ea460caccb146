#include "primitives/Outline.h"

#include <algorithm>
#include <cmath>

#include "primitives/solvers/Cubic.h"
#include "primitives/solvers/Quadratic.h"

namespace csg {

namespace {

double cross(Vec2 a, Vec2 b) {
    return a.x * b.y - a.y * b.x;
}

// Which side of the line o + t d the point p lies on (see Outline.h: 0 counts as positive).
double side(Vec2 o, Vec2 d, Vec2 p) {
    return cross(d, p - o);
}

// How much a box is widened, relative to the whole outline's size, and the slack of the
// line-box test relative to the line's scale: both far above the rounding of side() (a few
// ulps), so the hierarchy never culls a segment the side test would cross.
constexpr double kBoxWidenRel = 1e-9;
constexpr double kLineBoxSlack = 1e-12;

// The ellipse parameter of a point q on (or near) the arc's ellipse.
double arcAngle(const Segment2& s, Vec2 q) {
    const glm::dmat2 axes(s.p[2], s.p[3]);
    const Vec2 w = glm::inverse(axes) * (q - s.p[1]);
    return std::atan2(w.y, w.x);
}

// theta moved by whole turns into [th0, th0 + 2 pi).
double intoTurn(double theta, double th0) {
    const double turn = 2.0 * kPi;
    double k = std::floor((theta - th0) / turn);
    double out = theta - k * turn;
    if (out < th0) out += turn;
    if (out >= th0 + turn) out -= turn;
    return out;
}

// The roots u in (0, 1) of a curved segment's side function, at most 4.
int curvedRoots(const Segment2& s, Vec2 o, Vec2 d, double* u) {
    double roots[4];
    int n = 0;
    switch (s.kind) {
        case Segment2::Kind::Quadratic: {
            const double s0 = side(o, d, s.p[0]), s1 = side(o, d, s.p[1]), s2 = side(o, d, s.p[2]);
            n = solveQuadratic(s0 - 2.0 * s1 + s2, 2.0 * (s1 - s0), s0, roots[0], roots[1]);
            break;
        }
        case Segment2::Kind::Cubic: {
            const double s0 = side(o, d, s.p[0]), s1 = side(o, d, s.p[1]), s2 = side(o, d, s.p[2]),
                         s3 = side(o, d, s.p[3]);
            n = solveCubicAll(s3 - 3.0 * s2 + 3.0 * s1 - s0, 3.0 * (s0 - 2.0 * s1 + s2),
                              3.0 * (s1 - s0), s0, roots);
            break;
        }
        case Segment2::Kind::Arc: {
            // side(c + a cos + b sin) = gamma + alpha cos + beta sin.
            const double gamma = side(o, d, s.p[1]);
            const double alpha = cross(d, s.p[2]), beta = cross(d, s.p[3]);
            const double r = std::hypot(alpha, beta);
            if (r == 0.0 || std::abs(gamma) > r) break;
            const double phi = std::atan2(beta, alpha);
            const double half = std::acos(std::clamp(-gamma / r, -1.0, 1.0));
            const double span = s.th1 - s.th0;
            for (double theta : {phi - half, phi + half})
                roots[n++] = (intoTurn(theta, s.th0) - s.th0) / span;
            if (n == 2 && roots[0] > roots[1]) std::swap(roots[0], roots[1]);
            break;
        }
        case Segment2::Kind::Line:
            break;
    }
    int kept = 0;
    for (int i = 0; i < n; ++i)
        if (roots[i] > 0.0 && roots[i] < 1.0) u[kept++] = roots[i];
    return kept;
}

}  // namespace

Segment2 Segment2::line(Vec2 a, Vec2 b) {
    Segment2 s;
    s.kind = Kind::Line;
    s.p[0] = a;
    s.p[1] = b;
    return s;
}

Segment2 Segment2::quadratic(Vec2 a, Vec2 b, Vec2 c) {
    Segment2 s;
    s.kind = Kind::Quadratic;
    s.p[0] = a;
    s.p[1] = b;
    s.p[2] = c;
    return s;
}

Segment2 Segment2::cubic(Vec2 a, Vec2 b, Vec2 c, Vec2 d) {
    Segment2 s;
    s.kind = Kind::Cubic;
    s.p[0] = a;
    s.p[1] = b;
    s.p[2] = c;
    s.p[3] = d;
    return s;
}

Segment2 Segment2::arc(Vec2 center, Vec2 axisA, Vec2 axisB, double th0, double th1) {
    Segment2 s;
    s.kind = Kind::Arc;
    s.p[1] = center;
    s.p[2] = axisA;
    s.p[3] = axisB;
    s.th0 = th0;
    s.th1 = th1;
    s.p[0] = center + axisA * std::cos(th0) + axisB * std::sin(th0);
    const bool fullTurn = th1 - th0 >= 2.0 * kPi;
    s.end = fullTurn ? s.p[0] : center + axisA * std::cos(th1) + axisB * std::sin(th1);
    return s;
}

Segment2 Segment2::circle(Vec2 center, double radius) {
    return arc(center, {radius, 0.0}, {0.0, radius}, 0.0, 2.0 * kPi);
}

Vec2 Segment2::finish() const {
    switch (kind) {
        case Kind::Line:
            return p[1];
        case Kind::Quadratic:
            return p[2];
        case Kind::Cubic:
            return p[3];
        case Kind::Arc:
            return end;
    }
    return p[0];
}

Vec2 Segment2::at(double u) const {
    const double v = 1.0 - u;
    switch (kind) {
        case Kind::Line:
            return p[0] + (p[1] - p[0]) * u;
        case Kind::Quadratic:
            return p[0] * (v * v) + p[1] * (2.0 * u * v) + p[2] * (u * u);
        case Kind::Cubic:
            return p[0] * (v * v * v) + p[1] * (3.0 * u * v * v) + p[2] * (3.0 * u * u * v) +
                   p[3] * (u * u * u);
        case Kind::Arc: {
            const double th = th0 + u * (th1 - th0);
            return p[1] + p[2] * std::cos(th) + p[3] * std::sin(th);
        }
    }
    return p[0];
}

Vec2 Segment2::tangent(double u) const {
    const double v = 1.0 - u;
    switch (kind) {
        case Kind::Line:
            return p[1] - p[0];
        case Kind::Quadratic:
            return ((p[1] - p[0]) * v + (p[2] - p[1]) * u) * 2.0;
        case Kind::Cubic:
            return ((p[1] - p[0]) * (v * v) + (p[2] - p[1]) * (2.0 * u * v) +
                    (p[3] - p[2]) * (u * u)) *
                   3.0;
        case Kind::Arc: {
            const double th = th0 + u * (th1 - th0);
            return (p[3] * std::cos(th) - p[2] * std::sin(th)) * (th1 - th0);
        }
    }
    return {1.0, 0.0};
}

Segment2 Segment2::mapped(const glm::dmat2& m, Vec2 shift) const {
    Segment2 s = *this;
    if (kind == Kind::Arc) {
        s.p[0] = m * p[0] + shift;
        s.p[1] = m * p[1] + shift;
        s.p[2] = m * p[2];
        s.p[3] = m * p[3];
        s.end = m * end + shift;
        return s;
    }
    for (Vec2& q : s.p) q = m * q + shift;
    return s;
}

Bounds2 Segment2::bounds() const {
    Bounds2 b;
    switch (kind) {
        case Kind::Line:
            b.add(p[0]);
            b.add(p[1]);
            break;
        case Kind::Quadratic:
            for (int i = 0; i < 3; ++i) b.add(p[i]);
            break;
        case Kind::Cubic:
            for (const Vec2& q : p) b.add(q);
            break;
        case Kind::Arc: {
            // The whole ellipse's box: half-extent sqrt(a_i^2 + b_i^2) per axis.
            const Vec2 half(std::hypot(p[2].x, p[3].x), std::hypot(p[2].y, p[3].y));
            b.add(p[1] - half);
            b.add(p[1] + half);
            break;
        }
    }
    return b;
}

Bounds2 Outline::bounds() const {
    Bounds2 b;
    for (const Segment2& s : segments) {
        const Bounds2 one = s.bounds();
        b.add(one.lo);
        b.add(one.hi);
    }
    return b;
}

void Outline::crossSegment(uint32_t i, Vec2 o, Vec2 d, std::vector<Crossing2>& out) const {
    const double dd = glm::dot(d, d);
    const Segment2& s = segments[i];
    const Vec2 a = s.start(), b = s.finish();
    const double sa = side(o, d, a), sb = side(o, d, b);
    const bool negA = sa < 0.0, negB = sb < 0.0;
    if (s.kind == Segment2::Kind::Line) {
        if (negA == negB) return;
        // From the end nearer the line: the rounding of the step is then that of the shorter
        // part of the segment.
        const Vec2 q = std::abs(sa) <= std::abs(sb) ? a + (b - a) * (sa / (sa - sb))
                                                    : b + (a - b) * (sb / (sb - sa));
        out.push_back({glm::dot(q - o, d) / dd, i, int8_t(negA ? 1 : -1)});
        return;
    }
    // The side's sign on each piece between the roots (read at the piece's middle, so
    // a double root changes nothing) and at the ends (by the rule above): a crossing
    // wherever consecutive signs differ, at a root or at an end.
    double u[5];
    const int n = curvedRoots(s, o, d, u);
    u[n] = 1.0;
    bool negBefore = negA;
    double lo = 0.0;
    for (int k = 0; k <= n; ++k) {
        const double hi = u[k];
        const bool neg = side(o, d, s.at(0.5 * (lo + hi))) < 0.0;
        if (neg != negBefore)
            out.push_back(
                {glm::dot((k == 0 ? a : s.at(lo)) - o, d) / dd, i, int8_t(negBefore ? 1 : -1)});
        negBefore = neg;
        lo = hi;
    }
    if (negBefore != negB) out.push_back({glm::dot(b - o, d) / dd, i, int8_t(negBefore ? 1 : -1)});
}

void Outline::crossings(Vec2 o, Vec2 d, std::vector<Crossing2>& out) const {
    if (nodes.empty()) {
        for (uint32_t i = 0; i < segments.size(); ++i) crossSegment(i, o, d, out);
        return;
    }
    const double scale = std::abs(d.x) + std::abs(d.y);
    uint32_t stack[64];
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
        const OutlineNode& node = nodes[stack[--top]];
        // The line meets the box when the box's extent across the line reaches its centre's
        // side value; boxes are widened (buildIndex), so rounding never culls a crossing.
        const Vec2 c = 0.5 * (node.box.lo + node.box.hi), h = 0.5 * (node.box.hi - node.box.lo);
        if (std::abs(side(o, d, c)) >
            std::abs(d.y) * h.x + std::abs(d.x) * h.y +
                kLineBoxSlack * scale * (std::abs(c.x - o.x) + std::abs(c.y - o.y)))
            continue;
        if (node.count > 0) {
            for (uint32_t k = 0; k < node.count; ++k)
                crossSegment(order[node.first + k], o, d, out);
            continue;
        }
        stack[top++] = node.right;
        stack[top++] = uint32_t(&node - nodes.data()) + 1;
    }
}

void Outline::buildIndex() {
    nodes.clear();
    order.clear();
    if (segments.size() <= kIndexMinSegments) return;
    std::vector<Bounds2> boxes(segments.size());
    Bounds2 all;
    for (uint32_t i = 0; i < segments.size(); ++i) {
        boxes[i] = segments[i].bounds();
        all.add(boxes[i].lo);
        all.add(boxes[i].hi);
        order.push_back(i);
    }
    // Widened by a part in 10^9 of the whole outline: far above the rounding of a side value.
    const double margin = kBoxWidenRel * std::max(1.0, glm::length(all.hi - all.lo));
    const auto build = [&](auto& self, uint32_t first, uint32_t count) -> uint32_t {
        const uint32_t index = uint32_t(nodes.size());
        nodes.emplace_back();
        Bounds2 box;
        for (uint32_t k = first; k < first + count; ++k) {
            box.add(boxes[order[k]].lo);
            box.add(boxes[order[k]].hi);
        }
        box.lo -= Vec2(margin), box.hi += Vec2(margin);
        nodes[index].box = box;
        if (count <= 4) {
            nodes[index].first = first, nodes[index].count = count;
            return index;
        }
        const int axis = box.hi.x - box.lo.x >= box.hi.y - box.lo.y ? 0 : 1;
        const auto mid = order.begin() + first + count / 2;
        std::nth_element(order.begin() + first, mid, order.begin() + first + count,
                         [&](uint32_t a, uint32_t b) {
                             return boxes[a].lo[axis] + boxes[a].hi[axis] <
                                    boxes[b].lo[axis] + boxes[b].hi[axis];
                         });
        self(self, first, count / 2);
        const uint32_t right = self(self, first + count / 2, count - count / 2);
        nodes[index].right = right;
        return index;
    };
    build(build, 0, uint32_t(segments.size()));
}

bool Outline::inside(Vec2 p) const {
    thread_local std::vector<Crossing2> found;
    found.clear();
    crossings(p, Vec2(1.0, 0.0), found);
    int winding = 0;
    for (const Crossing2& c : found)
        if (c.t > 0.0) winding += c.winding;
    return filled(winding);
}

double Outline::nearestParameter(uint32_t segment, Vec2 q) const {
    const Segment2& s = segments[segment];
    if (s.kind == Segment2::Kind::Line) {
        const Vec2 e = s.p[1] - s.p[0];
        const double ee = glm::dot(e, e);
        return ee > 0.0 ? std::clamp(glm::dot(q - s.p[0], e) / ee, 0.0, 1.0) : 0.0;
    }
    if (s.kind == Segment2::Kind::Arc) {
        const double theta = intoTurn(arcAngle(s, q), s.th0);
        const double span = s.th1 - s.th0;
        if (theta <= s.th1) return (theta - s.th0) / span;
        // Past the arc's end: whichever end is nearer.
        return glm::distance(s.p[0], q) < glm::distance(s.end, q) ? 0.0 : 1.0;
    }
    // A Bezier: the best of 33 samples, then golden-section search around it.
    constexpr int kSamples = 32;
    double best = 0.0, bestDist = kInfinity;
    for (int k = 0; k <= kSamples; ++k) {
        const double u = double(k) / kSamples;
        const double dist = glm::distance(s.at(u), q);
        if (dist < bestDist) bestDist = dist, best = u;
    }
    double lo = std::max(0.0, best - 1.0 / kSamples), hi = std::min(1.0, best + 1.0 / kSamples);
    const double g = 0.5 * (std::sqrt(5.0) - 1.0);
    for (int it = 0; it < 60; ++it) {
        const double m1 = hi - g * (hi - lo), m2 = lo + g * (hi - lo);
        if (glm::distance(s.at(m1), q) < glm::distance(s.at(m2), q))
            hi = m2;
        else
            lo = m1;
    }
    return 0.5 * (lo + hi);
}

Vec2 Outline::outwardNormal(uint32_t segment, Vec2 q) const {
    const Segment2& s = segments[segment];
    const double u = nearestParameter(segment, q);
    Vec2 t = s.tangent(u);
    if (t == Vec2(0.0)) t = s.finish() - s.start();  // a cusp or degenerate arc
    // Scaled to its largest component first, so that a huge tangent does not overflow.
    const double size = std::max(std::abs(t.x), std::abs(t.y));
    if (!(size > 0.0) || !std::isfinite(size)) return {1.0, 0.0};
    Vec2 n = glm::normalize(Vec2(t.y, -t.x) / size);
    // Which side is inside is the fill rule's business: step off the boundary and ask.
    const Bounds2 box = bounds();
    const double step = 1e-7 * std::max(1.0, glm::length(box.hi - box.lo));
    const Vec2 on = s.at(u);
    if (inside(on + n * step) && !inside(on - n * step)) n = -n;
    return n;
}

Outline Outline::mapped(const glm::dmat2& m, Vec2 shift) const {
    Outline out;
    out.rule = rule;
    out.segments.reserve(segments.size());
    for (const Segment2& s : segments) out.segments.push_back(s.mapped(m, shift));
    out.buildIndex();
    return out;
}

}  // namespace csg
