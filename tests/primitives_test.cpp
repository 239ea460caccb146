// Tests of the primitives. The oracles are independent of the code under test:
//   - inside(), a one-line point-membership test, judges random lines by sampling: points
//     strictly within a span are inside, points beyond its ends (by a margin) are outside, and
//     a line aimed through a point deep inside must report a span covering that point;
//   - hand-derived values for exact cases (axis rays, apex, tangents, degenerate cones);
//   - 113-bit arithmetic (Boost.Multiprecision) for far and tiny spheres and far axis rays;
//   - black-box maximisation over surface samples for the tightness of boundsUnder.
// Notation: t is the parameter of o + t d; tSize = size / |d| is the t needed to travel one
// size of the primitive, the unit every margin below is measured in.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <boost/multiprecision/cpp_bin_float.hpp>
#include <cmath>
#include <cstdint>
#include <iomanip>
#include <iostream>
#include <iterator>
#include <numbers>
#include <sstream>
#include <string>

#include "primitives/Primitives.h"
#include "primitives/solvers/LinePoint.h"
#include "tests/SeededRng.h"

namespace csg {
namespace {

constexpr double kPi = std::numbers::pi;

// A point this far beyond a span end (unit: size) must be outside. Rounding in a span end is
// at most ~1e-8 of the size (near-tangent roots lose half the digits), well inside this.
constexpr double kEndMargin = 1e-7;
// Spans shorter than this (unit: size) are near-tangent: their interior is too shallow for
// inside() to judge reliably after rounding, so only their ends are checked.
constexpr double kShortSpan = 1e-6;
// A point at least this far inside (unit: size) is "deep": a line through it must hit.
constexpr double kDeep = 1e-6;

// ---- Random inputs, reproducible on every standard library ----

using testing::Rng;

// A magnitude from 1e-3 to 1e3, uniform in its logarithm.
double magnitude(Rng& rng) {
    return std::pow(10.0, rng.uniform(-3.0, 3.0));
}
// Random orientation, magnitude from 1e-3 to 1e3. The magnitude is drawn first, as gcc
// evaluated the former `unit() * magnitude()`, so each seed keeps its lines.
Vec3 direction(Rng& rng) {
    const double m = magnitude(rng);
    return rng.unit() * m;
}

std::string describe(const Vec3& o, const Vec3& d) {
    std::ostringstream s;
    s << std::setprecision(17) << "o=(" << o.x << ", " << o.y << ", " << o.z << ") d=(" << d.x
      << ", " << d.y << ", " << d.z << ")";
    return s.str();
}

template <class P>
LocalSpans spansOf(const P& prim, const Vec3& o, const Vec3& d) {
    LocalSpans s;
    prim.spans(o, d, s);
    return s;
}

// The t range where o + t d is inside box b, computed here rather than by the code under test.
bool clipLine(const Vec3& o, const Vec3& d, const Bounds3& b, double& t0, double& t1) {
    t0 = -kInfinity, t1 = kInfinity;
    for (int a = 0; a < 3; ++a) {
        if (d[a] == 0.0) {
            if (o[a] < b.lo[a] || o[a] > b.hi[a]) return false;
            continue;
        }
        const double u = (b.lo[a] - o[a]) / d[a], v = (b.hi[a] - o[a]) / d[a];
        t0 = std::max(t0, std::min(u, v));
        t1 = std::min(t1, std::max(u, v));
    }
    return t0 <= t1 && std::isfinite(t0) && std::isfinite(t1);
}

// p is inside by a margin: the six points kDeep * size away along the axes are inside too, so
// (by convexity) a ball of radius kDeep * size / sqrt(3) around p is.
template <class P>
bool deepInside(const P& prim, const Vec3& p, double size) {
    if (!prim.inside(p)) return false;
    for (int a = 0; a < 3; ++a)
        for (double sgn : {-1.0, 1.0}) {
            Vec3 q = p;
            q[a] += sgn * kDeep * size;
            if (!prim.inside(q)) return false;
        }
    return true;
}

// ---- The property check of one line against a bounded convex primitive ----

struct Line {
    Vec3 o, d;
    double tAim = std::nan("");  // where the line passes a deep interior point, if aimed
};

// Returns "" when the line's spans agree with inside(), else what went wrong.
template <class P>
std::string checkLine(const P& prim, const Line& line, double size, int faceCount) {
    const Vec3 &o = line.o, &d = line.d;
    const LocalSpans s = spansOf(prim, o, d);
    const double dLen = glm::length(d);
    const double tSize = size / dLen;
    const double margin = kEndMargin * tSize;
    const auto at = [&](double t) { return o + t * d; };
    if (s.count > 1) return "a convex primitive gave more than one span";
    for (int i = 0; i < s.count; ++i) {
        const LocalSpans::Entry& e = s.entries[i];
        if (!std::isfinite(e.tIn) || !std::isfinite(e.tOut)) return "a span end is not finite";
        if (e.faceIn >= faceCount || e.faceOut >= faceCount) return "a span end has a bad face";
        if (!(e.tIn <= e.tOut)) return "a span ends before it starts";
        const double len = e.tOut - e.tIn;
        const bool sampled = len > kShortSpan * tSize;
        if (sampled)
            for (double f : {0.25, 0.5, 0.75})
                if (!prim.inside(at(e.tIn + f * len))) return "a point within a span is outside";
        for (double off : {margin, 0.5 * tSize, 1e3 * tSize}) {
            if (prim.inside(at(e.tIn - off))) return "a point before a span is inside";
            if (prim.inside(at(e.tOut + off))) return "a point after a span is inside";
        }
        // Normals at the ends: unit, and the line crosses inward at tIn and outward at tOut.
        for (bool entering : {true, false}) {
            const double t = entering ? e.tIn : e.tOut;
            const Vec3 n = prim.normal(at(t), entering ? e.faceIn : e.faceOut);
            if (!(std::abs(glm::length(n) - 1.0) <= 1e-12)) return "a normal is not unit length";
            const double cosine = glm::dot(n, d) / dLen;
            if (sampled && (entering ? cosine > 1e-9 : cosine < -1e-9))
                return "a normal points the wrong way for the crossing";
        }
    }
    if (std::isfinite(line.tAim)) {
        const bool covered = s.count == 1 && s.entries[0].tIn - margin <= line.tAim &&
                             line.tAim <= s.entries[0].tOut + margin;
        if (!covered) return "the line passes a deep interior point outside every span";
    }
    if (s.count == 0) {
        // Sample where the line crosses the slightly grown bounds: all samples are outside.
        Bounds3 b = prim.bounds();
        b.lo -= Vec3(1e-3 * size);
        b.hi += Vec3(1e-3 * size);
        double t0, t1;
        if (clipLine(o, d, b, t0, t1))
            for (int j = 0; j < 200; ++j)
                if (prim.inside(at(t0 + (t1 - t0) * (j + 0.5) / 200)))
                    return "no span, yet a point on the line is inside";
    }
    return "";
}

// Origins in a box around the bounds (a few far away); directions random or aimed through a
// deep interior point.
template <class P>
Line randomLine(Rng& rng, const P& prim, double size) {
    const Bounds3 box = prim.bounds();
    const Vec3 c = box.center(), h = 1.5 * box.extent() + Vec3(0.1 * size);
    Line line;
    line.o = rng.inBox(c - h, c + h);
    if (rng.chance(0.05)) {
        // One draw per statement, the distance first (gcc's order for the former one
        // expression, so each seed keeps its lines; now the same on every compiler).
        const double far = std::pow(10.0, rng.uniform(1.0, 4.0));
        line.o = c + rng.unit() * size * far;
    }
    if (rng.chance(0.5)) {
        for (int tries = 0; tries < 1000; ++tries) {
            const Vec3 p = rng.inBox(box.lo, box.hi);
            if (!deepInside(prim, p, size)) continue;
            const double scale = magnitude(rng) / glm::length(p - line.o);
            line.d = (p - line.o) * scale;
            line.tAim = 1.0 / scale;
            return line;
        }
    }
    line.d = direction(rng);
    return line;
}

template <class P, class Special>
void runRandomLines(const P& prim, double size, int faceCount, int lines, uint64_t seed,
                    Special special) {
    Rng rng(seed);
    int hits = 0;
    for (int i = 0; i < lines; ++i) {
        Line line = randomLine(rng, prim, size);
        if (rng.chance(0.3)) line = special(rng);
        const std::string err = checkLine(prim, line, size, faceCount);
        ASSERT_TRUE(err.empty()) << err << " at line " << i << ": " << describe(line.o, line.d);
        hits += spansOf(prim, line.o, line.d).count;
    }
    // The generator must exercise hits as well as misses, or the test proves little.
    EXPECT_GT(hits, lines / 4);
    EXPECT_LT(hits, lines);
}

// ---- Random property tests ----

TEST(SphereProperty, RandomLinesAgreeWithInside) {
    for (double r : {1.0, 1e-3, 250.0}) {
        const Sphere sphere{r};
        runRandomLines(sphere, 2 * r, 1, 20000, 11, [&](Rng& rng) {
            // Lines starting on the surface.
            return Line{r * rng.unit(), direction(rng)};
        });
    }
}

TEST(BoxProperty, RandomLinesAgreeWithInside) {
    Rng shapes(21);
    for (int k = 0; k < 4; ++k) {
        const Vec3 lo = shapes.inBox(Vec3(-3.0), Vec3(0.0));
        const Box box{lo, lo + shapes.inBox(Vec3(0.01), Vec3(4.0))};
        const Vec3 e = box.hi - box.lo;
        const double size = std::max({e.x, e.y, e.z});
        runRandomLines(box, size, 6, 20000, 22 + k, [&](Rng& rng) {
            // Zero direction components (parallel to slabs) and origins on face planes.
            Line line{rng.inBox(box.lo - e, box.hi + e), direction(rng)};
            for (int a = 0; a < 3; ++a) {
                if (rng.chance(0.4)) line.d[a] = rng.chance(0.5) ? 0.0 : -0.0;
                if (rng.chance(0.3)) line.o[a] = rng.chance(0.5) ? box.lo[a] : box.hi[a];
            }
            if (line.d == Vec3(0.0)) line.d.x = 1.0;
            return line;
        });
    }
}

const Cylinder kCylinders[] = {
    {2.0, 1.0, 1.0},  {1.0, 1.0, 0.0},  {3.0, 0.0, 1.5},   {0.5, 2.0, 0.7},
    {10.0, 0.1, 0.3}, {0.01, 1.0, 0.0}, {100.0, 0.5, 0.0}, {1.0, 0.25, 3.0},
};

TEST(CylinderProperty, RandomLinesAgreeWithInside) {
    uint64_t seed = 31;
    for (const Cylinder& cyl : kCylinders) {
        const double h = cyl.height, rMax = std::max(cyl.r1, cyl.r2);
        const double size = std::max(h, 2 * rMax);
        const auto radiusAt = [&](double z) { return cyl.r1 + (cyl.r2 - cyl.r1) * z / h; };
        runRandomLines(cyl, size, 3, 20000, seed++, [&](Rng& rng) {
            const Vec3 lo(-2 * rMax, -2 * rMax, -h), hi(2 * rMax, 2 * rMax, 2 * h);
            Line line{rng.inBox(lo, hi), direction(rng)};
            const double a = rng.uniform(0.0, 2 * kPi);
            switch (rng.index(6)) {
                case 0: {  // parallel to the axis, sometimes on the axis or on the lateral surface
                    const double m = magnitude(rng);  // drawn first, as gcc did
                    line.d = Vec3(0.0, 0.0, rng.chance(0.5) ? 1.0 : -1.0) * m;
                    if (rng.chance(0.3)) line.o.x = line.o.y = 0.0;
                    break;
                }
                case 1:  // parallel to the caps, sometimes in a cap plane
                    line.d.z = 0.0;
                    if (rng.chance(0.5)) line.o.z = rng.chance(0.5) ? 0.0 : h;
                    break;
                case 2:  // through the apex (or the centre of a cap)
                    line.d = (Vec3(0.0, 0.0, cyl.r2 == 0.0 ? h : 0.0) - line.o) * magnitude(rng);
                    break;
                case 3:  // parallel to a generator
                    line.d =
                        Vec3((cyl.r2 - cyl.r1) * std::cos(a), (cyl.r2 - cyl.r1) * std::sin(a), h) *
                        magnitude(rng);
                    break;
                case 4: {  // starting on the lateral surface
                    const double z = rng.uniform(0.0, h);
                    line.o = Vec3(radiusAt(z) * std::cos(a), radiusAt(z) * std::sin(a), z);
                    break;
                }
                default:  // starting on a cap
                    // One draw per statement, in gcc's former order: the cap, then y and x
                    // (each from a point of the ball).
                    line.o.z = rng.chance(0.5) ? 0.0 : h;
                    line.o.y = rng.inBall().y * rMax;
                    line.o.x = rng.inBall().x * rMax;
                    break;
            }
            if (line.d == Vec3(0.0)) line.d.z = 1.0;
            return line;
        });
    }
}

// A half-space is unbounded: its spans have one infinite end (face kClipFace) or two.
std::string checkHalfSpaceLine(const HalfSpace& hs, const Vec3& o, const Vec3& d, double size) {
    const LocalSpans s = spansOf(hs, o, d);
    const double tSize = size / glm::length(d);
    const auto at = [&](double t) { return o + t * d; };
    if (s.count > 1) return "more than one span";
    if (s.count == 0) {
        for (double t : {-1e6, -1.0, 0.0, 1.0, 1e6})
            if (hs.inside(at(t * tSize))) return "no span, yet a point on the line is inside";
        return "";
    }
    const LocalSpans::Entry& e = s.entries[0];
    if (std::isnan(e.tIn) || std::isnan(e.tOut)) return "NaN end";
    if (std::isinf(e.tIn) != (e.faceIn == kClipFace) ||
        std::isinf(e.tOut) != (e.faceOut == kClipFace))
        return "an infinite end must carry kClipFace, a finite one face 0";
    if (e.tIn != -kInfinity && e.tOut != kInfinity) return "a half-space span is a half-line";
    if (std::isinf(e.tIn) && std::isinf(e.tOut)) {
        for (double t : {-1e6, -1.0, 0.0, 1.0, 1e6})
            if (!hs.inside(at(t * tSize))) return "whole-line span, yet a point is outside";
        return "";
    }
    const bool solidBefore = std::isinf(e.tIn);
    const double tEnd = solidBefore ? e.tOut : e.tIn;
    if ((solidBefore ? e.faceOut : e.faceIn) != 0) return "the plane is face 0";
    if (std::abs(tEnd) > 1e6 * tSize) return "";  // too far to sample beside it at this margin
    const double sgn = solidBefore ? 1.0 : -1.0;
    // The crossing is ill-conditioned for a grazing line (its error grows like |t| / sin of
    // the angle), so the margin grows with |t| as in the coincidence rule (Tolerances.h).
    for (double off : {kEndMargin * (tSize + std::abs(tEnd)), 0.5 * tSize, 1e3 * tSize}) {
        if (!hs.inside(at(tEnd - sgn * off))) return "a point on the solid side is outside";
        if (hs.inside(at(tEnd + sgn * off))) return "a point beyond the plane is inside";
    }
    const Vec3 n = hs.normal(at(tEnd), 0);
    if (!(std::abs(glm::length(n) - 1.0) <= 1e-12)) return "normal not unit";
    if (sgn * glm::dot(n, d) < 0.0) return "normal points into the solid";
    return "";
}

TEST(HalfSpaceProperty, RandomLinesAgreeWithInside) {
    Rng rng(41);
    for (int i = 0; i < 20000; ++i) {
        HalfSpace hs;
        Vec3 o = rng.inBox(Vec3(-3.0), Vec3(3.0)), d = direction(rng);
        if (rng.chance(0.3)) {
            // Small-integer normals with a direction exactly parallel to the plane.
            Vec3 n;  // drawn z first, as gcc evaluated the former Vec3(...) arguments
            for (int a = 2; a >= 0; --a) n[a] = rng.index(5) - 2;
            hs.planeNormal = n == Vec3(0.0) ? Vec3(0.0, 0.0, 1.0) : n;
            const Vec3& m = hs.planeNormal;
            d = (m.x != 0.0 || m.y != 0.0 ? Vec3(m.y, -m.x, 0.0) : Vec3(1.0, 0.0, 0.0)) *
                std::ldexp(1.0, rng.index(21) - 10);
            hs.offset = rng.uniform(-1.0, 1.0) * glm::length(hs.planeNormal);
            if (rng.chance(0.3)) {
                // On the plane up to rounding, where sampling cannot judge: the contract is
                // all or nothing, decided like inside(o).
                o -= m * ((glm::dot(m, o) - hs.offset) / glm::dot(m, m));
                const LocalSpans s = spansOf(hs, o, d);
                ASSERT_EQ(s.count, hs.inside(o) ? 1 : 0) << describe(o, d);
                if (s.count == 1) {
                    EXPECT_EQ(s.entries[0].tIn, -kInfinity);
                    EXPECT_EQ(s.entries[0].tOut, kInfinity);
                }
                continue;
            }
        } else {
            const double length = std::pow(10.0, rng.uniform(-2.0, 2.0));  // drawn first
            hs.planeNormal = rng.unit() * length;
            hs.offset = rng.uniform(-1.0, 1.0) * glm::length(hs.planeNormal);
        }
        const std::string err = checkHalfSpaceLine(hs, o, d, 1.0);
        ASSERT_TRUE(err.empty()) << err << " at line " << i << ": " << describe(o, d) << " plane "
                                 << describe(hs.planeNormal, Vec3(hs.offset));
    }
}

// ---- Exact cases with hand-derived values ----

constexpr double kExact = 1e-12;

void expectSpan(const LocalSpans& s, double tIn, double tOut, const char* what) {
    ASSERT_EQ(s.count, 1) << what;
    EXPECT_NEAR(s.entries[0].tIn, tIn, kExact) << what;
    EXPECT_NEAR(s.entries[0].tOut, tOut, kExact) << what;
}

void expectFaces(const LocalSpans& s, int faceIn, int faceOut, const char* what) {
    ASSERT_EQ(s.count, 1) << what;
    EXPECT_EQ(s.entries[0].faceIn, faceIn) << what;
    EXPECT_EQ(s.entries[0].faceOut, faceOut) << what;
}

// A touch may be reported as a zero-length span at tTouch or not at all; never as NaN.
void expectTouchOrMiss(const LocalSpans& s, double tTouch, double tol, const char* what) {
    ASSERT_LE(s.count, 1) << what;
    if (s.count == 0) return;
    EXPECT_NEAR(s.entries[0].tIn, tTouch, tol) << what;
    EXPECT_NEAR(s.entries[0].tOut, tTouch, tol) << what;
}

TEST(SphereExact, AxisTangentAndSurfaceRays) {
    const Sphere s{2.0};
    expectSpan(spansOf(s, {-5, 0, 0}, {2, 0, 0}), 1.5, 3.5, "x axis, |d| = 2");
    expectSpan(spansOf(s, {0, 0, 10}, {0, 0, -0.5}), 16.0, 24.0, "z axis, backwards");
    // Chord at height 1.2: half-length sqrt(4 - 1.44) = 1.6.
    expectSpan(spansOf(s, {-4, 1.2, 0}, {1, 0, 0}), 2.4, 5.6, "chord");
    expectTouchOrMiss(spansOf(s, {-5, 2, 0}, {1, 0, 0}), 5.0, 1e-7, "tangent");
    EXPECT_EQ(spansOf(s, {-5, 2.000001, 0}, {1, 0, 0}).count, 0) << "just missing";
    expectSpan(spansOf(s, {2, 0, 0}, {-1, 0, 0}), 0.0, 4.0, "starting on the surface");
    expectTouchOrMiss(spansOf(s, {2, 0, 0}, {0, 1, 0}), 0.0, 1e-7, "tangent from the surface");
    EXPECT_EQ(spansOf(s, {-5, 0, 0}, {0, 0, 0}).count, 0) << "zero direction";
}

TEST(BoxExact, AxisFacePlaneAndParallelRays) {
    const Box b{{-1, -2, -3}, {1, 2, 3}};
    LocalSpans s = spansOf(b, {-5, 0, 0}, {1, 0, 0});
    expectSpan(s, 4.0, 6.0, "+x");
    expectFaces(s, 0, 1, "+x");
    s = spansOf(b, {5, 0, 0}, {-0.5, 0, 0});
    expectSpan(s, 8.0, 12.0, "-x");
    expectFaces(s, 1, 0, "-x");
    s = spansOf(b, {0, 0, 10}, {0, 0, -2});
    expectSpan(s, 3.5, 6.5, "-z");
    expectFaces(s, 5, 4, "-z");
    expectSpan(spansOf(b, {-5, 2, 0}, {1, 0, 0}), 4.0, 6.0, "in the face plane y = 2");
    expectSpan(spansOf(b, {-5, 2, 3}, {1, 0, 0}), 4.0, 6.0, "along the edge y = 2, z = 3");
    EXPECT_EQ(spansOf(b, {-5, 2.5, 0}, {1, 0, 0}).count, 0) << "parallel outside the y slab";
    EXPECT_EQ(spansOf(b, {-5, -0.0, 0}, {1, -0.0, 0.0}).count, 1) << "signed zeros";
    // Diagonal through two corners: (-1,-2,-3) at t = 1, (1, 2, 3) at t = 2.
    s = spansOf(b, {-3, -6, -9}, {2, 4, 6});
    expectSpan(s, 1.0, 2.0, "corner to corner");
    // Starting on the +x face and leaving: the line crossed the box before, from t = -2.
    expectSpan(spansOf(b, {1, 0, 0}, {1, 1, 0}), -2.0, 0.0, "leaving from a face");
    // Through the edge x = 1, y = 2 only: a touch at t = 0.
    expectTouchOrMiss(spansOf(b, {1, 2, 0}, {1, -1, 0}), 0.0, 0.0, "touching an edge");
    expectSpan(spansOf(b, {1, 0, 0}, {-1, 0, 0}), 0.0, 2.0, "entering from a face");
    EXPECT_EQ(spansOf(b, {0, 0, 0}, {0, 0, 0}).count, 0) << "zero direction";
}

TEST(CylinderExact, CylinderRays) {
    const Cylinder c{4.0, 1.0, 1.0};
    LocalSpans s = spansOf(c, {0, 0, -1}, {0, 0, 1});
    expectSpan(s, 1.0, 5.0, "along the axis");
    expectFaces(s, 1, 2, "along the axis");
    s = spansOf(c, {0.5, 0, 6}, {0, 0, -2});
    expectSpan(s, 1.0, 3.0, "parallel to the axis, downwards");
    expectFaces(s, 2, 1, "parallel to the axis, downwards");
    expectSpan(spansOf(c, {1, 0, -1}, {0, 0, 1}), 1.0, 5.0, "in the lateral surface");
    EXPECT_EQ(spansOf(c, {1.5, 0, -1}, {0, 0, 1}).count, 0) << "parallel, outside";
    s = spansOf(c, {-3, 0, 2}, {1, 0, 0});
    expectSpan(s, 2.0, 4.0, "across");
    expectFaces(s, 0, 0, "across");
    expectSpan(spansOf(c, {-3, 0, 0}, {1, 0, 0}), 2.0, 4.0, "in the bottom cap plane");
    expectSpan(spansOf(c, {-3, 0, 4}, {1, 0, 0}), 2.0, 4.0, "in the top cap plane");
    EXPECT_EQ(spansOf(c, {-3, 0, 4.0001}, {1, 0, 0}).count, 0) << "just above the top";
    expectTouchOrMiss(spansOf(c, {-3, 1, 2}, {1, 0, 0}), 3.0, 1e-7, "tangent");
    EXPECT_EQ(spansOf(c, {-3, 1.000001, 2}, {1, 0, 0}).count, 0) << "just missing";
    // In through the bottom at (0.25, 0, 0), out through the side at (1, 0, 3).
    s = spansOf(c, {0, 0, -1}, {0.25, 0, 1});
    expectSpan(s, 1.0, 4.0, "slanted");
    expectFaces(s, 1, 0, "slanted");
    expectSpan(spansOf(c, {1, 0, 2}, {-1, 0, 0}), 0.0, 2.0, "starting on the surface");
}

TEST(CylinderExact, ConeRays) {
    // Apex at (0, 0, 2); r(z) = 1 - z / 2.
    const Cylinder cone{2.0, 1.0, 0.0};
    LocalSpans s = spansOf(cone, {0, 0, -1}, {0, 0, 1});
    expectSpan(s, 1.0, 3.0, "along the axis to the apex");
    EXPECT_EQ(s.entries[0].faceIn, 1);
    EXPECT_TRUE(s.entries[0].faceOut == 0 || s.entries[0].faceOut == 2);
    // Through (0.5, 0, 0) at t = 1 and the apex at t = 2; inside between (x <= r(z)).
    expectSpan(spansOf(cone, {1, 0, -2}, {-0.5, 0, 2}), 1.0, 2.0, "through the apex");
    expectSpan(spansOf(cone, {0, 0, 4}, {0, 0, -1}), 2.0, 4.0, "down the axis from above");
    expectTouchOrMiss(spansOf(cone, {-3, 0, 2}, {1, 0, 0}), 3.0, 1e-7, "touching the apex");
    expectSpan(spansOf(cone, {-3, 0, 1}, {1, 0, 0}), 2.5, 3.5, "across at half height");
    // Parallel to the generator from (1,0,0) to the apex: points (0.5 - u, 0, 2u), inside
    // while |0.5 - u| <= 1 - u, i.e. u <= 0.75. Here A == 0 exactly.
    s = spansOf(cone, {1.5, 0, -2}, {-1, 0, 2});
    expectSpan(s, 1.0, 1.75, "parallel to a generator");
    expectFaces(s, 1, 0, "parallel to a generator");
    EXPECT_EQ(spansOf(cone, {2.5, 0, -2}, {-1, 0, 2}).count, 0) << "parallel to it, outside";
    // On the generator itself: the whole generator is on the closed surface.
    expectSpan(spansOf(cone, {2, 0, -2}, {-1, 0, 2}), 1.0, 2.0, "along a generator");
}

TEST(CylinderExact, DegenerateCones) {
    // r1 = 0: apex at the origin, r(z) = z / 2.
    const Cylinder up{2.0, 0.0, 1.0};
    LocalSpans s = spansOf(up, {0, 0, -1}, {0, 0, 1});
    expectSpan(s, 1.0, 3.0, "r1 = 0, along the axis");
    EXPECT_EQ(s.entries[0].faceOut, 2);
    expectSpan(spansOf(up, {-3, 0, 1}, {1, 0, 0}), 2.5, 3.5, "r1 = 0, across");
    expectTouchOrMiss(spansOf(up, {-3, 0, 0}, {1, 0, 0}), 3.0, 1e-7, "r1 = 0, bottom plane");
    // r2 = 0 and a wide flat cone: h = 0.5, r1 = 4, r(z) = 4 - 8 z.
    const Cylinder flat{0.5, 4.0, 0.0};
    expectSpan(spansOf(flat, {-5, 0, 0.25}, {1, 0, 0}), 3.0, 7.0, "flat cone across");
    expectSpan(spansOf(flat, {0, 0, 1}, {0, 0, -1}), 0.5, 1.0, "flat cone down the axis");
    EXPECT_EQ(spansOf(flat, {0, 0, 1}, {0, 0, 0}).count, 0) << "zero direction";
}

TEST(HalfSpaceExact, CrossingsParallelAndBounds) {
    const HalfSpace hs{{0, 0, 2}, 2};  // z <= 1
    LocalSpans s = spansOf(hs, {0, 0, 5}, {0, 0, -2});
    ASSERT_EQ(s.count, 1);
    EXPECT_NEAR(s.entries[0].tIn, 2.0, kExact);
    EXPECT_EQ(s.entries[0].faceIn, 0);
    EXPECT_EQ(s.entries[0].tOut, kInfinity);
    EXPECT_EQ(s.entries[0].faceOut, kClipFace);
    s = spansOf(hs, {0, 0, 5}, {0, 0, 2});
    ASSERT_EQ(s.count, 1);
    EXPECT_EQ(s.entries[0].tIn, -kInfinity);
    EXPECT_EQ(s.entries[0].faceIn, kClipFace);
    EXPECT_NEAR(s.entries[0].tOut, -2.0, kExact);
    EXPECT_EQ(spansOf(hs, {0, 0, 5}, {1, 0, 0}).count, 0) << "parallel above";
    for (double z : {1.0, -3.0}) {
        s = spansOf(hs, {0, 0, z}, {1, 1, 0});
        ASSERT_EQ(s.count, 1) << "parallel in or below the plane";
        EXPECT_EQ(s.entries[0].tIn, -kInfinity);
        EXPECT_EQ(s.entries[0].tOut, kInfinity);
    }
    EXPECT_EQ(HalfSpace({{0, 0, 2}, 4}).bounds().hi, Vec3(kInfinity, kInfinity, 2.0));
    EXPECT_EQ(HalfSpace({{0, 0, 2}, 4}).bounds().lo, Vec3(-kInfinity));
    EXPECT_EQ(HalfSpace({{-3, 0, 0}, 6}).bounds().lo, Vec3(-2.0, -kInfinity, -kInfinity));
    EXPECT_EQ(HalfSpace({{-3, 0, 0}, 6}).bounds().hi, Vec3(kInfinity));
    const Bounds3 tilted = HalfSpace({{1, 1, 0}, 1}).bounds();
    EXPECT_EQ(tilted.lo, Vec3(-kInfinity));
    EXPECT_EQ(tilted.hi, Vec3(kInfinity));
    EXPECT_EQ(HalfSpace({{0, -4, 0}, 1}).normal({}, 0), Vec3(0, -1, 0));
}

TEST(CylinderExact, BoundsAndInside) {
    const Cylinder c{3.0, 0.5, 2.0};
    EXPECT_EQ(c.bounds().lo, Vec3(-2, -2, 0));
    EXPECT_EQ(c.bounds().hi, Vec3(2, 2, 3));
    EXPECT_TRUE(c.inside({0, 0, 0}));
    EXPECT_TRUE(c.inside({2, 0, 3}));
    EXPECT_TRUE(c.inside({1.25, 0, 1.5}));  // r(1.5) = 1.25
    EXPECT_FALSE(c.inside({1.26, 0, 1.5}));
    EXPECT_FALSE(c.inside({0, 0, 3.0000001}));
    EXPECT_FALSE(c.inside({0, 0, -1e-300}));
}

// ---- Far and tiny: against 113-bit arithmetic ----

using Quad = boost::multiprecision::cpp_bin_float_quad;

// The chord of the line o + t d with the ball |p| <= r, in 113-bit arithmetic.
bool referenceChord(double r, const Vec3& o, const Vec3& d, double& tIn, double& tOut) {
    Quad dd = 0, od = 0, oo = 0;
    for (int a = 0; a < 3; ++a) {
        dd += Quad(d[a]) * d[a];
        od += Quad(o[a]) * d[a];
        oo += Quad(o[a]) * o[a];
    }
    const Quad disc = od * od - dd * (oo - Quad(r) * r);
    if (disc < 0) return false;
    const Quad root = sqrt(disc);
    tIn = double((-od - root) / dd);
    tOut = double((-od + root) / dd);
    return true;
}

// How the caller moves the origin to the entry of the bounds before asking for spans.
enum class Move { kNone, kPlain, kFma };
const char* const kMoveNames[] = {"not moved", "moved by o + t d", "moved by fma(t, d, o)"};

// Largest error of the span ends, as a distance along the line relative to the radius, over
// lines from `distance` away aimed through the ball.
double sphereEndError(double r, double distance, Move move, uint64_t seed) {
    Rng rng(seed);
    const Sphere sphere{r};
    double worst = 0.0;
    for (int i = 0; i < 2000; ++i) {
        const Vec3 o = rng.unit() * distance;
        const double scale = magnitude(rng) / distance;  // drawn first
        const Vec3 d = (0.9 * r * rng.inBall() - o) * scale;
        double tIn = 0.0, tOut = 0.0;
        EXPECT_TRUE(referenceChord(r, o, d, tIn, tOut));
        double tShift = 0.0, tEnd;
        if (move != Move::kNone) {
            EXPECT_TRUE(clipLine(o, d, sphere.bounds(), tShift, tEnd));
        }
        const Vec3 moved = move == Move::kFma ? pointOnLine(o, d, tShift) : o + tShift * d;
        const LocalSpans s = spansOf(sphere, moved, d);
        EXPECT_EQ(s.count, 1) << describe(o, d);
        if (s.count != 1) return kInfinity;
        const double dLen = glm::length(d);
        worst = std::max(worst, std::abs(tShift + s.entries[0].tIn - tIn) * dLen / r);
        worst = std::max(worst, std::abs(tShift + s.entries[0].tOut - tOut) * dLen / r);
    }
    return worst;
}

TEST(SphereFarAndTiny, SpansMatchHighPrecision) {
    struct Case {
        double r, distance;
        Move move;
    };
    const Case cases[] = {{1.0, 1e6, Move::kNone},   {1.0, 1e6, Move::kPlain},
                          {1.0, 1e6, Move::kFma},    {1e-6, 1.0, Move::kNone},
                          {1e-6, 1.0, Move::kPlain}, {1e-6, 1.0, Move::kFma},
                          {1e-6, 1e-5, Move::kNone}, {1e3, 1e4, Move::kNone}};
    for (const Case& c : cases) {
        const double err = sphereEndError(c.r, c.distance, c.move, 51);
        const char* how = kMoveNames[int(c.move)];
        EXPECT_LE(err, 1e-9) << "r = " << c.r << " from " << c.distance << ", " << how;
        // Unless the caller's move rounds the origin, the sphere itself is far better than
        // that: its ends are correctly rounded or nearly (a regression guard).
        if (c.move != Move::kPlain) {
            EXPECT_LE(err, 1e-12) << "r = " << c.r << ", " << how;
        }
        std::cout << "[ info ] sphere r = " << c.r << " from " << c.distance << ", " << how
                  << ": worst end error " << err << " r\n";
    }
}

TEST(FarAxisRays, BoxAndCylinderMatchHighPrecision) {
    // Along -x at y = 0.5 from x = 1e6, |d| = 1e-3: exact crossings x = +-sqrt(0.75) for the
    // cylinder and x = +-1 for the box, in 113-bit arithmetic.
    const Vec3 o(1e6, 0.5, 1.0), d(-1e-3, 0.0, 0.0);
    const auto tAt = [&](const Quad& x) { return double((Quad(o.x) - x) / Quad(-d.x)); };
    const Quad halfChord = sqrt(Quad(0.75));
    // Error of an end as a distance along the line, relative to the unit size of both solids.
    const auto error = [&](double t, double tExact) { return std::abs(t - tExact) * -d.x; };
    for (bool move : {false, true}) {
        const Cylinder cyl{2.0, 1.0, 1.0};
        double tShift = 0.0, tEnd;
        if (move) {
            ASSERT_TRUE(clipLine(o, d, cyl.bounds(), tShift, tEnd));
        }
        LocalSpans s = spansOf(cyl, o + tShift * d, d);
        ASSERT_EQ(s.count, 1);
        EXPECT_LE(error(tShift + s.entries[0].tIn, tAt(halfChord)), 1e-9) << move;
        EXPECT_LE(error(tShift + s.entries[0].tOut, tAt(-halfChord)), 1e-9) << move;
        const Box box{Vec3(-1.0), Vec3(1.0)};
        tShift = 0.0;
        if (move) {
            ASSERT_TRUE(clipLine(o, d, box.bounds(), tShift, tEnd));
        }
        s = spansOf(box, o + tShift * d, d);
        ASSERT_EQ(s.count, 1);
        EXPECT_LE(error(tShift + s.entries[0].tIn, tAt(Quad(1))), 1e-9) << move;
        EXPECT_LE(error(tShift + s.entries[0].tOut, tAt(Quad(-1))), 1e-9) << move;
    }
}

// ---- Normals at sampled surface points ----

template <class P>
void expectOutwardUnitNormal(const P& prim, const Vec3& p, uint16_t face, double size) {
    const Vec3 n = prim.normal(p, face);
    ASSERT_NEAR(glm::length(n), 1.0, 1e-12) << describe(p, n);
    const double eps = 1e-6 * size;
    EXPECT_FALSE(prim.inside(p + eps * n)) << "face " << face << " " << describe(p, n);
    EXPECT_TRUE(prim.inside(p - eps * n)) << "face " << face << " " << describe(p, n);
}

TEST(Normals, UnitOutwardAndDefinedAtTheApex) {
    Rng rng(61);
    for (int i = 0; i < 2000; ++i) {
        const Sphere sphere{3.0};
        expectOutwardUnitNormal(sphere, 3.0 * rng.unit(), 0, 6.0);
        const Box box{{-1, -2, 0}, {3, 1, 0.5}};
        const uint16_t f = uint16_t(rng.index(6));
        const Vec3 e = box.hi - box.lo;
        Vec3 p = rng.inBox(box.lo + 0.01 * e, box.hi - 0.01 * e);
        p[f / 2] = f & 1 ? box.hi[f / 2] : box.lo[f / 2];
        expectOutwardUnitNormal(box, p, f, 4.0);
    }
    for (const Cylinder& c : kCylinders) {
        const double h = c.height, size = std::max({h, 2 * c.r1, 2 * c.r2});
        for (int i = 0; i < 500; ++i) {
            const double a = rng.uniform(0.0, 2 * kPi), z = rng.uniform(0.01, 0.99) * h;
            const double r = c.r1 + (c.r2 - c.r1) * z / h;
            expectOutwardUnitNormal(c, {r * std::cos(a), r * std::sin(a), z}, 0, size);
            const Vec3 q = 0.99 * rng.inBall();
            if (c.r1 > 0.0) expectOutwardUnitNormal(c, {q.x * c.r1, q.y * c.r1, 0.0}, 1, size);
            if (c.r2 > 0.0) expectOutwardUnitNormal(c, {q.x * c.r2, q.y * c.r2, h}, 2, size);
        }
    }
    // The apex: the axis pointing away from the base.
    EXPECT_EQ(Cylinder({2.0, 1.0, 0.0}).normal({0, 0, 2}, 0), Vec3(0, 0, 1));
    EXPECT_EQ(Cylinder({2.0, 0.0, 1.0}).normal({0, 0, 0}, 0), Vec3(0, 0, -1));
    for (int i = 0; i < 200; ++i) {
        HalfSpace hs{direction(rng), rng.uniform(-1.0, 1.0)};
        const Vec3 n = hs.planeNormal;
        const Vec3 onPlane = n * (hs.offset / glm::dot(n, n)) + glm::cross(n, rng.unit());
        expectOutwardUnitNormal(hs, onPlane, 0, 1.0);
    }
}

// ---- boundsUnder: contains the transformed surface and touches it on every face ----

Mat4 randomAffine(Rng& rng) {
    Mat4 shear(1.0);
    shear[1][0] = rng.uniform(-1.0, 1.0);
    shear[2][0] = rng.uniform(-1.0, 1.0);
    shear[2][1] = rng.uniform(-1.0, 1.0);
    // One draw per statement, in the order gcc evaluated the former one-expression form (so
    // each seed keeps its matrices), now the same on every compiler.
    Vec3 scale;
    for (int a = 2; a >= 0; --a) scale[a] = rng.uniform(0.1, 10.0);
    const Vec3 axisFirst = rng.unit();
    const double angleFirst = rng.uniform(0.0, 6.3);
    const Vec3 axisLast = rng.unit();
    const double angleLast = rng.uniform(0.0, 6.3);
    const Vec3 shift = rng.inBox(Vec3(-10.0), Vec3(10.0));
    const Mat4 m = glm::translate(Mat4(1.0), shift) * glm::rotate(Mat4(1.0), angleLast, axisLast) *
                   shear * glm::scale(Mat4(1.0), scale) *
                   glm::rotate(Mat4(1.0), angleFirst, axisFirst);
    return m;
}

// Maximises f over a parameter vector by compass search from the best of many samples: a
// black box that knows nothing of the closed forms in the code under test.
template <int N, class F, class Sample>
double maximise(F f, Sample sample, Rng& rng) {
    using Param = std::array<double, N>;
    Param best = sample(rng);
    double fBest = f(best);
    for (int i = 0; i < 2000; ++i) {
        const Param p = sample(rng);
        if (const double v = f(p); v > fBest) best = p, fBest = v;
    }
    for (double step = 0.1; step > 1e-12;) {
        bool improved = false;
        for (int k = 0; k < N; ++k)
            for (double sgn : {-1.0, 1.0}) {
                Param p = best;
                p[k] += sgn * step;
                if (const double v = f(p); v > fBest) best = p, fBest = v, improved = true;
            }
        if (!improved) step *= 0.5;
    }
    return fBest;
}

// The box contains every sample (within rounding) and each face is within 1e-9 of the box
// size from the maximum found over the surface.
template <class Surface>
void expectTightBounds(const Bounds3& b, Surface point, Rng& rng, const char* what) {
    using Param = std::array<double, 3>;
    const double size = glm::length(b.extent());
    const auto sample = [](Rng& r) { return Param{r.uniform(), r.uniform(), r.uniform()}; };
    for (int i = 0; i < 2000; ++i) {
        const Vec3 q = point(sample(rng));
        for (int a = 0; a < 3; ++a) {
            EXPECT_GE(q[a], b.lo[a] - 1e-12 * size) << what;
            EXPECT_LE(q[a], b.hi[a] + 1e-12 * size) << what;
        }
    }
    for (int a = 0; a < 3; ++a) {
        const double hi = maximise<3>([&](const Param& p) { return point(p)[a]; }, sample, rng);
        const double lo = -maximise<3>([&](const Param& p) { return -point(p)[a]; }, sample, rng);
        EXPECT_NEAR(b.hi[a], hi, 1e-9 * size) << what << " axis " << a;
        EXPECT_NEAR(b.lo[a], lo, 1e-9 * size) << what << " axis " << a;
    }
}

TEST(BoundsUnder, SphereAndCylinderAreTightUnderAffineMaps) {
    Rng rng(71);
    for (int i = 0; i < 20; ++i) {
        const Mat4 m = randomAffine(rng);
        const Sphere sphere{rng.uniform(0.1, 3.0)};
        // (p0, p1) are spherical angles; p2 is unused.
        expectTightBounds(
            sphere.boundsUnder(m),
            [&](const std::array<double, 3>& p) {
                const double th = p[0] * kPi * 4, ph = p[1] * kPi * 4;
                const Vec3 u(std::sin(th) * std::cos(ph), std::sin(th) * std::sin(ph),
                             std::cos(th));
                return transformPoint(m, sphere.radius * u);
            },
            rng, "sphere");
        const Cylinder& c = kCylinders[i % std::size(kCylinders)];
        // (p0, p1, p2) = (angle, height fraction, radius fraction), each folded into range.
        expectTightBounds(
            c.boundsUnder(m),
            [&](const std::array<double, 3>& p) {
                const auto fold = [](double x) { return std::abs(x - 2 * std::floor(x / 2) - 1); };
                const double a = p[0] * kPi * 4, z = fold(p[1]) * c.height;
                const double r = fold(p[2]) * (c.r1 + (c.r2 - c.r1) * z / c.height);
                return transformPoint(m, Vec3(r * std::cos(a), r * std::sin(a), z));
            },
            rng, "cylinder");
    }
}

}  // namespace
}  // namespace csg
