#include "csg/mesh/EarClip.h"

#include <algorithm>
#include <cmath>

namespace csg {

namespace {

double cross(const Vec2& a, const Vec2& b) {
    return a.x * b.y - a.y * b.x;
}

// Twice the signed area of the triangle abc: positive when it turns counter-clockwise.
double turn(const Vec2& a, const Vec2& b, const Vec2& c) {
    return cross(b - a, c - a);
}

// The loop being cut, as a ring of nodes; a corner shared by a bridge appears in two nodes.
class Ring {
public:
    explicit Ring(std::span<const Vec2> points) : points_(points) {}

    // A closed ring of the loop's corners, in its order; returns one node of it.
    uint32_t addLoop(const std::vector<uint32_t>& loop) {
        const uint32_t first = uint32_t(nodes_.size());
        for (size_t i = 0; i < loop.size(); ++i) {
            const uint32_t self = first + uint32_t(i);
            nodes_.push_back({loop[i], i == 0 ? first + uint32_t(loop.size()) - 1 : self - 1,
                              i + 1 == loop.size() ? first : self + 1});
        }
        return first;
    }

    // Joins the hole ring holding `hole` to the ring holding `start` by a bridge (see the header).
    // False when the hole sees no edge to its right (it is not inside).
    bool bridge(uint32_t start, uint32_t hole, double minHeight) {
        uint32_t m = hole;
        for (uint32_t n = next(hole); n != hole; n = next(n))
            if (at(n).x > at(m).x) m = n;
        const Vec2 pm = at(m);
        // The nearest crossing of the ray pm + (s, 0), s >= 0, with an edge of the outer ring.
        double bestX = INFINITY;
        uint32_t edge = kNone;
        forEach(start, [&](uint32_t p) {
            const Vec2 a = at(p), b = at(next(p));
            if (a.y == b.y || (a.y - pm.y) * (b.y - pm.y) > 0.0) return;
            const double x = a.x + (pm.y - a.y) * (b.x - a.x) / (b.y - a.y);
            if (x >= pm.x && x < bestX) bestX = x, edge = p;
        });
        if (edge == kNone) return false;
        uint32_t p = at(next(edge)).x > at(edge).x ? next(edge) : edge;
        const Vec2 crossing(bestX, pm.y);
        // A corner inside the triangle (pm, crossing, p) would hide p: the one seen at the
        // smallest angle from the ray is visible instead.
        if (at(p) != crossing) {
            const Vec2 pp = at(p);
            double bestTan = INFINITY, bestDistance = INFINITY;
            const uint32_t seen = p;
            forEach(start, [&](uint32_t r) {
                if (r == seen) return;
                const Vec2 pr = at(r);
                if (!(pr.x >= pm.x) || !insideOrOn(pm, crossing, pp, pr)) return;
                const double tangent = std::abs(pr.y - pm.y) / std::max(pr.x - pm.x, 1e-300);
                const double distance = pr.x - pm.x;
                if (tangent < bestTan || (tangent == bestTan && distance < bestDistance))
                    bestTan = tangent, bestDistance = distance, p = r;
            });
        }
        // A corner within minHeight of the bridge lies on it but for rounding (a glyph's counter
        // level with the bowl's edge, 7e-15 apart): a bridge past it would leave it on a
        // diagonal, a spike no ear can cut. The nearest such corner is the end instead; the
        // bridge then runs on into its edge, a straight corner a neighbour's ear takes.
        {
            const Vec2 pp = at(p);
            const double length = glm::length(pp - pm);
            double nearest = length;
            const uint32_t seen = p;
            forEach(start, [&](uint32_t r) {
                if (r == seen || nodes_[r].point == nodes_[seen].point) return;
                const Vec2 pr = at(r);
                const double along = glm::dot(pr - pm, pp - pm) / length;
                if (!(along > 0.0 && along < nearest) ||
                    std::abs(turn(pm, pp, pr)) > minHeight * length)
                    return;
                nearest = along, p = r;
            });
        }
        // A corner already met by a bridge has two nodes: take the one whose corner opens
        // towards the hole.
        if (!opensTowards(p, pm)) {
            const uint32_t seen = p;
            forEach(start, [&](uint32_t r) {
                if (r != seen && nodes_[r].point == nodes_[seen].point && opensTowards(r, pm))
                    p = r;
            });
        }
        split(p, m);
        return true;
    }

    // Cuts ears from the ring holding start until a triangle is left; false when it sticks.
    bool clip(uint32_t start, double minHeight, std::vector<std::array<uint32_t, 3>>& out) {
        uint32_t count = 0;
        forEach(start, [&](uint32_t) { ++count; });
        uint32_t b = start, stale = 0;
        while (count > 3) {
            if (isEar(b, minHeight)) {
                out.push_back({nodes_[prev(b)].point, nodes_[b].point, nodes_[next(b)].point});
                const uint32_t a = prev(b), c = next(b);
                nodes_[a].next = c, nodes_[c].prev = a;
                b = c;
                --count;
                stale = 0;
            } else {
                b = next(b);
                if (++stale > count) return false;
            }
        }
        if (!convex(b, minHeight)) return false;
        out.push_back({nodes_[prev(b)].point, nodes_[b].point, nodes_[next(b)].point});
        return true;
    }

private:
    struct Node {
        uint32_t point, prev, next;
    };
    static constexpr uint32_t kNone = UINT32_MAX;

