// linear_extrude with twist and with a scale per axis (primitives/TwistedExtrusion.h). The
// oracles are independent of the code under test:
//   - spans derived by hand: the section at height z of linear_extrude(height = 10, twist = 90)
//     square(2, center = true) is the square turned by -9z degrees, so a vertical line at
//     (rho cos b, rho sin b) is inside while the circle point turned by 9z + b degrees has both
//     coordinates within [-1, 1], and a level line's chord is a slab clip in the square's frame;
//   - the primitive's own point test (inside) against its spans on random lines, for outlines
//     of lines, arcs, quadratic and cubic Beziers under twists, per-axis scales and apexes;
//   - volumes against area x height (a twist turns each section rigidly, so it keeps the
//     volume; a scale per axis multiplies the section's area by sigma_x sigma_y);
//   - OpenSCAD 2021's own STL of example020 and Basics/linear_extrude.scad: its vertices lie on
//     the exact surface to within its slicing error, and so does its volume.
// Notation: t is the parameter of o + t d; lines along an axis have unit d, so t is a length.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <numbers>
#include <sstream>

#include "BinaryStl.h"
#include "MissingTool.h"
#include "csg/Scene.h"
#include "csg/Volume.h"
#include "io/Evaluate.h"
#include "primitives/Extrusion.h"
#include "primitives/SegmentCarrier.h"
#include "tests/CountingNew.h"
#include "tests/PartHelpers.h"
#include "tests/SeededRng.h"
#include "tests/TempDir.h"
#include "tests/TextFiles.h"

