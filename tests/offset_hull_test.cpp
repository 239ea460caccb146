// offset() and hull() (csg/derived/, io/Offset.cpp, io/Hull.cpp). The oracles are independent
// of the code under test:
//   - spans of rays derived by hand: chords of the rounded corners' circles, the miter and
//     chamfer lines (OPENSCAD.md section 2: square(10) chamfered by 1 has its corner points at
//     10.4142), tangent lines of two circles, the planes of a 3-D hull through given vertices;
//   - for seeded random points, membership against the definition: within r of the region
//     (r > 0), or in the region at least |r| from its boundary (r < 0), with distances to
//     segments and circles computed here;
//   - OpenSCAD 2021's own STL (`openscad` on the PATH) through csgray's compare command under
//     --curves openscad: Clipper's offset on its 2^-16 grid, the hulls of faceted solids.
// Notation: t is the parameter of o + t d.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <numbers>

#include <nlohmann/json.hpp>

#include "CliRunner.h"
#include "MissingTool.h"
#include "csg/Scene.h"
#include "io/Evaluate.h"
#include "tests/PartHelpers.h"
#include "tests/SeededRng.h"

namespace {

using csg::testing::compiled;
using csg::testing::diagnosticsOf;
using csg::testing::evaluate;
using csg::testing::expectRow;
using csg::testing::Interval;

using csg::Vec2;
using csg::Vec3;

// Lines here may touch a rounded offset's arcs: their zero-length spans are left out.
std::vector<Interval> solidSpans(const csg::Scene& scene, Vec3 o, Vec3 d) {
    return csg::testing::spansOf(scene, o, d, true);
}
void expectSolidSpans(const csg::Scene& scene, Vec3 o, Vec3 d,
                      const std::vector<Interval>& expected, double tol) {
    csg::testing::expectSpans(scene, o, d, expected, tol, true);
}

// offset(r = 1) of square(2): the square grown by 1 with quarter circles of radius 1 about its
// corners. At height y above the top edge (2 < y < 3) the corners' circles give
// x in [-sqrt(1 - (y-2)^2), 2 + sqrt(1 - (y-2)^2)].
TEST(Offset, RoundedSquareByHand) {
    const csg::Scene scene = compiled("linear_extrude(1) offset(r = 1) square(2);");
    expectRow(scene, 1.0, {{-1, 3}}, 1e-12);
    for (double y : {2.25, 2.5, 2.9, 2.999}) {
        const double h = std::sqrt(1.0 - (y - 2) * (y - 2));
        expectRow(scene, y, {{-h, 2 + h}}, 1e-12);
    }
    expectRow(scene, 3.001, {}, 0.0);
    // Diagonally through the corner circle about (0, 0): x = y = t - 5 from -1/sqrt 2.
    const double c = std::sqrt(0.5);
    expectSolidSpans(scene, {-5, -5, 0.5}, {1, 1, 0}, {{5 - c, 7 + c}}, 1e-12);
    // r is the first positional argument; no argument at all is r = 1.
    expectRow(compiled("linear_extrude(1) offset(1) square(2);"), 2.5,
              {{-std::sqrt(0.75), 2 + std::sqrt(0.75)}}, 1e-12);
    expectRow(compiled("linear_extrude(1) offset() square(2);"), 2.5,
              {{-std::sqrt(0.75), 2 + std::sqrt(0.75)}}, 1e-12);
}

// offset(r < 0): the square shrinks by 0.5; an L's reflex corner at (1, 1) becomes an arc of
// radius 0.25 about it, joining its moved edges x = 0.75 and y = 0.75, while its convex
// corners stay sharp.
TEST(Offset, NegativeRadiusByHand) {
    const csg::Scene square = compiled("linear_extrude(1) offset(r = -0.5) square(2);");
    expectRow(square, 1.0, {{0.5, 1.5}}, 1e-12);
    expectRow(square, 1.49, {{0.5, 1.5}}, 1e-12);
    expectRow(square, 1.51, {}, 0.0);
    const std::string l = "polygon([[0,0],[2,0],[2,1],[1,1],[1,2],[0,2]])";
    const csg::Scene shrunk = compiled("linear_extrude(1) offset(r = -0.25) " + l + ";");
    expectRow(shrunk, 0.5, {{0.25, 1.75}}, 1e-12);
    // Between the moved edges y = 0.75 and x = 0.75: the arc about (1, 1).
    for (double y : {0.8, 0.9, 0.99}) {
        const double dy = 1.0 - y;
        expectRow(shrunk, y, {{0.25, 1.0 - std::sqrt(0.0625 - dy * dy)}}, 1e-12);
    }
    expectRow(shrunk, 1.1, {{0.25, 0.75}}, 1e-12);
    // A shape narrower than twice |r| vanishes.
    EXPECT_TRUE(solidSpans(compiled("linear_extrude(1) offset(r = -1) square([10, 1.9]);"),
                           {5, 0.95, -5}, {0, 0, 1})
                    .empty());
}

// offset(delta): Clipper's miter joins, sharp at any angle OpenSCAD meets (miter limit 1e6).
TEST(Offset, DeltaKeepsCornersSharp) {
    const csg::Scene grown = compiled("linear_extrude(1) offset(delta = 1) square(2);");
    expectRow(grown, 2.9, {{-1, 3}}, 1e-12);
    expectSolidSpans(grown, {-5, -5, 0.5}, {1, 1, 0}, {{4, 8}}, 1e-12);
    // A triangle's 45 degree corner: the miter point lies 1 / sin(22.5 deg) from the vertex
    // along the bisector. Triangle (0,0), (10,0), (0,10): its corner at (10, 0) moves to
    // (10 + 1 + sqrt 2, -1) (where y = -1 meets x + y = 10 + sqrt 2).
    const csg::Scene triangle =
        compiled("linear_extrude(1) offset(delta = 1) polygon([[0,0],[10,0],[0,10]]);");
    expectRow(triangle, -0.5, {{-1, 11 + std::sqrt(2.0) - 0.5}}, 1e-12);
    // Shrinking an L keeps its reflex corner sharp: the moved edges x = 0.75 (above y = 0.75)
    // and y = 0.75 meet at (0.75, 0.75).
    const csg::Scene shrunk = compiled(
        "linear_extrude(1) offset(delta = -0.25) polygon([[0,0],[2,0],[2,1],[1,1],[1,2],[0,2]]);");
    expectRow(shrunk, 0.76, {{0.25, 0.75}}, 1e-12);
    expectRow(shrunk, 0.74, {{0.25, 1.75}}, 1e-12);
}

// chamfer = true: each corner cut by the line perpendicular to its bisector at distance delta
// from the vertex; for square(10) and delta 1 it meets the moved edges at 10 + tan(22.5 deg)
// = 10.4142 (OPENSCAD.md), i.e. it is the line x + y = 21.4142 at the top right corner.
TEST(Offset, ChamferCutsCornersAtDelta) {
    const double cut = 10.0 + std::tan(std::numbers::pi / 8);
    for (io::CurveMode mode : {io::CurveMode::Auto, io::CurveMode::OpenScad}) {
        const double tol = mode == io::CurveMode::Auto ? 1e-12 : 3e-5;  // Clipper's grid
        const csg::Scene scene =
            compiled("linear_extrude(1) offset(delta = 1, chamfer = true) square(10);", mode);
        expectRow(scene, 5.0, {{-1, 11}}, tol);
        expectRow(scene, 10.2, {{-1, 11}}, tol);
        const double y = 10.7;
        expectRow(scene, y, {{y - 1 - cut, 11 + cut - y}}, tol);
        // The corner points themselves: at y = cut the chamfer starts at x = 11.
        expectRow(scene, cut - 1e-9, {{-1, 11}}, tol + 1e-8);
    }
}

// The boundary of a difference is what grows, not its leaves' outlines: square(10) minus a
// block that removes its right half grows to x in [-1, 6], not to 11 (the removed edge) or
// 16 (the block's far side); a square hole shrinks to a square of side 2 with sharp corners
// (a hole's corners are reflex corners of the shape) and, shrinking the shape, grows with
// rounded ones.
TEST(Offset, DifferenceGrowsItsOwnBoundary) {
    const csg::Scene halved = compiled(
        "linear_extrude(1) offset(r = 1) difference() { square(10); "
        "translate([5, -5]) square([10, 20]); }");
    expectRow(halved, 5.0, {{-1, 6}}, 1e-12);
    expectRow(halved, 10.5, {{-std::sqrt(0.75), 5 + std::sqrt(0.75)}}, 1e-12);
    const std::string holed =
        "difference() { square(10, center = true); square(4, center = true); }";
    const csg::Scene grown = compiled("linear_extrude(1) offset(r = 1) " + holed + ";");
    expectRow(grown, 0.0, {{-6, -1}, {1, 6}}, 1e-12);
    expectRow(grown, 0.99, {{-6, -1}, {1, 6}}, 1e-12);
    expectRow(grown, 1.01, {{-6, 6}}, 1e-12);
    const csg::Scene shrunk = compiled("linear_extrude(1) offset(r = -1) " + holed + ";");
    expectRow(shrunk, 0.0, {{-4, -3}, {3, 4}}, 1e-12);
    const double x = 2 + std::sqrt(0.75);  // the arc of radius 1 about the hole's corner
    expectRow(shrunk, 2.5, {{-4, -x}, {x, 4}}, 1e-12);
    expectRow(shrunk, 3.5, {{-4, 4}}, 1e-12);
}

// Offsets of offsets: closing two squares 2 apart with r = 3 fills the gap but for a notch of
// depth 3 - sqrt(3^2 - 1^2) at the gap's middle (the discs of radius 3 about (10, 0) and
// (12, 0) meet at y = -sqrt 8 before shrinking back).
TEST(Offset, NestedOffsetsByHand) {
    const csg::Scene closed = compiled(
        "linear_extrude(1) offset(r = -3) offset(r = 3) "
        "union() { square(10); translate([12, 0]) square(10); }");
    expectRow(closed, 5.0, {{0, 22}}, 1e-9);
    const double notch = 3.0 - std::sqrt(8.0);
    expectSolidSpans(closed, {11, -5, 0.5}, {0, 1, 0}, {{5 + notch, 15 - notch}}, 1e-9);
    expectSolidSpans(closed, {0.5, -5, 0.5}, {0, 1, 0}, {{5, 15}}, 1e-9);
}

// Distances for the membership oracle.
double segmentDistance(Vec2 p, Vec2 a, Vec2 b) {
    const Vec2 d = b - a;
    const double u = std::clamp(glm::dot(p - a, d) / glm::dot(d, d), 0.0, 1.0);
    return glm::length(p - (a + d * u));
}

bool inPolygon(Vec2 p, const std::vector<Vec2>& poly) {
    bool in = false;
    for (size_t i = 0; i < poly.size(); ++i) {
        const Vec2 a = poly[i], b = poly[(i + 1) % poly.size()];
        if ((a.y > p.y) != (b.y > p.y) && p.x < a.x + (p.y - a.y) * (b.x - a.x) / (b.y - a.y))
            in = !in;
    }
    return in;
}

double polygonBoundaryDistance(Vec2 p, const std::vector<Vec2>& poly) {
    double best = csg::kInfinity;
    for (size_t i = 0; i < poly.size(); ++i)
        best = std::min(best, segmentDistance(p, poly[i], poly[(i + 1) % poly.size()]));
    return best;
}

// Whether the part's solid contains (x, y, 0.5): a vertical line's spans.
bool partContains(const csg::Scene& scene, Vec2 p) {
    for (const Interval& s : solidSpans(scene, {p.x, p.y, -5}, {0, 0, 1}))
        if (s.in <= 5.5 && s.out >= 5.5) return true;
    return false;
}

// Seeded random points against the definition of the offset, away from its boundary.
TEST(Offset, RandomPointsAgainstTheDefinition) {
    // A non-convex star (convex and reflex corners, edges at many angles), its points as the
    // part reads them (std::to_string's 6 decimals).
    std::vector<Vec2> star;
    std::string points;
    for (int k = 0; k < 10; ++k) {
        const double a = 2 * std::numbers::pi * k / 10, r = k % 2 ? 2.0 : 5.0;
        const std::string x = std::to_string(r * std::cos(a)), y = std::to_string(r * std::sin(a));
        star.push_back({std::stod(x), std::stod(y)});
        points += (k ? ",[" : "[") + x + "," + y + "]";
    }
    csg::testing::Rng rng(2021);
    for (double r : {0.7, -0.4}) {
        const csg::Scene scene = compiled("linear_extrude(1) offset(r = " + std::to_string(r) +
                                          ") polygon([" + points + "]);");
        int checked = 0;
        for (int i = 0; i < 3000; ++i) {
            const double x = rng.uniform(-6.0, 6.0);
            const double y = rng.uniform(-6.0, 6.0);
            const Vec2 p{x, y};
            const bool in = inPolygon(p, star);
            const double d = polygonBoundaryDistance(p, star);
            if (std::abs(d - std::abs(r)) < 1e-6) continue;  // on the offset's boundary
            const bool expected = r > 0 ? (in || d <= r) : (in && d >= -r);
            ASSERT_EQ(partContains(scene, p), expected) << "r = " << r << " at " << x << ", " << y;
            ++checked;
        }
        EXPECT_GT(checked, 2900);
    }
    // square(10) minus circle(3) (exact): the hole's boundary is a circle.
    for (double r : {0.8, -0.8}) {
        const csg::Scene scene =
            compiled("linear_extrude(1) offset(r = " + std::to_string(r) +
                     ") difference() { square(10, center = true); circle(3); }");
        const std::vector<Vec2> square{{-5, -5}, {5, -5}, {5, 5}, {-5, 5}};
        for (int i = 0; i < 2000; ++i) {
            const double x = rng.uniform(-6.0, 6.0);
            const double y = rng.uniform(-6.0, 6.0);
            const Vec2 p{x, y};
            const double fromCircle = glm::length(p) - 3.0;  // > 0 outside the hole
            const bool in = inPolygon(p, square) && fromCircle > 0.0;
            const double d = std::min(polygonBoundaryDistance(p, square), std::abs(fromCircle));
            if (std::abs(d - std::abs(r)) < 1e-6) continue;
            const bool expected = r > 0 ? (in || d <= r) : (in && d >= -r);
            ASSERT_EQ(partContains(scene, p), expected) << "r = " << r << " at " << x << ", " << y;
        }
    }
}

// Under faceting (a $fn on the offset, or --curves openscad) the offset is OpenSCAD's Clipper
// offset: $fn = 8 turns a right angle in two 45 degree steps, so the corner about (2, 2) is the
// chords (3, 2) - (2 + c, 2 + c) - (2, 3), c = cos 45; OpenSCAD's default (r = 1: 5 fragments)
// makes it one bevel from (3, 2) to (2, 3).
TEST(Offset, FacetedIsClippersPolygon) {
    const double c = std::sqrt(0.5);
    const csg::Scene eight = compiled("linear_extrude(1) offset(r = 1, $fn = 8) square(2);");
    // At y = 2.5 the chord from (3, 2) to (2 + c, 2 + c): x = 3 - 0.5 (1 - c) / c.
    const double x = 3.0 - 0.5 * (1.0 - c) / c;
    expectRow(eight, 2.5, {{2 - x, x}}, 3e-5);
    const csg::Scene bevel =
        compiled("linear_extrude(1) offset(r = 1) square(2);", io::CurveMode::OpenScad);
    expectRow(bevel, 2.5, {{-0.5, 2.5}}, 3e-5);
    expectRow(bevel, 1.0, {{-1, 3}}, 3e-5);
}

// hull() of two circles: the tangent lines of the circles and arcs of them. Equal radii give a
// stadium; radii 2 and 3 with centres 10 apart have the outer tangent at angle asin(0.1), so
// at x it lies at (2 + 0.1 x) / sqrt(0.99).
TEST(Hull, TwoCirclesByHand) {
    const csg::Scene stadium =
        compiled("linear_extrude(1) hull() { circle(1); translate([5, 0]) circle(1); }");
    expectSolidSpans(stadium, {2.5, -5, 0.5}, {0, 1, 0}, {{4, 6}}, 1e-12);
    expectSolidSpans(stadium, {-0.5, -5, 0.5}, {0, 1, 0},
                     {{5 - std::sqrt(0.75), 5 + std::sqrt(0.75)}}, 1e-12);
    expectRow(stadium, 0.5, {{-std::sqrt(0.75), 5 + std::sqrt(0.75)}}, 1e-12);
    const csg::Scene cone =
        compiled("linear_extrude(1) hull() { circle(2); translate([10, 0]) circle(3); }");
    for (double x : {0.0, 5.0, 9.0}) {
        const double y = (2 + 0.1 * x) / std::sqrt(0.99);
        expectSolidSpans(cone, {x, -10, 0.5}, {0, 1, 0}, {{10 - y, 10 + y}}, 1e-12);
    }
    // Beyond the tangent points, the circles themselves.
    expectRow(cone, 0.1, {{-std::sqrt(4 - 0.01), 10 + std::sqrt(9 - 0.01)}}, 1e-12);
    // Faceted circles: the hull of their vertices (a hexagon's corner on +x).
    const csg::Scene hexagons = compiled(
        "linear_extrude(1) hull() { circle(1, $fn = 6); translate([5, 0]) circle(1, $fn = 6); }");
    expectRow(hexagons, 0.0, {{-1, 6}}, 1e-12);
    expectSolidSpans(hexagons, {2.5, -5, 0.5}, {0, 1, 0},
                     {{5 - std::sqrt(0.75), 5 + std::sqrt(0.75)}}, 1e-12);
}

// Seeded random circles and squares: points against the hull of densely sampled points of
// their outlines (the sampled hull is inside the true one by a sagitta below 1e-7), with a
// point-in-convex-polygon test of its own.
TEST(Hull, RandomCirclesAgainstSampledHull) {
    csg::testing::Rng rng(1969);
    for (int layout = 0; layout < 4; ++layout) {
        std::string part = "linear_extrude(1) hull() {";
        std::vector<Vec2> samples;
        for (int k = 0; k < 5; ++k) {
            const double cx = rng.uniform(-8.0, 8.0);
            const double cy = rng.uniform(-8.0, 8.0);
            const double r = rng.uniform(0.2, 3.0);
            const bool square = rng.chance(0.3);
            // Print the numbers exactly (17 digits), so the oracle's shapes are the part's.
            char text[160];
            std::snprintf(text, sizeof text, " translate([%.17g, %.17g]) %s(%.17g%s);", cx, cy,
                          square ? "square" : "circle", square ? 2 * r : r,
                          square ? ", center = true" : "");
            part += text;
            if (square) {
                for (double sx : {-r, r})
                    for (double sy : {-r, r}) samples.push_back({cx + sx, cy + sy});
            } else {
                for (int i = 0; i < 20000; ++i) {
                    const double a = 2 * std::numbers::pi * i / 20000;
                    samples.push_back({cx + r * std::cos(a), cy + r * std::sin(a)});
                }
            }
        }
        part += " }";
        // Andrew's monotone chain over the samples.
        std::sort(samples.begin(), samples.end(),
                  [](Vec2 a, Vec2 b) { return a.x < b.x || (a.x == b.x && a.y < b.y); });
        auto turn = [](Vec2 o, Vec2 a, Vec2 b) {
            return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x);
        };
        std::vector<Vec2> hull;
        for (int pass = 0; pass < 2; ++pass) {
            const size_t base = hull.size();
            for (const Vec2& p : samples) {
                while (hull.size() >= base + 2 && turn(hull[hull.size() - 2], hull.back(), p) <= 0)
                    hull.pop_back();
                hull.push_back(p);
            }
            hull.pop_back();
            std::reverse(samples.begin(), samples.end());
        }
        const csg::Scene scene = compiled(part);
        int inside = 0;
        for (int i = 0; i < 2000; ++i) {
            const double x = rng.uniform(-12.0, 12.0);
            const double y = rng.uniform(-12.0, 12.0);
            const Vec2 p{x, y};
            bool in = true;
            double margin = csg::kInfinity;
            for (size_t k = 0; k < hull.size(); ++k) {
                const Vec2 a = hull[k], b = hull[(k + 1) % hull.size()];
                const double side = turn(a, b, p) / glm::length(b - a);
                in = in && side >= 0.0;
                margin = std::min(margin, segmentDistance(p, a, b));
            }
            if (margin < 1e-6) continue;
            inside += in;
            ASSERT_EQ(partContains(scene, p), in) << part << " at " << x << ", " << y;
        }
        EXPECT_GT(inside, 50) << part;
    }
}

