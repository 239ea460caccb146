// A region of the plane given by its boundary: closed curves made of segments (straight
// lines, elliptic arcs, quadratic and cubic Beziers) and a fill rule. It is the profile of the
// extrusions (primitives/Extrusion.h) and, with no extrusion, OpenSCAD's 2-D shapes.
//
// Notation: a line of the plane is o + t d; side(p) = cross(d, p - o) tells which side of it
// p lies on, and a point with side exactly 0 counts as positive. A straight segment is crossed
// when its two ends' sides differ. Because a vertex shared by two segments has one side value
// (the same expression of the same doubles), the crossings of a closed curve always pair up,
// whatever the rounding: a line through a vertex is crossed once there, a line touching a
// vertex 0 or 2 times. A curved segment's side is read at its ends (by the same rule) and in
// the middle of each piece between the roots of its side function: it is crossed wherever
// two consecutive signs differ, so a double root crosses nothing and a root the solver put
// just past an end still leaves the ends' parity.
//
// The region is the set of points whose crossing count (even-odd, polygon()) or winding
// number (nonzero, glyphs and unions) along any line is odd (non-zero). Segments need not be
// in contour order: the region depends only on the multiset of directed segments.
#pragma once

#include <cstdint>
#include <vector>

#include "primitives/base/Math.h"

namespace csg {

// An axis-aligned box of the plane.
struct Bounds2 {
    Vec2 lo{kInfinity};
    Vec2 hi{-kInfinity};
    bool empty() const { return lo.x > hi.x || lo.y > hi.y; }
    void add(Vec2 p) {
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
    }
};

struct Segment2 {
    enum class Kind : uint8_t { Line, Arc, Quadratic, Cubic };
    Kind kind = Kind::Line;
    // Line: p[0] -> p[1]. Quadratic: control points p[0..2]. Cubic: p[0..3].
    // Arc: the ellipse c + a cos(th) + b sin(th) for th from th0 to th1 (th0 < th1, at most a
    // full turn), with c = p[1], a = p[2], b = p[3]; p[0] is its start point and end its end
    // point, stored so that the neighbouring segments share the very same doubles.
    Vec2 p[4]{};
    Vec2 end{};  // Arc only
    double th0 = 0.0, th1 = 0.0;

    static Segment2 line(Vec2 a, Vec2 b);
    static Segment2 quadratic(Vec2 a, Vec2 b, Vec2 c);
    static Segment2 cubic(Vec2 a, Vec2 b, Vec2 c, Vec2 d);
    // A circular or elliptic arc; a full turn (th1 = th0 + 2 pi) closes on itself.
    static Segment2 arc(Vec2 center, Vec2 axisA, Vec2 axisB, double th0, double th1);
    // The whole circle about `center`, counter-clockwise from angle 0: arc's full turn.
    static Segment2 circle(Vec2 center, double radius);

    Vec2 start() const { return p[0]; }
    Vec2 finish() const;
    // The point at parameter u in [0, 1].
    Vec2 at(double u) const;
    // The derivative with respect to u.
    Vec2 tangent(double u) const;
    // A box holding the segment (for a Bezier its control points' box, for an arc its
    // ellipse's).
    Bounds2 bounds() const;
    // The same segment under the affine map x -> m * x + shift.
    Segment2 mapped(const glm::dmat2& m, Vec2 shift) const;
};

enum class FillRule : uint8_t { EvenOdd, NonZero };

// A crossing of a line with the boundary: the line parameter, the segment crossed and the
// winding step (+1 when the boundary crosses the line from its negative to its positive side).
struct Crossing2 {
    double t;
    uint32_t segment;
    int8_t winding;
};

// A node of an outline's segment hierarchy: a leaf holds segments order[first, first + count),
// an inner node (count 0) has its left child next to it and its right child at `right`.
struct OutlineNode {
    Bounds2 box;  // widened: see Outline::buildIndex
    uint32_t first = 0, count = 0, right = 0;
};

struct Outline {
    std::vector<Segment2> segments;
    FillRule rule = FillRule::EvenOdd;
    // A binary hierarchy of the segments' boxes, so that a line meets O(log n) of them in a
    // smooth outline; empty (every segment tried) until buildIndex(), and for few segments.
    std::vector<OutlineNode> nodes;
    std::vector<uint32_t> order;

    // Builds the hierarchy (call once the segments are final; mapped() and
    // Extrusion::plane() do).
    void buildIndex();
    bool indexed() const { return !nodes.empty() || segments.size() <= kIndexMinSegments; }
    static constexpr size_t kIndexMinSegments = 16;

    Bounds2 bounds() const;
    // Whether p is in the region (a point on the boundary may go either way).
    bool inside(Vec2 p) const;
    // Appends the crossings of the line o + t d (d != 0) in the order of the segments, not
    // of t. The caller sorts.
    void crossings(Vec2 o, Vec2 d, std::vector<Crossing2>& out) const;
    // Calls f(i) for every segment i whose (widened) box may meet `box`: all of them when
    // there is no hierarchy.
    template <class F>
    void forSegmentsIn(const Bounds2& box, F&& f) const;
    // The crossings of the line with segment i (see crossings()).
    void crossSegment(uint32_t i, Vec2 o, Vec2 d, std::vector<Crossing2>& out) const;
    // Whether a winding number or crossing count means inside, by the fill rule.
    bool filled(int winding) const {
        return rule == FillRule::EvenOdd ? (winding & 1) != 0 : winding != 0;
    }
    // The unit normal of segment i at (or nearest to) q, pointing out of the region.
    Vec2 outwardNormal(uint32_t segment, Vec2 q) const;
    // The parameter u of segment i nearest to q.
    double nearestParameter(uint32_t segment, Vec2 q) const;
    // This outline under the affine map x -> m * x + shift (a mirror keeps the same region:
    // crossing counts and winding magnitudes do not depend on orientation... except the
    // winding sign, which both fill rules ignore).
    Outline mapped(const glm::dmat2& m, Vec2 shift) const;
};

template <class F>
void Outline::forSegmentsIn(const Bounds2& box, F&& f) const {
    if (nodes.empty()) {
        for (uint32_t i = 0; i < segments.size(); ++i) f(i);
        return;
    }
    uint32_t stack[64];
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
        const uint32_t index = stack[--top];
        const OutlineNode& node = nodes[index];
        if (node.box.lo.x > box.hi.x || node.box.hi.x < box.lo.x || node.box.lo.y > box.hi.y ||
            node.box.hi.y < box.lo.y)
            continue;
        if (node.count > 0) {
            for (uint32_t k = 0; k < node.count; ++k) f(order[node.first + k]);
            continue;
        }
        stack[top++] = node.right;
        stack[top++] = index + 1;
    }
}

}  // namespace csg