namespace {

using csg::testing::diagnosticsOf;
using csg::testing::evaluate;
using csg::testing::readFile;
using csg::testing::shellQuote;

using csg::Extrusion;
using csg::Outline;
using csg::Segment2;
using csg::Vec2;
using csg::Vec3;
constexpr double kPi = std::numbers::pi;
constexpr double kDeg = kPi / 180.0;

// ---- helpers ----

std::shared_ptr<const Outline> loop(const std::vector<Vec2>& points) {
    auto outline = std::make_shared<Outline>();
    for (size_t i = 0; i < points.size(); ++i)
        outline->segments.push_back(Segment2::line(points[i], points[(i + 1) % points.size()]));
    return outline;
}

std::shared_ptr<const Outline> centredSquare(double half) {
    return loop({{-half, -half}, {half, -half}, {half, half}, {-half, half}});
}

Extrusion extrude(std::shared_ptr<const Outline> outline, double z0, double z1, Vec2 scale,
                  double twistDegrees) {
    return Extrusion::plane(std::move(outline), "polygon").linear(z0, z1, scale, twistDegrees);
}

struct Interval1 {
    double in, out;
};

std::vector<Interval1> spansOf(const Extrusion& e, const Vec3& o, const Vec3& d) {
    csg::LocalSpans s;
    e.spans(o, d, s);
    std::vector<Interval1> out;
    for (int i = 0; i < s.count; ++i) out.push_back({s.entries[i].tIn, s.entries[i].tOut});
    return out;
}

// The chord of the line p + t u through the square [-1, 1]^2 (Liang and Barsky's slabs);
// false when it misses.
bool squareChord(Vec2 p, Vec2 u, double& tIn, double& tOut) {
    tIn = -csg::kInfinity, tOut = csg::kInfinity;
    for (int a = 0; a < 2; ++a) {
        if (u[a] == 0.0) {
            if (std::abs(p[a]) > 1.0) return false;
            continue;
        }
        double t0 = (-1.0 - p[a]) / u[a], t1 = (1.0 - p[a]) / u[a];
        if (t0 > t1) std::swap(t0, t1);
        tIn = std::max(tIn, t0), tOut = std::min(tOut, t1);
    }
    return tIn <= tOut;
}

Vec2 rotated(Vec2 p, double radians) {
    const double c = std::cos(radians), s = std::sin(radians);
    return {c * p.x - s * p.y, s * p.x + c * p.y};
}

// ---- (a) lines along the axis and vertical lines, by hand ----

// The axis lies inside every section of a centred square, whatever the twist: one span from
// the bottom face to the top face.
TEST(TwistedSpans, AxisSpansTheHeight) {
    for (const double twist : {90.0, -45.0, 720.0, 3600.0, 1e5}) {
        const Extrusion e = extrude(centredSquare(1.0), 0.0, 10.0, Vec2(1.0), twist);
        csg::LocalSpans s;
        e.spans(Vec3(0, 0, -5), Vec3(0, 0, 1), s);
        ASSERT_EQ(s.count, 1) << "twist " << twist;
        EXPECT_NEAR(s.entries[0].tIn, 5.0, 1e-14);
        EXPECT_NEAR(s.entries[0].tOut, 15.0, 1e-14);
        EXPECT_EQ(s.entries[0].faceIn, Extrusion::kBottomFace);
        EXPECT_EQ(s.entries[0].faceOut, Extrusion::kTopFace);
        // Downward along the axis: the top face first.
        s = csg::LocalSpans{};
        e.spans(Vec3(0, 0, 12), Vec3(0, 0, -2), s);
        ASSERT_EQ(s.count, 1);
        EXPECT_NEAR(s.entries[0].tIn, 1.0, 1e-14);
        EXPECT_NEAR(s.entries[0].tOut, 6.0, 1e-14);
        EXPECT_EQ(s.entries[0].faceIn, Extrusion::kTopFace);
    }
}

// A vertical line at (rho, 0), 1 < rho < sqrt 2: its point turned by phi = twist z / 10 is
// (rho cos phi, rho sin phi), inside the square while phi mod 90 degrees lies in
// [acos(1 / rho), asin(1 / rho)]. For twist 90 that is one span; for 720, eight.
TEST(TwistedSpans, VerticalLineOffTheAxis) {
    const double rho = 1.2;
    const double lo = std::acos(1.0 / rho) / kDeg, hi = std::asin(1.0 / rho) / kDeg;
    for (const double twist : {90.0, 720.0, -720.0}) {
        const Extrusion e = extrude(centredSquare(1.0), 0.0, 10.0, Vec2(1.0), twist);
        const auto spans = spansOf(e, Vec3(rho, 0, 0), Vec3(0, 0, 1));
        const int turns = int(std::abs(twist) / 90.0);
        ASSERT_EQ(int(spans.size()), turns) << "twist " << twist;
        const double degreesPerUnit = std::abs(twist) / 10.0;
        for (int k = 0; k < turns; ++k) {
            // For a negative twist the point turns the other way: phi mod 90 runs from 90
            // down, and the window [lo, hi] is symmetric about 45, so the same heights.
            EXPECT_NEAR(spans[k].in, (90.0 * k + lo) / degreesPerUnit, 1e-12) << k;
            EXPECT_NEAR(spans[k].out, (90.0 * k + hi) / degreesPerUnit, 1e-12) << k;
        }
    }
}

// ---- (b) level lines through linear_extrude(height = 10, twist = 90) square(2, center) ----

// At height z the section is the square turned by -9z degrees; in the square's own frame (turned
// back by +9z degrees) the line y = y0 is p + t u, clipped by the square's slabs.
TEST(TwistedSpans, LevelLinesMatchTheTurnedSquare) {
    const io::EvaluateResult r =
        evaluate("linear_extrude(height = 10, twist = 90) square(2, center = true);");
    ASSERT_TRUE(r.ok()) << diagnosticsOf(r);
    const csg::Scene scene = csg::Scene::compile(r.model->root);
    csg::QueryContext ctx;
    int checked = 0;
    for (const double z : {0.0, 0.3, 1.0, 2.5, 5.0, 7.77, 9.9, 10.0}) {
        for (const double y0 : {0.0, 0.4, -0.9, 1.3, -1.41}) {
            for (const double slope : {0.0, 1e-9}) {  // exactly level, and all but level
                const double phi = 9.0 * z * kDeg;
                double tIn, tOut;
                const bool hit = squareChord(rotated(Vec2(-5.0, y0), phi),
                                             rotated(Vec2(1.0, 0.0), phi), tIn, tOut);
                const csg::Ray ray{Vec3(-5.0, y0, z), Vec3(1.0, 0.0, slope), -csg::kInfinity,
                                   csg::kInfinity};
                const auto spans = scene.spans(ray, ctx);
                if (!hit) {
                    EXPECT_TRUE(spans.empty()) << "z " << z << " y " << y0;
                    continue;
                }
                if (slope != 0.0 && (z == 10.0)) continue;  // climbs out through the top
                ASSERT_EQ(spans.size(), 1u) << "z " << z << " y " << y0 << " slope " << slope;
                // The slope moves the line by 5e-9 over the chord: 9 degrees per unit turns the
                // section by ~1e-9 there.
                const double tolerance = slope == 0.0 ? 1e-12 : 1e-7;
                EXPECT_NEAR(spans[0].in.t, tIn, tolerance) << "z " << z << " y " << y0;
                EXPECT_NEAR(spans[0].out.t, tOut, tolerance) << "z " << z << " y " << y0;
                ++checked;
            }
        }
    }
    EXPECT_GE(checked, 45);
}

// Oblique lines: in the square's frame the line's image is a spiral, so the oracle is the
// bisection of "inside" along it: the first and last heights where the turned point enters
// and leaves the square, found on a fine grid and refined by bisection of the hand-derived
// membership (both coordinates of R(9z degrees) (x, y) within [-1, 1]).
TEST(TwistedSpans, ObliqueLinesMatchTheTurnedSquare) {
    const Extrusion e = extrude(centredSquare(1.0), 0.0, 10.0, Vec2(1.0), 90.0);
    const auto member = [](const Vec3& p) {
        if (p.z < 0.0 || p.z > 10.0) return false;
        const Vec2 q = rotated(Vec2(p), 9.0 * p.z * kDeg);
        return std::abs(q.x) <= 1.0 && std::abs(q.y) <= 1.0;
    };
    csg::testing::Rng rng(11);
    int compared = 0, skipped = 0;
    for (int i = 0; i < 300; ++i) {
        const Vec3 target = rng.inBox(Vec3(-1.4, -1.4, 0.0), Vec3(1.4, 1.4, 10.0));
        const Vec3 o = target + 12.0 * rng.unit();
        const Vec3 d = target - o;
        const auto spans = spansOf(e, o, d);
        // Membership changes along the line, by a grid of 20000 steps and bisection.
        std::vector<double> changes;
        const int n = 20000;
        bool was = member(o - d);
        for (int k = 1; k <= n; ++k) {
            double a = -1.0 + 3.0 * (k - 1) / n, b = -1.0 + 3.0 * k / n;
            const bool now = member(o + b * d);
            if (now == was) continue;
            for (int it = 0; it < 80; ++it) {
                const double m = 0.5 * (a + b);
                (member(o + m * d) == was ? a : b) = m;
            }
            changes.push_back(0.5 * (a + b));
            was = now;
        }
        std::vector<double> ends;
        for (const Interval1& s : spans) ends.push_back(s.in), ends.push_back(s.out);
        // A span shorter than two grid steps may slip between the grid's points: such a line
        // is skipped (counted), the rest must match end for end.
        bool thin = false;
        for (const Interval1& s : spans) thin = thin || s.out - s.in < 2.0 * 3.0 / n;
        if (thin && ends.size() != changes.size()) {
            ++skipped;
            continue;
        }
        ASSERT_EQ(ends.size(), changes.size()) << "line " << i;
        for (size_t k = 0; k < ends.size(); ++k) EXPECT_NEAR(ends[k], changes[k], 1e-12);
        compared += int(ends.size());
    }
    EXPECT_LE(skipped, 3);
    EXPECT_GT(compared, 300);
}

// ---- (c) grazing the helicoid ----

// linear_extrude(height = 10, twist = 180) square(2, center = true): the vertical line at
// (rho, 0) turns, in the square's frame, along the circle of radius rho, phi = 18 z degrees.
// The circle of radius 1 is the square's inscribed circle: it touches the edge x = 1 at
// phi = 0 (z = 0), y = 1 at phi = 90 (z = 5) and x = -1 at phi = 180 (z = 10). Just outside
// it (rho = 1 + eps, a double so that eps = rho - 1 exactly) the line is outside the solid
// for |phi - 90 k| < acos(1 / rho) = atan(sqrt((rho - 1)(rho + 1))); just inside, never.
TEST(TwistedSpans, VerticalLineGrazingTheSweptEdges) {
    const Extrusion e = extrude(centredSquare(1.0), 0.0, 10.0, Vec2(1.0), 180.0);
    for (const double eps : {1e-4, 1e-7, 1e-10, 1e-12}) {
        const double rho = 1.0 + eps;
        const double half = std::atan(std::sqrt((rho - 1.0) * (rho + 1.0))) / (18.0 * kDeg);
        const auto spans = spansOf(e, Vec3(rho, 0.0, 0.0), Vec3(0, 0, 1));
        ASSERT_EQ(spans.size(), 2u) << "eps " << eps;
        // Simple roots 2 half apart where the function is ~eps: rounding (1e-16 of it) moves
        // them by ~1e-16 / sqrt(eps) relative, 1e-10 at eps = 1e-12.
        EXPECT_NEAR(spans[0].in, half, 1e-9) << "eps " << eps;
        EXPECT_NEAR(spans[0].out, 5.0 - half, 1e-9) << "eps " << eps;
        EXPECT_NEAR(spans[1].in, 5.0 + half, 1e-9) << "eps " << eps;
        EXPECT_NEAR(spans[1].out, 10.0 - half, 1e-9) << "eps " << eps;
    }
    for (const double eps : {1e-4, 1e-7, 1e-12, 0.0}) {
        const double rho = 1.0 - eps;
        const auto spans = spansOf(e, Vec3(rho, 0.0, 0.0), Vec3(0, 0, 1));
        // Tangent (eps = 0): the solid is closed, so spans may only be split by gaps as narrow
        // as rounding's reach at a double root (~sqrt(1e-16) relative).
        ASSERT_GE(spans.size(), 1u) << "eps " << eps;
        if (eps > 0.0) {
            ASSERT_EQ(spans.size(), 1u) << "eps " << eps;
        }
        EXPECT_NEAR(spans.front().in, 0.0, eps > 0.0 ? 1e-14 : 1e-6);
        EXPECT_NEAR(spans.back().out, 10.0, eps > 0.0 ? 1e-14 : 1e-6);
        for (size_t k = 1; k < spans.size(); ++k) EXPECT_LT(spans[k].in - spans[k - 1].out, 1e-6);
    }
}

// A level line touching a corner of the turned section: just below the corner's height it
// crosses a short chord (the slab oracle), just above nothing.
TEST(TwistedSpans, LevelLineGrazingACorner) {
    const Extrusion e = extrude(centredSquare(1.0), 0.0, 10.0, Vec2(1.0), 90.0);
    for (const double z : {1.0, 3.3, 6.0}) {
        const double phi = 9.0 * z * kDeg;
        // The corners of the section are R(-phi)(+-1, +-1); the highest has y = top.
        double top = -csg::kInfinity;
        for (const Vec2 c : {Vec2(1, 1), Vec2(1, -1), Vec2(-1, 1), Vec2(-1, -1)})
            top = std::max(top, rotated(c, -phi).y);
        for (const double below : {1e-3, 1e-6, 1e-9}) {
            double tIn, tOut;
            ASSERT_TRUE(squareChord(rotated(Vec2(-5.0, top - below), phi),
                                    rotated(Vec2(1.0, 0.0), phi), tIn, tOut));
            const auto spans = spansOf(e, Vec3(-5.0, top - below, z), Vec3(1, 0, 0));
            ASSERT_EQ(spans.size(), 1u);
            EXPECT_NEAR(spans[0].in, tIn, 1e-12);
            EXPECT_NEAR(spans[0].out, tOut, 1e-12);
        }
        EXPECT_TRUE(spansOf(e, Vec3(-5.0, top + 1e-9, z), Vec3(1, 0, 0)).empty());
    }
}

// ---- (d) the point test agrees with the spans on random lines ----

std::shared_ptr<const Outline> offsetCircle() {
    auto o = std::make_shared<Outline>();
    o->segments.push_back(Segment2::circle(Vec2(1.5, 0.0), 1.0));
    return o;
}

std::shared_ptr<const Outline> star() {
    std::vector<Vec2> p;
    for (int i = 0; i < 10; ++i) {
        const double r = i % 2 ? 0.8 : 2.0, a = i * 36.0 * kDeg;
        p.push_back({r * std::cos(a) + 0.3, r * std::sin(a)});
    }
    return loop(p);
}

// A glyph-like outline of quadratic and cubic Beziers with a hole (even-odd), an ellipse arc
// and a degree-raised quadratic written as a cubic.
std::shared_ptr<const Outline> curvy() {
    auto o = std::make_shared<Outline>();
    const Vec2 a(-2, -1), b(2, -1.5), c(2.5, 1.5), d(-1.5, 2);
    o->segments.push_back(Segment2::quadratic(a, Vec2(0, -3), b));
    o->segments.push_back(Segment2::cubic(b, Vec2(4, -0.5), Vec2(1, 0.5), c));
    o->segments.push_back(
        Segment2::arc(Vec2(0.5, 1.75), Vec2(2.0, -0.25), Vec2(0.1, 0.8), 0.0, kPi));
    o->segments.push_back(Segment2::line(o->segments.back().finish(), d));
    // d -> a as a raised quadratic (control points (d + 2m) / 3, (a + 2m) / 3).
    const Vec2 m(-3, 0.5);
    o->segments.push_back(Segment2::cubic(d, (d + 2.0 * m) / 3.0, (a + 2.0 * m) / 3.0, a));
    // A hole: a cubic loop and a quadratic back.
    const Vec2 h0(0.2, -0.2), h1(1.0, 0.4);
    o->segments.push_back(Segment2::cubic(h0, Vec2(0.5, -0.8), Vec2(1.4, -0.2), h1));
    o->segments.push_back(Segment2::quadratic(h1, Vec2(0.3, 0.6), h0));
    return o;
}

struct RandomCase {
    const char* name;
    std::shared_ptr<const Outline> outline;
    Vec2 scale;
    double twist;
};

std::vector<RandomCase> randomCases() {
    return {
        {"square twist 90", centredSquare(1.0), Vec2(1.0), 90.0},
        {"square twist -400", centredSquare(1.0), Vec2(1.0), -400.0},
        {"offset circle twist 270", offsetCircle(), Vec2(1.0), 270.0},
        {"star twist 200", star(), Vec2(1.0), 200.0},
        {"star scale [2, 0.5]", star(), Vec2(2.0, 0.5), 0.0},
        {"star scale [2, 0.5] twist 120", star(), Vec2(2.0, 0.5), 120.0},
        {"square apex twist -360", centredSquare(1.0), Vec2(0.0), -360.0},
        {"square edge [0, 1.5] twist 45", centredSquare(1.0), Vec2(0.0, 1.5), 45.0},
        {"curvy twist 150", curvy(), Vec2(1.0), 150.0},
        {"curvy scale [0.5, 1.5]", curvy(), Vec2(0.5, 1.5), 0.0},
        {"curvy scale 0.3 twist -90", curvy(), Vec2(0.3), -90.0},
        {"offset circle scale [1, 3]", offsetCircle(), Vec2(1.0, 3.0), 0.0},
    };
}

// Points along each line, away from the span ends by more than the ends' accuracy, are inside
// exactly when they lie in a span; span ends are ascending and disjoint, never NaN.
TEST(TwistedSpans, AgreeWithInsideOnRandomLines) {
    csg::testing::Rng rng(2024);
    for (const RandomCase& c : randomCases()) {
        const Extrusion e = extrude(c.outline, -1.0, 4.0, c.scale, c.twist);
        ASSERT_EQ(e.invalidReason(), nullptr);
        const csg::Bounds3 box = e.bounds();
        const double size = glm::length(box.hi - box.lo);
        int hits = 0, samples = 0, disagreements = 0;
        for (int i = 0; i < 400; ++i) {
            const Vec3 target = rng.inBox(box.lo, box.hi);
            Vec3 dir = rng.unit();
            if (i % 10 == 0) dir = Vec3(0, 0, 1);                       // vertical
            if (i % 10 == 1) dir = glm::normalize(Vec3(Vec2(dir), 0));  // level
            const Vec3 o = target - size * dir;
            const Vec3 d = dir * std::pow(10.0, rng.uniform(-2.0, 2.0));
            const auto spans = spansOf(e, o, d);
            const double tSize = size / glm::length(d);
            for (size_t k = 0; k < spans.size(); ++k) {
                ASSERT_TRUE(std::isfinite(spans[k].in) && std::isfinite(spans[k].out)) << c.name;
                ASSERT_LE(spans[k].in, spans[k].out) << c.name;
                if (k > 0) {
                    ASSERT_LT(spans[k - 1].out, spans[k].in) << c.name;
                }
            }
            hits += !spans.empty();
            for (int k = 0; k <= 200; ++k) {
                const double t = 2.0 * tSize * k / 200.0;
                bool near = false, in = false;
                for (const Interval1& s : spans) {
                    near = near || std::abs(t - s.in) < 1e-9 * tSize ||
                           std::abs(t - s.out) < 1e-9 * tSize;
                    in = in || (t >= s.in && t <= s.out);
                }
                if (near) continue;
                ++samples;
                if (e.inside(o + t * d) != in) {
                    ++disagreements;
                    ADD_FAILURE() << c.name << ": line " << i << " t " << t << " inside "
                                  << e.inside(o + t * d) << " spans " << spans.size();
                }
                if (disagreements > 5) return;
            }
        }
        EXPECT_GT(hits, 50) << c.name;
        EXPECT_GT(samples, 50000) << c.name;
    }
}

// The spans of a list, clipped to [a, b]; what is left shorter than `sliver` is dropped (the
// clipping of two lists solved from different middles may leave one a rounding-sized piece).
std::vector<Interval1> clippedTo(const std::vector<Interval1>& spans, double a, double b,
                                 double sliver) {
    std::vector<Interval1> out;
    for (const Interval1& s : spans) {
        const Interval1 c{std::max(s.in, a), std::min(s.out, b)};
        if (c.out - c.in > sliver) out.push_back(c);
    }
    return out;
}

// A line read only over a stretch (LocalSpans::from and to, as a measuring line reads a short
// one) is solved over that stretch alone: there its spans are the whole line's, and its points
// away from the span ends are inside exactly when they lie in one. Where the primitive says it
// left nothing out past the stretch (cutAtTo false), the list holds every span from the
// stretch's start on, as the caller may then serve a farther stretch from it.
TEST(TwistedSpans, AStretchOfALineIsSolvedOverItAlone) {
    csg::testing::Rng rng(2026);
    int stopped = 0, through = 0;
    for (const RandomCase& c : randomCases()) {
        const Extrusion e = extrude(c.outline, -1.0, 4.0, c.scale, c.twist);
        const csg::Bounds3 box = e.bounds();
        const double size = glm::length(box.hi - box.lo);
        for (int i = 0; i < 200; ++i) {
            const Vec3 target = rng.inBox(box.lo, box.hi);
            const Vec3 dir = i % 10 == 0 ? Vec3(0, 0, 1) : rng.unit();
            const Vec3 o = target - size * dir;
            const Vec3 d = dir * std::pow(10.0, rng.uniform(-1.0, 1.0));
            const double tSize = size / glm::length(d);
            const std::vector<Interval1> wholeLine = spansOf(e, o, d);
            csg::LocalSpans s;
            s.from = rng.uniform(0.5, 1.5) * tSize;
            s.to = s.from + rng.uniform(0.01, 0.5) * tSize;
            s.margin = 1e-6 * tSize;
            e.spans(o, d, s);
            std::vector<Interval1> stretch;
            for (int k = 0; k < s.count; ++k)
                stretch.push_back({s.entries[k].tIn, s.entries[k].tOut});
            const double sliver = 1e-9 * tSize;
            (s.cutAtTo ? stopped : through) += 1;
            const double end = s.cutAtTo ? s.to : csg::kInfinity;
            const auto expected = clippedTo(wholeLine, s.from, end, sliver);
            const auto got = clippedTo(stretch, s.from, end, sliver);
            ASSERT_EQ(got.size(), expected.size()) << c.name << ": line " << i;
            for (size_t k = 0; k < got.size(); ++k) {
                EXPECT_NEAR(got[k].in, expected[k].in, sliver) << c.name << ": line " << i;
                EXPECT_NEAR(got[k].out, expected[k].out, sliver) << c.name << ": line " << i;
            }
            for (int k = 0; k <= 50; ++k) {
                const double t = s.from + (s.to - s.from) * k / 50.0;
                bool near = false, in = false;
                for (const Interval1& span : got) {
                    near = near || std::abs(t - span.in) < 1e-9 * tSize ||
                           std::abs(t - span.out) < 1e-9 * tSize;
                    in = in || (t >= span.in && t <= span.out);
                }
                if (!near) {
                    EXPECT_EQ(e.inside(o + t * d), in) << c.name << ": line " << i << " t " << t;
                }
            }
        }
    }
    // Both kinds of stretch were tried: one the solve stopped at, one past the solid.
    EXPECT_GT(stopped, 200);
    EXPECT_GT(through, 200);
}

// The same through the scene: a ray's spans over [tmin, tmax] are those of the whole line
// clipped there, and closest() from a point inside finds the whole line's first exit. Its walk
// may meet the twisted leaf twice: over a stretch that a hit on the ball has shortened, and
// then over the whole line (csg/Query.cpp's fallback for a ray that starts inside), where the
// list solved for the stretch must not serve.
TEST(TwistedSpans, TheSceneReadsAStretchAsItsPartOfTheLine) {
    // The ball comes first, so that the union's scan meets it before the difference.
    const csg::Scene scene = csg::testing::compiled(
        "translate([0, 0, 5]) sphere(1.9);\n"
        "difference() { linear_extrude(height = 10, twist = 720) square(4, center = true);\n"
        "  translate([0, 0, 5]) cube([1, 1, 20], center = true); }\n"
        "translate([5, 0, 0]) cube(1);");
    csg::QueryContext ctx;
    csg::testing::Rng rng(7);
    int checked = 0, exits = 0;
    for (int i = 0; i < 500; ++i) {
        const Vec3 a = rng.inBox(Vec3(-2, -2, 0), Vec3(2, 2, 10));
        const Vec3 d = rng.unit();
        const csg::Ray line{a - 30.0 * d, d, 0.0, csg::kInfinity};
        std::vector<csg::Span> full;
        for (const csg::Span& span : scene.spans(line, ctx)) full.push_back(span);
        const double t0 = 30.0 + rng.uniform(-3.0, 3.0), t1 = t0 + rng.uniform(0.1, 4.0);
        const auto part = scene.spans(csg::Ray{line.o, d, t0, t1}, ctx);
        std::vector<Interval1> expected, got;
        for (const csg::Span& span : full) expected.push_back({span.in.t, span.out.t});
        for (const csg::Span& span : part) got.push_back({span.in.t, span.out.t});
        expected = clippedTo(expected, t0, t1, 1e-9);
        got = clippedTo(got, t0, t1, 1e-9);
        ASSERT_EQ(got.size(), expected.size()) << "ray " << i;
        for (size_t k = 0; k < got.size(); ++k) {
            EXPECT_NEAR(got[k].in, expected[k].in, 1e-9) << "ray " << i;
            EXPECT_NEAR(got[k].out, expected[k].out, 1e-9) << "ray " << i;
        }
        checked += !got.empty();

        // From a point inside the twisted prism, if a is one: the first surface end past it.
        if (!scene.inside(a)) continue;
        const std::optional<csg::Hit> hit = scene.closest(csg::Ray{a, d, 0.0, csg::kInfinity}, ctx);
        double firstExit = csg::kInfinity;
        for (const csg::Span& span : full)
            if (span.out.t > 30.0 + 1e-9) {
                firstExit = span.in.t > 30.0 + 1e-9 ? span.in.t : span.out.t;
                break;
            }
        ASSERT_TRUE(hit.has_value()) << "ray " << i;
        EXPECT_NEAR(hit->t, firstExit - 30.0, 1e-9) << "ray " << i;
        ++exits;
    }
    EXPECT_GT(checked, 100);
    EXPECT_GT(exits, 50);
}

// The normal at a span end is the exact surface's: for the twisted square's edge x' = 1 the
// surface is p(u, z) = (R(-9z deg) (1, u), z), whose tangents are d/du = (R (0, 1), 0) and
// d/dz = (R' (1, u) 9 deg, 1). The normal is orthogonal to both and points out (against d
// where the line enters).
TEST(TwistedSpans, NormalsAreOrthogonalToTheSurface) {
    const Extrusion e = extrude(centredSquare(1.0), 0.0, 10.0, Vec2(1.0), 90.0);
    csg::testing::Rng rng(5);
    int checked = 0;
    for (int i = 0; i < 500; ++i) {
        const Vec3 target = rng.inBox(Vec3(-0.5, -0.5, 1.0), Vec3(0.5, 0.5, 9.0));
        const Vec3 o = target + 4.0 * rng.unit();
        const Vec3 d = target - o;
        csg::LocalSpans s;
        e.spans(o, d, s);
        ASSERT_GE(s.count, 1);
        for (const bool entry : {true, false}) {
            const double t = entry ? s.entries[0].tIn : s.entries[s.count - 1].tOut;
            const uint16_t face = entry ? s.entries[0].faceIn : s.entries[s.count - 1].faceOut;
            if (face < Extrusion::kFirstSideFace) continue;
            const Vec3 p = o + t * d;
            const Vec3 n = e.normal(p, face);
            EXPECT_NEAR(glm::length(n), 1.0, 1e-14);
            EXPECT_EQ(glm::dot(n, d) < 0.0, entry);
            // The section's frame: which edge of the square the point is on.
            const double phi = 9.0 * p.z * kDeg;
            const Vec2 q = rotated(Vec2(p), phi);
            const int axis = std::abs(q.x) > std::abs(q.y) ? 0 : 1;
            const double sign = q[axis] > 0 ? 1.0 : -1.0;
            Vec2 along(0.0);
            along[1 - axis] = 1.0;
            const Vec3 du(rotated(along, -phi), 0.0);
            // d/dz of R(-phi(z)) q with q fixed: -phi' J R(-phi) q, J the quarter turn.
            const Vec2 rq = rotated(q, -phi);
            const Vec3 dz(9.0 * kDeg * Vec2(rq.y, -rq.x), 1.0);
            EXPECT_NEAR(glm::dot(n, du), 0.0, 1e-12);
            EXPECT_NEAR(glm::dot(n, glm::normalize(dz)), 0.0, 1e-12);
            (void)sign;
            ++checked;
        }
    }
    EXPECT_GT(checked, 600);
}

// For per-axis scales and curved segments the normal is checked against the solid itself: a
// step of 1e-6 of the part along it from a side hit leaves the solid and a step against it
// enters (hits near the segments' ends and the caps' rims, where the surface has an edge, are
// skipped), and the hits of lines 1e-5 of the part beside it lie in the tangent plane to
// second order.
TEST(TwistedSpans, NormalsPointOutOfScaledAndCurvedSolids) {
    const RandomCase cases[] = {
        {"star scale [2, 0.5] twist 120", star(), Vec2(2.0, 0.5), 120.0},
        {"offset circle scale [1, 3]", offsetCircle(), Vec2(1.0, 3.0), 0.0},
        {"curvy scale 0.3 twist -90", curvy(), Vec2(0.3), -90.0},
    };
    csg::testing::Rng rng(77);
    for (const RandomCase& c : cases) {
        const Extrusion e = extrude(c.outline, -1.0, 4.0, c.scale, c.twist);
        const csg::Bounds3 box = e.bounds();
        const double size = glm::length(box.hi - box.lo);
        int checked = 0;
        for (int i = 0; i < 400; ++i) {
            const Vec3 target = rng.inBox(box.lo, box.hi);
            const Vec3 d = rng.unit();
            const Vec3 o = target - size * d;
            csg::LocalSpans s;
            e.spans(o, d, s);
            if (s.count == 0 || s.entries[0].faceIn < Extrusion::kFirstSideFace) continue;
            const double t = s.entries[0].tIn;
            const Vec3 p = o + t * d;
            if (p.z < -1.0 + 1e-3 * size || p.z > 4.0 - 1e-3 * size) continue;
            const Vec3 n = e.normal(p, s.entries[0].faceIn);
            // Away from edges: the neighbouring lines hit the same face.
            const Vec3 side = glm::normalize(glm::cross(d, n + Vec3(0.1, 0.2, 0.3)));
            const Vec3 side2 = glm::cross(d, side);
            bool smooth = true;
            for (const Vec3 offset : {side, -side, side2, -side2}) {
                csg::LocalSpans near;
                e.spans(o + 1e-5 * size * offset, d, near);
                if (near.count == 0 || near.entries[0].faceIn != s.entries[0].faceIn ||
                    std::abs(near.entries[0].tIn - t) > 1e-3 * size) {
                    smooth = false;
                    break;
                }
                // Off the tangent plane by the curvature (radii >= 0.1 here) times the squared
                // distance; a normal off by an angle a would add a |q - p|.
                const Vec3 q = o + 1e-5 * size * offset + near.entries[0].tIn * d;
                const double gap = glm::distance(q, p);
                EXPECT_LT(std::abs(glm::dot(q - p, n)), 10.0 * gap * gap + 1e-12 * size) << c.name;
            }
            if (!smooth) continue;
            EXPECT_FALSE(e.inside(p + 1e-6 * size * n)) << c.name << " line " << i;
            EXPECT_TRUE(e.inside(p - 1e-6 * size * n)) << c.name << " line " << i;
            ++checked;
        }
        EXPECT_GT(checked, 60) << c.name;
    }
}

// ---- (e) volumes ----

// The part a .scad text evaluates to, turned by `turn`, compiled.
csg::Scene scadScene(const std::string& text, const csg::Mat4& turn) {
    const io::EvaluateResult r = evaluate(text);
    EXPECT_TRUE(r.ok()) << diagnosticsOf(r);
    return csg::Scene::compile(csg::transformed(turn, r.model->root));
}

double scadVolume(const std::string& text, int resolution, bool onItsSide) {
    // On its side: level rays through the twisted solid, not only vertical ones.
    const csg::Mat4 turn =
        onItsSide ? glm::rotate(csg::Mat4(1.0), 0.5 * kPi, Vec3(1, 0, 0)) : csg::Mat4(1.0);
    // Lines along z: through the upright solid along its axis, through the one on its side level.
    return csg::volume(scadScene(text, turn), resolution, 0, csg::VolumeAxis::Z);
}

// volume()'s lines run across a twisted extrusion's axis, where each meets one section (a
// line along the axis sweeps the whole twist), and every axis gives the same volume.
TEST(TwistedVolume, LinesRunAcrossTheTwistedAxis) {
    const std::string twisted =
        "linear_extrude(height = 10, twist = 720) square(2, center = true);";
    // Upright, on its side along y, along x, and tilted: the lines' axis is one the twisted
    // axis (turned by the rounded rotation) is nearly perpendicular to.
    for (const Vec3& about : {Vec3(0, 0, 1), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(1, 1, 0)}) {
        const csg::Mat4 turn = glm::rotate(csg::Mat4(1.0), 0.5 * kPi, glm::normalize(about));
        const Vec3 axis = csg::Mat3(turn) * Vec3(0, 0, 1);
        const int k = int(csg::volumeLineAxis(scadScene(twisted, turn)));
        ASSERT_TRUE(k >= 0 && k < 3);
        EXPECT_LT(std::abs(axis[k]), 1e-9) << about.x << " " << about.y << " " << about.z;
    }
    // Without twist, z as ever.
    EXPECT_EQ(csg::volumeLineAxis(scadScene("linear_extrude(10) square(2);", csg::Mat4(1.0))),
              csg::VolumeAxis::Z);
    const csg::Scene part = scadScene(twisted, csg::Mat4(1.0));
    for (const csg::VolumeAxis axis :
         {csg::VolumeAxis::X, csg::VolumeAxis::Y, csg::VolumeAxis::Z, csg::VolumeAxis::Auto})
        EXPECT_NEAR(csg::volume(part, 256, 0, axis), 40.0, 40.0 * 1e-3) << int(axis);
}

// A twist turns every section rigidly: the volume is the profile's area times the height.
// A scale per axis makes the section's area A sigma_x(s) sigma_y(s), so the volume is
// A h (1 + (a + b) / 2 + a b / 3), a = sx - 1, b = sy - 1, with or without a twist.
TEST(TwistedVolume, IsAreaTimesHeight) {
    struct Case {
        const char* scad;
        double volume;
    };
    const double a = 1.0, b = -0.5;  // scale [2, 0.5]
    const Case cases[] = {
        {"linear_extrude(height = 10, twist = 90) square(2, center = true);", 40.0},
        {"linear_extrude(height = 5, twist = -300) translate([1, 0]) square([2, 1]);", 10.0},
        {"linear_extrude(height = 4, twist = 180) translate([2, 0]) circle(1);", 4.0 * kPi},
        {"linear_extrude(height = 3, scale = [2, 0.5]) square(2, center = true);",
         12.0 * (1.0 + 0.5 * (a + b) + a * b / 3.0)},
        {"linear_extrude(height = 3, scale = [2, 0.5], twist = 100) square(2, center = true);",
         12.0 * (1.0 + 0.5 * (a + b) + a * b / 3.0)},
        // A twisted pyramid: scale 0 gives A h / 3.
        {"linear_extrude(height = 6, scale = 0, twist = 360) square(2, center = true);", 8.0},
    };
    for (const Case& c : cases) {
        for (const bool side : {false, true}) {
            const double v = scadVolume(c.scad, 512, side);
            // The span integral is exact per ray; the silhouette's quadrature at 512^2 rays
            // is within 1e-3 for these sizes (tests/volume_test.cpp uses the same bound).
            EXPECT_NEAR(v / c.volume, 1.0, 1e-3) << c.scad << (side ? " on its side" : "");
        }
    }
}

// ---- (f) against OpenSCAD 2021's own meshes ----

using csg::testing::haveOpenScad;

struct StlMesh {
    std::vector<std::array<Vec3, 3>> triangles;
};

// A binary STL as OpenSCAD writes it with --export-format binstl.
StlMesh readBinaryStl(const std::filesystem::path& path) {
    return {csg::testing::binaryStlTriangles(path)};
}

struct MeshMeasures {
    double volume = 0.0, area = 0.0;
};
MeshMeasures measure(const StlMesh& mesh) {
    MeshMeasures m;
    for (const auto& t : mesh.triangles) {
        m.volume += glm::dot(t[0], glm::cross(t[1], t[2])) / 6.0;
        m.area += 0.5 * glm::length(glm::cross(t[1] - t[0], t[2] - t[0]));
    }
    return m;
}

// The distance from p to the solid's boundary is at most that to the nearest span end of any
// line through p: the vertical one and 180 level ones, 2 degrees apart (starting at 1 degree,
// off the axes). So many because a vertex at a sharp tip of a section (the spring's ends, a
// corner of the frustum's base) is touched, not crossed, by most lines through it; a tip of
// an opening wider than 2 degrees is entered by one of the level lines.
double boundaryDistanceBound(const csg::Scene& scene, const Vec3& p, csg::QueryContext& ctx) {
    double best = csg::kInfinity;
    const auto along = [&](const Vec3& d) {
        for (const csg::Span& s : scene.spans({p, d, -csg::kInfinity, csg::kInfinity}, ctx))
            best = std::min({best, std::abs(s.in.t), std::abs(s.out.t)});
    };
    along(Vec3(0.0, 0.0, 1.0));
    for (int k = 0; k < 180 && best > 0.0; ++k) {
        const double a = (1.0 + 2.0 * k) * kDeg;
        along(Vec3(std::cos(a), std::sin(a), 0.0));
    }
    return best;
}

struct OpenScadCase {
    const char* name;
    std::string file;
    // OpenSCAD's slicing error, a bound on how far its triangles stand off the exact surface
    // (derived in the test below for each part).
    double slicingError;
};

// OpenSCAD samples the exact surface at its slices and joins the samples by triangles: every
// vertex it makes from the profile lies on the exact surface (to float rounding, 1e-5 at these
// sizes), and a vertex of a boolean cut (the nut's bore) on its triangles, so within the
// slicing error of the exact surface. Between layers s_j and s_j + ds, a point of an edge
// sweeps R(-theta s) sigma(s) p, whose chord between the layers is off by at most
// ds^2 / 8 max|d^2/ds^2| <= (theta ds)^2 rho / 8 + |sigma'| theta ds^2 rho / 4, and the two
// triangles of the quad are off its bilinear patch by at most |twist vector| / 4 <=
// (theta ds sigma + |d sigma|) L / 4 (L the edge's length, rho the largest radius). The volumes
// differ by at most that error times the surface area, plus the exact side's quadrature.
TEST(AgainstOpenScad, VerticesAndVolumesWithinTheSlicingError) {
    if (!haveOpenScad()) GTEST_SKIP() << "openscad is not installed";
    const std::string examples = "/usr/share/openscad/examples/";
    if (!std::filesystem::exists(examples + "Old/example020.scad"))
        GTEST_SKIP() << "OpenSCAD's examples are not installed";
    // example020: the screw (twist 360 * 8 / 7 = 411.4 degrees over 100, 35 slices; rho <= 40,
    // edges <= 20): 411.4 / 35 = 11.76 degrees a slice, 0.205 rad: 0.205^2 * 40 / 8 +
    // 0.205 * 20 / 4 = 1.24. The nut's screw: 2 x 411.4 degrees over 40, 69 slices: 0.208 rad,
    // rho <= 42: 1.27. The spring: twist 1500 over 100, $fn = 19.2 -> 80 slices of 0.327 rad,
    // rho <= 110, edges <= 20 (a segment's radial side): 1.47 + 1.64 = 3.1. csgray's solid is
    // the exact one (--curves auto: --curves openscad would build OpenSCAD's slices, see
    // sliced_extrusion_test), so its circles are exact where OpenSCAD's are 30-gons: the
    // sagitta, 20 (1 - cos 6 degrees) = 0.11, fits in each margin.
    // Basics/linear_extrude: the cyan block (twist 90 over 20, 7 slices: 0.224 rad, rho 11.2,
    // L 20: 0.07 + 1.12 = 1.2) and the gray pyramid (twist -360 over 40 with scale 0 and 200
    // slices: 0.0314 rad, rho 11.2, L 20, d sigma = 0.005: 0.0014 + 0.0014 + 0.2 = 0.2).
    const OpenScadCase cases[] = {
        {"example020", examples + "Old/example020.scad", 3.2},
        {"linear_extrude", examples + "Basics/linear_extrude.scad", 1.2},
    };
    for (const OpenScadCase& c : cases) {
        csg::testing::TempDir dir(std::string("csgray_twist_") + c.name);
        const auto stl = dir.path / "part.stl";
        const std::string command = "openscad --export-format binstl -o " + shellQuote(stl) + " " +
                                    shellQuote(c.file) + " >/dev/null 2>&1";
        ASSERT_EQ(std::system(command.c_str()), 0) << command;
        const StlMesh mesh = readBinaryStl(stl);
        ASSERT_GT(mesh.triangles.size(), 100u) << c.name;

        io::EvaluateOptions options;
        options.curves = io::CurveMode::Auto;
        const io::EvaluateResult r = io::evaluateString(readFile(c.file), c.file, options);
        ASSERT_TRUE(r.ok()) << diagnosticsOf(r);
        const csg::Scene scene = csg::Scene::compile(r.model->root);
        csg::QueryContext ctx;
        // The distinct vertices (each is shared by ~6 triangles), every one of them.
        std::vector<Vec3> vertices;
        for (const auto& t : mesh.triangles) vertices.insert(vertices.end(), t.begin(), t.end());
        std::sort(vertices.begin(), vertices.end(), [](const Vec3& a, const Vec3& b) {
            return a.x != b.x ? a.x < b.x : a.y != b.y ? a.y < b.y : a.z < b.z;
        });
        vertices.erase(std::unique(vertices.begin(), vertices.end()), vertices.end());
        double worst = 0.0;
        Vec3 worstAt(0.0);
        for (const Vec3& v : vertices) {
            const double distance = boundaryDistanceBound(scene, v, ctx);
            if (distance > worst) worst = distance, worstAt = v;
        }
        EXPECT_LE(worst, c.slicingError)
            << c.name << " over " << vertices.size() << " vertices; the farthest at " << worstAt.x
            << ", " << worstAt.y << ", " << worstAt.z;
        const MeshMeasures theirs = measure(mesh);
        const double ours = csg::volume(scene, 256);
        EXPECT_LE(std::abs(ours - theirs.volume), c.slicingError * theirs.area)
            << c.name << ": csgray " << ours << ", OpenSCAD " << theirs.volume;
        std::printf("%s: OpenSCAD volume %.6g, exact %.6g (%.3g%%); farthest vertex %.3g\n", c.name,
                    theirs.volume, ours, 100.0 * (ours - theirs.volume) / theirs.volume, worst);
    }
}

// ---- (h) the carriers: implicit equations of the outline's segments ----

// Every point of a segment zeroes its carrier (relative to F a tenth of the segment's size off
// it); F is homogeneous of its degree; the gradient and the second derivative along a
// direction match central differences; the interval evaluation encloses the double one.
TEST(SegmentCarrier, VanishesOnTheSegmentAndDifferentiates) {
    using csg::Interval;
    using csg::SegmentCarrier;
    struct Case {
        const char* name;
        Segment2 segment;
        SegmentCarrier::Kind kind;
        int degree;
    };
    const Case cases[] = {
        {"line", Segment2::line({-1, 2}, {3, 0.5}), SegmentCarrier::Kind::Line, 1},
        {"arc", Segment2::arc({0.5, 1.75}, {2.0, -0.25}, {0.1, 0.8}, 0.3, 2.5),
         SegmentCarrier::Kind::Ellipse, 2},
        {"quadratic", Segment2::quadratic({-2, -1}, {0, -3}, {2, -1.5}),
         SegmentCarrier::Kind::Parabola, 2},
        {"cubic", Segment2::cubic({2, -1.5}, {4, -0.5}, {1, 0.5}, {2.5, 1.5}),
         SegmentCarrier::Kind::Cubic, 3},
        {"cubic loop", Segment2::cubic({0, 0}, {3, 2}, {-1, 2}, {2, 0}),
         SegmentCarrier::Kind::Cubic, 3},
        // The quadratic (-1.5, 2), (-3, 0.5), (-2, -1) raised to degree 3: carried by its
        // parabola.
        {"raised", Segment2::cubic({-1.5, 2}, {-7.5 / 3, 3.0 / 3}, {-8.0 / 3, 0.0}, {-2, -1}),
         SegmentCarrier::Kind::Parabola, 2},
        // Collinear control points: carried by the line.
        {"flat cubic", Segment2::cubic({0, 0}, {1, 1}, {3, 3}, {2, 2}), SegmentCarrier::Kind::Line,
         1},
    };
    csg::testing::Rng rng(9);
    for (const Case& c : cases) {
        const SegmentCarrier carrier = SegmentCarrier::of(c.segment);
        EXPECT_EQ(carrier.kind, c.kind) << c.name;
        const int degree = carrier.kind == SegmentCarrier::Kind::Line    ? 1
                           : carrier.kind == SegmentCarrier::Kind::Cubic ? 3
                                                                         : 2;
        const auto F = [&](Vec3 z) { return csg::carrierValue(carrier, z.x, z.y, z.z); };
        for (int k = 0; k <= 20; ++k) {
            const double u = k / 20.0;
            const Vec2 q = c.segment.at(u);
            const Vec2 n = glm::normalize(Vec2(-c.segment.tangent(u).y, c.segment.tangent(u).x));
            const double off =
                std::max(std::abs(F(Vec3(q + 0.1 * n, 1.0))), std::abs(F(Vec3(q - 0.1 * n, 1.0))));
            EXPECT_LE(std::abs(F(Vec3(q, 1.0))), 1e-12 * off) << c.name << " u " << u;
        }
        for (int k = 0; k < 20; ++k) {
            const Vec3 z(rng.uniform(-3, 3), rng.uniform(-3, 3), rng.uniform(0.2, 2));
            const Vec3 e = rng.unit();
            const double lambda = rng.uniform(0.5, 3.0);
            const double f = F(z);
            EXPECT_NEAR(F(lambda * z), std::pow(lambda, degree) * f,
                        1e-11 * (std::abs(f) + 1.0) * std::pow(lambda, degree))
                << c.name;
            double g[3];
            csg::carrierGradient(carrier, z.x, z.y, z.z, g);
            const double h = 1e-5;
            for (int a = 0; a < 3; ++a) {
                Vec3 dz(0.0);
                dz[a] = h;
                const double fd = (F(z + dz) - F(z - dz)) / (2 * h);
                EXPECT_NEAR(g[a], fd, 1e-6 * (std::abs(fd) + std::abs(f) + 1.0)) << c.name;
            }
            const double curvature = csg::carrierCurvature(carrier, z.x, z.y, z.z, e.x, e.y, e.z);
            const double hc = 1e-3;
            const double fdd = (F(z + hc * e) - 2 * f + F(z - hc * e)) / (hc * hc);
            EXPECT_NEAR(curvature, fdd, 1e-4 * (std::abs(fdd) + std::abs(f) + 1.0)) << c.name;
            const Interval x{z.x, z.x}, y{z.y, z.y}, w{z.z, z.z};
            const Interval enclosed = csg::carrierValue(carrier, x, y, w);
            EXPECT_LE(enclosed.lo, f) << c.name;
            EXPECT_GE(enclosed.hi, f) << c.name;
        }
    }
}

// ---- (g) the language and the contract ----

TEST(TwistLanguage, AcceptsTwistScalePairAndSlices) {
    const io::EvaluateResult r = evaluate(
        "linear_extrude(height = 3, twist = 30, slices = 7, scale = [1.5, 0.5], center = true)"
        " square(1);");
    ASSERT_TRUE(r.ok()) << diagnosticsOf(r);
    const auto& e = std::get<Extrusion>(r.model->root->primitive);
    EXPECT_EQ(e.twist, 30.0);
    EXPECT_EQ(e.scale, Vec2(1.5, 0.5));
    EXPECT_EQ(e.z0, -1.5);
    EXPECT_EQ(e.z1, 1.5);
    // A negative factor is 0, as in OpenSCAD; a non-number is an error at the argument.
    const io::EvaluateResult zero = evaluate("linear_extrude(1, scale = [-1, 2]) square(1);");
    ASSERT_TRUE(zero.ok()) << diagnosticsOf(zero);
    EXPECT_EQ(std::get<Extrusion>(zero.model->root->primitive).scale, Vec2(0.0, 2.0));
    EXPECT_FALSE(evaluate("linear_extrude(1, twist = \"a\") square(1);").ok());
}

// A twisted extrusion unions its children first, as OpenSCAD does: one leaf whose outline is
// the boundary of the children's booleans (circular arcs kept, holes clockwise). Vertical lines
// by hand, twist 90 over height 10 (a point turns by 9z degrees): in the square of half-width 5
// with a hole of radius 3, the line at radius 4 is inside at every height and the one at
// radius 2 nowhere; the one at (6, 0) is inside while its turned point (6 cos a, 6 sin a) has
// both coordinates within 5: a in [acos(5/6), asin(5/6)]. In the bar [-5, 5] x [-2, 2] united
// with the disc of radius 3, the line at (0, 3.5) is inside while |3.5 cos a| <= 2: from
// a = acos(4/7) up.
TEST(TwistLanguage, ChildrenAreUnitedIntoOneLeaf) {
    const auto heightOf = [](double radians) { return radians / (kPi / 2) * 10.0; };
    const io::EvaluateResult holed = evaluate(
        "linear_extrude(10, twist = 90) difference() { square(10, center = true); circle(3); }");
    ASSERT_TRUE(holed.ok()) << diagnosticsOf(holed);
    ASSERT_EQ(holed.model->root->op, csg::Op::Leaf);
    const auto& e = std::get<Extrusion>(holed.model->root->primitive);
    const auto spans = [&](const Extrusion& x, Vec2 at) {
        return spansOf(x, Vec3(at, -5.0), Vec3(0, 0, 1));
    };
    auto s = spans(e, {0.0, 4.0});
    ASSERT_EQ(s.size(), 1u);
    EXPECT_NEAR(s[0].in, 5.0, 1e-12);
    EXPECT_NEAR(s[0].out, 15.0, 1e-12);
    EXPECT_TRUE(spans(e, {-2.0, 0.0}).empty());
    s = spans(e, {6.0, 0.0});
    ASSERT_EQ(s.size(), 1u);
    EXPECT_NEAR(s[0].in, 5.0 + heightOf(std::acos(5.0 / 6.0)), 1e-12);
    EXPECT_NEAR(s[0].out, 5.0 + heightOf(std::asin(5.0 / 6.0)), 1e-12);

    const io::EvaluateResult barred = evaluate(
        "linear_extrude(10, twist = 90) union() { square([10, 4], center = true); circle(3); }");
    ASSERT_TRUE(barred.ok()) << diagnosticsOf(barred);
    ASSERT_EQ(barred.model->root->op, csg::Op::Leaf);
    const auto& bar = std::get<Extrusion>(barred.model->root->primitive);
    s = spans(bar, {0.0, 3.5});
    ASSERT_EQ(s.size(), 1u);
    EXPECT_NEAR(s[0].in, 5.0 + heightOf(std::acos(4.0 / 7.0)), 1e-12);
    EXPECT_NEAR(s[0].out, 15.0, 1e-12);
    s = spans(bar, {0.0, 2.5});  // in the disc at every height
    ASSERT_EQ(s.size(), 1u);
    EXPECT_NEAR(s[0].in, 5.0, 1e-12);
    EXPECT_NEAR(s[0].out, 15.0, 1e-12);
    // An ellipse has no circular boundary pieces: the children stay a tree, exactly.
    const io::EvaluateResult elliptic =
        evaluate("linear_extrude(10, twist = 90) union() { scale([2, 1]) circle(1); square(1); }");
    ASSERT_TRUE(elliptic.ok()) << diagnosticsOf(elliptic);
    EXPECT_EQ(elliptic.model->root->op, csg::Op::Union);
}

// A piece of an arc is carried by its whole ellipse, but its box is its own: the arc's points
// (sampled) lie in it, and a quarter of a circle's box is a quarter of the circle's.
TEST(SegmentCarrier, AnArcsBoxIsItsOwn) {
    const Segment2 quarter = Segment2::arc({1, 2}, {3, 0}, {0, 3}, 0.25 * kPi, 0.75 * kPi);
    const csg::Bounds2 box = csg::SegmentCarrier::of(quarter).box;
    EXPECT_NEAR(box.lo.x, 1.0 - 3.0 * std::sqrt(0.5), 1e-13);
    EXPECT_NEAR(box.hi.x, 1.0 + 3.0 * std::sqrt(0.5), 1e-13);
    EXPECT_NEAR(box.lo.y, 2.0 + 3.0 * std::sqrt(0.5), 1e-13);
    EXPECT_NEAR(box.hi.y, 5.0, 1e-13);  // the top of the circle, at pi / 2
    csg::testing::Rng rng(4);
    for (int k = 0; k < 200; ++k) {
        const Vec2 centre{rng.uniform(-5, 5), rng.uniform(-5, 5)};  // braces: drawn in order
        const Vec2 a{rng.uniform(-3, 3), rng.uniform(-3, 3)},
            b{rng.uniform(-3, 3), rng.uniform(-3, 3)};
        const double th0 = rng.uniform(-10, 10), th1 = th0 + rng.uniform(0.01, 6.2);
        const Segment2 arc = Segment2::arc(centre, a, b, th0, th1);
        const csg::Bounds2 arcBox = csg::SegmentCarrier::of(arc).box;
        for (int j = 0; j <= 100; ++j) {
            const Vec2 p = arc.at(j / 100.0);
            EXPECT_TRUE(p.x >= arcBox.lo.x && p.x <= arcBox.hi.x && p.y >= arcBox.lo.y &&
                        p.y <= arcBox.hi.y)
                << k << " " << j;
        }
    }
}

// Twisted lines allocate nothing once the per-thread scratch has grown.
TEST(TwistedSpans, QueriesAllocateNothing) {
    const io::EvaluateResult r = evaluate(
        "linear_extrude(height = 10, twist = 200, scale = [1.5, 0.7]) difference() {"
        " square(4, center = true); translate([1, 0]) circle(0.5); }");
    ASSERT_TRUE(r.ok()) << diagnosticsOf(r);
    const csg::Scene scene = csg::Scene::compile(r.model->root);
    csg::QueryContext ctx;
    auto runAll = [&] {
        csg::testing::Rng rng(3);
        size_t found = 0;
        for (int i = 0; i < 2000; ++i) {
            const Vec3 target = rng.inBox(Vec3(-3, -3, 0), Vec3(3, 3, 10));
            const Vec3 o = target + 20.0 * rng.unit();
            const csg::Ray ray{o, target - o, 0.0, 2.0};
            found += scene.spans(ray, ctx).size();
            found += scene.closest(ray, ctx).has_value();
            found += scene.occluded(ray, ctx);
        }
        return found;
    };
    const size_t warm = runAll();
    const long before = csg::testing::allocations.load();
    EXPECT_EQ(runAll(), warm);
    EXPECT_EQ(csg::testing::allocations.load() - before, 0);
    EXPECT_GT(warm, 1000u);
}

}  // namespace