// The hull of a 2-D difference is the hull of the result's vertices: square(10) with its top
// right quarter cut away has the pentagon (0,0), (10,0), (10,5), (5,10), (0,10) as its hull.
TEST(Hull, TwoDimensionalDifference) {
    const csg::Scene scene = compiled(
        "linear_extrude(1) hull() difference() { square(10); translate([5, 5]) square(10); }");
    expectRow(scene, 7.5, {{0, 7.5}}, 1e-12);
    expectRow(scene, 2.5, {{0, 10}}, 1e-12);
    // A half disc: the hull is the half disc itself (its chord and its arc).
    const csg::Scene half = compiled(
        "linear_extrude(1) hull() difference() { circle(10); translate([-20, -20]) square([40, "
        "20]); }");
    expectRow(half, 6.0, {{-8, 8}}, 1e-12);
    expectRow(half, -0.5, {}, 0.0);
}

// hull() of solids: the hull of their faceted vertices.
TEST(Hull, SolidsByHand) {
    const csg::Scene boxes = compiled("hull() { cube(1); translate([4, 0, 0]) cube(1); }");
    expectSolidSpans(boxes, {-5, 0.5, 0.5}, {1, 0, 0}, {{5, 10}}, 1e-12);
    // A cube and a sphere with $fn = 4: its rings at polar 45 and 135 degrees, of radius
    // c = cos 45 at heights 5 +- c, vertices on the axes' directions. The hull's face over the
    // cube's top edge x = 1, z = 1 runs to the vertex (c, 0, 5 + c): x = 1 - k (z - 1),
    // k = (1 - c) / (4 + c).
    const double c = std::sqrt(0.5), k = (1 - c) / (4 + c);
    const csg::Scene capsule =
        compiled("hull() { cube(2, center = true); translate([0, 0, 5]) sphere(1, $fn = 4); }");
    expectSolidSpans(capsule, {0, 0, -10}, {0, 0, 1}, {{9, 15 + c}}, 1e-12);
    const double x = 1 - 2 * k;  // at z = 3
    expectSolidSpans(capsule, {-10, 0, 3}, {1, 0, 0}, {{10 - x, 10 + x}}, 1e-12);
    // An exact sphere is hulled as OpenSCAD facets it: r = 1 has 5 fragments, so its equator
    // has a vertex at (1, 0, 0) and an edge at x = cos 144 deg on the other side.
    const csg::Scene spheres =
        compiled("hull() { sphere(1); translate([3, 0, 0]) sphere(1); }", io::CurveMode::Exact);
    expectSolidSpans(spheres, {-5, 0, 0}, {1, 0, 0},
                     {{5 + std::cos(144 * std::numbers::pi / 180), 9}}, 1e-12);
}