    const Vec2& at(uint32_t n) const { return points_[nodes_[n].point]; }
    uint32_t next(uint32_t n) const { return nodes_[n].next; }
    uint32_t prev(uint32_t n) const { return nodes_[n].prev; }

    template <class Fn>
    void forEach(uint32_t start, Fn&& fn) const {
        uint32_t n = start;
        do {
            fn(n);
            n = next(n);
        } while (n != start);
    }

    // Whether q lies in the triangle abc or on its edges, whichever way abc turns.
    static bool insideOrOn(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& q) {
        const double s = turn(a, b, q), t = turn(b, c, q), u = turn(c, a, q);
        return (s >= 0.0 && t >= 0.0 && u >= 0.0) || (s <= 0.0 && t <= 0.0 && u <= 0.0);
    }

    // Whether the corner at node b turns left by more than minHeight off its neighbours' line.
    bool convex(uint32_t b, double minHeight) const {
        const Vec2 pa = at(prev(b)), pb = at(b), pc = at(next(b));
        return turn(pa, pb, pc) > minHeight * glm::length(pc - pa);
    }

    // Whether the point q lies in the region's side of the corner at node b (between its
    // incoming and outgoing edges, the inside on their left).
    bool opensTowards(uint32_t b, const Vec2& q) const {
        const Vec2 pa = at(prev(b)), pb = at(b), pc = at(next(b));
        const bool leftOfIn = turn(pa, pb, q) > 0.0, leftOfOut = turn(pb, pc, q) > 0.0;
        return turn(pa, pb, pc) >= 0.0 ? leftOfIn && leftOfOut : leftOfIn || leftOfOut;
    }

    // An ear: a convex corner whose triangle holds no other corner of the ring (corners met by a
    // bridge, being the triangle's own, excepted). A corner within minHeight outside the new
    // edge c -> a blocks it too: a corner that lies on that diagonal but for rounding would be
    // left touching the ring's new edge, a spike of no width that no ear can cut.
    bool isEar(uint32_t b, double minHeight) const {
        if (!convex(b, minHeight)) return false;
        const uint32_t a = prev(b), c = next(b);
        const uint32_t ia = nodes_[a].point, ib = nodes_[b].point, ic = nodes_[c].point;
        const Vec2 pa = at(a), pb = at(b), pc = at(c);
        const Vec2 lo = glm::min(pa, glm::min(pb, pc)) - minHeight,
                   hi = glm::max(pa, glm::max(pb, pc)) + minHeight;
        const double graze = -minHeight * glm::length(pa - pc);
        for (uint32_t n = next(c); n != a; n = next(n)) {
            const uint32_t in = nodes_[n].point;
            if (in == ia || in == ib || in == ic) continue;
            const Vec2 q = points_[in];
            if (q.x < lo.x || q.x > hi.x || q.y < lo.y || q.y > hi.y) continue;
            if (turn(pa, pb, q) >= 0.0 && turn(pb, pc, q) >= 0.0 && turn(pc, pa, q) >= graze)
                return false;
        }
        return true;
    }

    // Splices the bridge p -> m, around the hole ring, m' -> p' into the outer ring.
    void split(uint32_t p, uint32_t m) {
        const uint32_t p2 = uint32_t(nodes_.size()), m2 = p2 + 1;
        nodes_.push_back({nodes_[p].point, m2, next(p)});
        nodes_.push_back({nodes_[m].point, prev(m), p2});
        nodes_[next(p)].prev = p2;
        nodes_[prev(m)].next = m2;
        nodes_[p].next = m;
        nodes_[m].prev = p;
    }

    std::span<const Vec2> points_;
    std::vector<Node> nodes_;
};

}  // namespace

double signedArea(std::span<const Vec2> points, const std::vector<uint32_t>& loop) {
    double sum = 0.0;
    for (size_t i = 0, k = loop.size(); i < k; ++i)
        sum += cross(points[loop[i]], points[loop[(i + 1) % k]]);
    return 0.5 * sum;
}

bool earClip(std::span<const Vec2> points, const std::vector<uint32_t>& outer,
             const std::vector<std::vector<uint32_t>>& holes, double minHeight,
             std::vector<std::array<uint32_t, 3>>& out) {
    if (outer.size() < 3) return false;
    Ring ring(points);
    std::vector<uint32_t> counterClockwise = outer;
    if (signedArea(points, counterClockwise) < 0.0)
        std::reverse(counterClockwise.begin(), counterClockwise.end());
    const uint32_t start = ring.addLoop(counterClockwise);
    // Holes from the rightmost in: a hole's ray to the right then meets no hole not yet joined.
    std::vector<std::pair<double, uint32_t>> order;
    std::vector<uint32_t> firsts;
    for (const auto& hole : holes) {
        if (hole.size() < 3) return false;
        std::vector<uint32_t> clockwise = hole;
        if (signedArea(points, clockwise) > 0.0) std::reverse(clockwise.begin(), clockwise.end());
        double right = -INFINITY;
        for (const uint32_t i : clockwise) right = std::max(right, points[i].x);
        order.push_back({right, uint32_t(firsts.size())});
        firsts.push_back(ring.addLoop(clockwise));
    }
    std::sort(order.begin(), order.end(), std::greater<>());
    for (const auto& [right, index] : order)
        if (!ring.bridge(start, firsts[index], minHeight)) return false;
    const size_t before = out.size();
    if (ring.clip(start, minHeight, out)) return true;
    out.resize(before);
    return false;
}

}  // namespace csg