// A CSG result's vertices, not its leaves': a cube with a corner cube removed is hulled to the
// cube cut by the plane through (10,10,5), (10,5,10), (5,10,10); three slabs meet in a cube
// whose corner (10,10,10) is no leaf's vertex.
TEST(Hull, VerticesOfTheResult) {
    const csg::Scene cut =
        compiled("hull() difference() { cube(10); translate([5, 5, 5]) cube(10); }");
    expectSolidSpans(cut, {0, 0, 0}, {1, 1, 1}, {{0, 25.0 / 3.0}}, 1e-9);
    const csg::Scene slabs = compiled(
        "hull() intersection() { cube([10, 100, 100]); cube([100, 10, 100]); "
        "cube([100, 100, 10]); }");
    expectSolidSpans(slabs, {-5, -5, -5}, {1, 1, 1}, {{5, 15}}, 1e-9);
    expectSolidSpans(slabs, {-5, 5, 5}, {1, 0, 0}, {{5, 15}}, 1e-9);
}

TEST(OffsetHull, Diagnostics) {
    io::EvaluateResult r = evaluate("offset(1) cube(1);", io::CurveMode::Auto);
    ASSERT_TRUE(r.ok());
    EXPECT_NE(diagnosticsOf(r).find("part.scad:1:1: warning: offset(): its children are 3-D"),
              std::string::npos)
        << diagnosticsOf(r);
    r = evaluate(
        "cube();\nhull() surface(f = \"x*x + y*y + z*z - 1\", bbox = [[-1,-1,-1], [1,1,1]]);",
        io::CurveMode::Auto);
    EXPECT_FALSE(r.ok());
    EXPECT_NE(diagnosticsOf(r).find("part.scad:2:1: error: hull(): a surface has no vertices"),
              std::string::npos)
        << diagnosticsOf(r);
    r = evaluate("hull() polyhedron([[0,0,0],[1,0,0],[0,1,0],[1,1,0]], [[0,1,2],[1,3,2]]);",
                 io::CurveMode::Auto);
    EXPECT_NE(diagnosticsOf(r).find("hull(): the points span no volume"), std::string::npos)
        << diagnosticsOf(r);
}

// OpenSCAD 2021's own STL of faceted offsets and hulls lies on csgray's part, and the part on
// it, within Clipper's grid (2^-16 = 1.5e-5 per coordinate, twice for a transformed leaf).
TEST(OffsetHull, LiesOnOpenScadsMesh) {
    if (std::system("command -v openscad >/dev/null 2>&1") != 0)
        SKIP_OR_FAIL_IN_CI("openscad is not installed");
    std::vector<std::string> parts = {
        "linear_extrude(1) offset(r = 1) square(2);",
        "linear_extrude(1) offset(r = 1, $fn = 12) square(2);",
        "linear_extrude(1) offset(r = -2, $fn = 30) circle(5);",
        "linear_extrude(1) offset(delta = -1, chamfer = true) "
        "polygon([[0,0],[10,0],[10,10],[5,5],[0,10]]);",
        "linear_extrude(1) offset(r = -1, $fn = 16) difference() { square(10, center = true); "
        "circle(3); }",
        "linear_extrude(1) hull() { circle(2); translate([10, 0]) circle(3); }",
        "hull() { cylinder(r = 2, h = 3); translate([6, 0, 0]) sphere(2, $fn = 12); }",
        "hull() difference() { cube(10); translate([5, 5, 5]) cube(10); }",
        "hull() rotate_extrude($fn = 7) translate([5, 0]) square(1);",
    };
    const std::filesystem::path example = "/usr/share/openscad/examples/Advanced/offset.scad";
    if (std::filesystem::exists(example)) parts.push_back(cli::readFile(example));
    cli::ScratchDir dir;
    int index = 0;
    for (const std::string& text : parts) {
        const std::string part = (dir / ("part" + std::to_string(index) + ".scad")).string();
        const std::string stl = (dir / ("part" + std::to_string(index++) + ".stl")).string();
        cli::writeFile(part, text + "\n");
        const std::string command = "openscad --export-format binstl -o " + cli::shellQuote(stl) +
                                    " " + cli::shellQuote(part) + " >/dev/null 2>&1";
        ASSERT_EQ(std::system(command.c_str()), 0) << command;
        const cli::RunResult r =
            cli::runCsgray({"compare", part, stl, "--json", "--curves=openscad"}, dir.path());
        ASSERT_FALSE(r.out.empty()) << r.err;
        const nlohmann::json j = nlohmann::json::parse(r.out);
        EXPECT_LE(j["meshToSurface"]["max"].get<double>(), 3e-5) << text;
        EXPECT_LE(j["surfaceToMesh"]["max"].get<double>(), 3e-5) << text;
    }
}

}  // namespace
