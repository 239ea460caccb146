// minkowski() (io/Minkowski.cpp, csg/derived/Minkowski3D.h, csg/derived/Clipper2D.h): boxes
// summed by hand, the exact rounded box against its closed-form volume and its corner ball, a
// non-convex operand (a frame) summed with a box and with a ball, two non-convex operands by
// hand, OpenSCAD 2021's own sums of faceted solids and polygons against csgray's, the size
// csgray refuses with its reason; 2-D
// shapes rounded by an exact circle and summed as Clipper sums them, by hand.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <random>

#include "MissingTool.h"
#include "PartHelpers.h"
#include "TempDir.h"
#include "TextFiles.h"
#include "csg/Volume.h"

namespace {

using csg::Vec3;
using csg::testing::compiled;
using csg::testing::diagnosticsOf;
using csg::testing::evaluate;
using csg::testing::expectRow;
using csg::testing::expectSpans;

constexpr double kPi = std::numbers::pi;

TEST(Minkowski, BoxesAddTheirSides) {
    const csg::Scene scene = compiled("minkowski() { cube([2, 3, 4]); cube(1); }");
    expectSpans(scene, {0.5, 0.5, -10}, {0, 0, 1}, {{10, 15}}, 1e-12);
    expectSpans(scene, {-10, 1, 1}, {1, 0, 0}, {{10, 13}}, 1e-12);
    expectSpans(scene, {1, -10, 1}, {0, 1, 0}, {{10, 14}}, 1e-12);
    // Three children fold left to right; an empty child is skipped; one child is itself.
    const csg::Scene three = compiled(
        "minkowski() { cube(1); cube(1); difference() { cube(1); cube(3, center = true); } "
        "cube(2); }");
    expectSpans(three, {0.5, 0.5, -10}, {0, 0, 1}, {{10, 14}}, 1e-12);
    expectSpans(compiled("minkowski() cube(2);"), {1, 1, -10}, {0, 0, 1}, {{10, 12}}, 0.0);
}

TEST(Minkowski, ConvexPolyhedraAreSummedWhole) {
    // The octahedron |x| + |y| + |z| <= 1 as a polyhedron, plus itself: the octahedron of
    // radius 2 (one hull: a convex mesh is a convex piece, not a non-convex part).
    const std::string octahedron =
        "polyhedron([[1,0,0],[-1,0,0],[0,1,0],[0,-1,0],[0,0,1],[0,0,-1]], "
        "[[0,2,4],[2,1,4],[1,3,4],[3,0,4],[2,0,5],[1,2,5],[3,1,5],[0,3,5]]);";
    const csg::Scene scene = compiled("minkowski() { " + octahedron + octahedron + " }");
    EXPECT_EQ(scene.leafCount(), 1u);
    expectSpans(scene, {-5, 0, 0}, {1, 0, 0}, {{3, 7}}, 1e-12);
    expectSpans(scene, {-5, 0.5, 0.5}, {1, 0, 0}, {{4, 6}}, 1e-12);
}

TEST(Minkowski, ExactBallRoundsABoxWithNoFacets) {
    // The box [-1, 1]^3 rounded by a ball of radius 1 (no $fn: the ball stays exact).
    const csg::Scene scene = compiled("minkowski() { cube(2, center = true); sphere(1); }");
    // The box, a prism on each of its 6 faces (one per face: no seam across a face), a
    // cylinder on each of its 12 edges, a ball at each of its 8 corners.
    EXPECT_EQ(scene.leafCount(), 1u + 6u + 12u + 8u);
    // Along a diagonal the surface is the corner ball's: at sqrt(3) + 1 from the centre.
    const Vec3 d = glm::normalize(Vec3(1, 1, 1));
    const double reach = std::sqrt(3.0) + 1.0;
    expectSpans(scene, Vec3(0.0), d, {{-reach, reach}}, 1e-12);
    // Across an edge (x = y = 1 + cos 45, z = 0) the surface is the edge cylinder's.
    const Vec3 e = glm::normalize(Vec3(1, 1, 0));
    expectSpans(scene, Vec3(0.0), e, {{-(std::sqrt(2.0) + 1), std::sqrt(2.0) + 1}}, 1e-12);
    // Through a face: the prism's, at 2.
    expectSpans(scene, Vec3(0.3, 0.2, -5), {0, 0, 1}, {{3, 7}}, 1e-12);
    // Its volume: the box, six slabs, twelve quarter cylinders, eight eighth balls.
    const double a = 2.0, r = 1.0;
    const double exact =
        a * a * a + 6 * a * a * r + 3 * kPi * r * r * a + 4.0 / 3.0 * kPi * r * r * r;
    EXPECT_NEAR(csg::volume(scene, 1024), exact, 2e-4 * exact);
}

// A ray that enters the rounded box through a face a hair from an edge meets the face's prism
// there and the edge cylinder below it a little later (the cylinder sags by delta^2 / 2r at
// delta from the edge: 2.5e-9 at delta = 1e-4). The first hit is the face, at the t the ray
// was built with, with the face's normal: closest() clipped the prism's span at the
// cylinder's entry once it had seen the cylinder, dropped it as a sliver, and returned the
// cylinder's point, inside the prism, whose shadow ray then started inside the solid (the
// rendered box's dark specks).
TEST(Minkowski, RayEntersAFaceNotTheEdgeCylinderBelowIt) {
    const csg::Scene scene =
        compiled("minkowski() { cube([20, 10, 5], center = true); sphere(2); }");
    csg::QueryContext ctx;
    const Vec3 d = glm::normalize(Vec3(-0.388, 0.775, -0.499));  // the render's view of it
    constexpr double kT = 31.4;
    for (double delta : {1e-5, 3e-5, 1e-4, 3e-4, 1e-3})
        for (double x : {-6.5, -1.0, 3.25, 6.159}) {
            // The top face z = 4.5, delta inside its edge y = -5 (over the cylinder of that edge).
            const Vec3 p(x, -5.0 + delta, 4.5);
            const csg::Ray ray{p - kT * d, d, 0.0, csg::kInfinity};
            const std::optional<csg::Hit> hit = scene.closest(ray, ctx);
            ASSERT_TRUE(hit) << "delta " << delta << " x " << x;
            EXPECT_NEAR(hit->t, kT, 1e-12 * kT) << "delta " << delta << " x " << x;
            const csg::SurfacePoint s = scene.surface(ray, *hit);
            EXPECT_NEAR(s.normal.z, 1.0, 1e-12) << "delta " << delta << " x " << x;
        }
}

TEST(Minkowski, NonConvexFrameWithABoxAndWithABall) {
    // A 4 x 4 x 4 block with a 2 x 2 hole along z, summed with a 0.5 cube: the block grows to
    // 4.5 and the hole shrinks to 1.5 (from x = 1.5 to 3).
    const std::string frame = "difference() { cube(4); translate([1, 1, -1]) cube([2, 2, 6]); }";
    const csg::Scene boxed = compiled("minkowski() { " + frame + " cube(0.5); }");
    expectSpans(boxed, {2.25, 2.25, -5}, {0, 0, 1}, {}, 0.0);
    expectSpans(boxed, {1.4, 2.25, -5}, {0, 0, 1}, {{5, 9.5}}, 1e-12);
    expectSpans(boxed, {-5, 2.25, 2}, {1, 0, 0}, {{5, 6.5}, {8, 9.5}}, 1e-12);
    // 900 x 900 lines over [0, 4.5]^2: every edge of the silhouette lies between cells, so
    // the quadrature is exact.
    EXPECT_NEAR(csg::volume(boxed, 900), 4.5 * 4.5 * 4.5 - 1.5 * 1.5 * 4.5, 1e-9);
    // The same frame rounded by a ball of radius 0.5: the hole's walls move in by 0.5 and its
    // edges stay sharp (they are concave); the outside rounds.
    const csg::Scene rounded = compiled("minkowski() { " + frame + " sphere(0.5); }");
    expectSpans(rounded, {2, 2, -5}, {0, 0, 1}, {}, 0.0);
    // At x = 1.45 the line passes 0.45 beyond the hole's top and bottom edges (x = 1), whose
    // cylinders of radius 0.5 reach sqrt(0.5^2 - 0.45^2) past z = 0 and z = 4.
    const double past = std::sqrt(0.5 * 0.5 - 0.45 * 0.45);
    expectSpans(rounded, {1.45, 2, -5}, {0, 0, 1}, {{5 - past, 9 + past}}, 1e-12);
    expectSpans(rounded, {-5, 2, 2}, {1, 0, 0}, {{4.5, 6.5}, {7.5, 9.5}}, 1e-12);
    // The outer corner (4, 4, 4) is rounded by the corner ball.
    const Vec3 d = glm::normalize(Vec3(1, 1, 1));
    const auto spans = csg::testing::spansOf(rounded, Vec3(4.0) - 2.0 * d, d);
    ASSERT_FALSE(spans.empty());
    EXPECT_NEAR(spans.back().out, 2.5, 1e-12);
}

TEST(Minkowski, FacetedSumsAreOpenScadsPolyhedra) {
    // With $fn the curves are OpenSCAD's polyhedra (polygons), and so is their sum. OpenSCAD 2021's
    // own mesh of each part, imported, must give the same spans on lines in general position (its
    // STL has 6 significant digits: ends agree to 1e-4 on these 5-unit parts).
    if (std::system("openscad --version >/dev/null 2>&1") != 0)
        SKIP_OR_FAIL_IN_CI("openscad (2021.01, Debian's) is not installed");
    const std::string parts[] = {
        "minkowski() { cube([3, 2, 1]); sphere(1, $fn = 8); }",
        "minkowski() { cylinder(r = 2, h = 1, $fn = 6); rotate([30, 20, 10]) cube(1); }",
        "minkowski() { difference() { cube(4); translate([1, 1, -1]) cube([2, 2, 6]); } "
        "cylinder(r = 0.5, h = 0.5, $fn = 8); }",
        // Two non-convex operands: OpenSCAD decomposes both into convex pieces (CGAL).
        "minkowski() { difference() { cube(4); translate([1, 1, -1]) cube([2, 2, 6]); } "
        "rotate([10, 20, 30]) difference() { cube([1, 1, 0.5]); translate([0.5, 0.5, -1]) "
        "cube(2); } }",
        // 2-D: Clipper's sums, on its grid, extruded.
        "linear_extrude(1) minkowski() { square([3, 2]); circle(1, $fn = 8); }",
        "linear_extrude(1) minkowski() { polygon([[0,0],[4,0],[4,1],[1,1],[1,4],[0,4]]); "
        "rotate(10) circle(0.5, $fn = 6); }",
    };
    csg::testing::TempDir dir("csgray_minkowski");
    std::mt19937 random(11);
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    for (const std::string& part : parts) {
        SCOPED_TRACE(part);
        const std::filesystem::path scad = dir.path / "part.scad", stl = dir.path / "part.stl";
        csg::testing::writeFile(scad, part + "\n");
        const std::string command =
            "openscad -o '" + stl.string() + "' '" + scad.string() + "' >/dev/null 2>&1";
        ASSERT_EQ(std::system(command.c_str()), 0) << command;
        const csg::Scene ours = compiled(part);
        const csg::Scene theirs = compiled("import(\"" + stl.string() + "\");");
        const csg::Bounds3 box = ours.bounds();
        const Vec3 middle = 0.5 * (box.lo + box.hi), half = 0.5 * (box.hi - box.lo);
        int compared = 0;
        for (int i = 0; i < 200; ++i) {
            const Vec3 o = middle + half * Vec3(unit(random), unit(random), unit(random));
            const Vec3 d = glm::normalize(Vec3(unit(random), unit(random), unit(random)));
            const auto expected = csg::testing::spansOf(theirs, o, d, true);
            std::vector<csg::testing::Interval> spans = csg::testing::spansOf(ours, o, d, true);
            ASSERT_EQ(spans.size(), expected.size()) << "line " << i;
            for (size_t k = 0; k < spans.size(); ++k) {
                EXPECT_NEAR(spans[k].in, expected[k].in, 1e-4) << "line " << i;
                EXPECT_NEAR(spans[k].out, expected[k].out, 1e-4) << "line " << i;
            }
            compared += !spans.empty();
        }
        EXPECT_GT(compared, 50);  // most lines cross the part
    }
}

// Two non-convex solids: an L (three unit squares, [0, 2]^2 without its (1, 2]^2 corner, one
// high) summed with itself. Minkowski sums distribute over unions, so the sum is the union of
// the six 2 x 2 squares at offsets (0, 0), (1, 0), (0, 1), (2, 0), (1, 1), (0, 2), two high:
// x in [0, 4] for y in [0, 2], [0, 3] for y in [2, 3], [0, 2] for y in [3, 4]; area 8 + 3 + 2.
TEST(Minkowski, TwoNonConvexSolidsByHand) {
    const std::string l = "difference() { cube([2, 2, 1]); translate([1, 1, -1]) cube(3); }";
    const csg::Scene sum = compiled("minkowski() { " + l + " " + l + " }");
    expectSpans(sum, {-5, 0.5, 1}, {1, 0, 0}, {{5, 9}}, 1e-12);
    expectSpans(sum, {-5, 2.5, 1}, {1, 0, 0}, {{5, 8}}, 1e-12);
    expectSpans(sum, {-5, 3.5, 1}, {1, 0, 0}, {{5, 7}}, 1e-12);
    expectSpans(sum, {2.5, 2.5, -5}, {0, 0, 1}, {{5, 7}}, 1e-12);
    expectSpans(sum, {3.5, 2.5, -5}, {0, 0, 1}, {}, 0.0);
    expectSpans(sum, {3.5, 3.5, -5}, {0, 0, 1}, {}, 0.0);
    // 400 x 400 lines over [0, 4]^2: the edges at whole coordinates lie between cells.
    EXPECT_NEAR(csg::volume(sum, 400), 13.0 * 2.0, 1e-9);

    // A thick frame (walls 2 wide) and a small L (0.5 wide, 0.25 high): deep in the wall the
    // sum holds points that no pair of boundary triangles reaches (x - Q lies inside the
    // frame), only the frame moved by a point of the L. Along z at (1.1, 1.1): the wall's
    // [0, 6] grown by the L's 0.25.
    const std::string frame = "difference() { cube(6); translate([2, 2, -1]) cube([2, 2, 8]); }";
    const std::string small =
        "difference() { cube([0.5, 0.5, 0.25]); translate([0.25, 0.25, -1]) cube(3); }";
    const csg::Scene thick = compiled("minkowski() { " + frame + " " + small + " }");
    expectSpans(thick, {1.1, 1.1, -5}, {0, 0, 1}, {{5, 11.25}}, 1e-12);
    // Through the hole, which the L narrows by its 0.5 on the low sides only.
    expectSpans(thick, {-5, 3, 3}, {1, 0, 0}, {{5, 7.5}, {9, 11.5}}, 1e-12);
}

TEST(Minkowski, RefusesTooManyTrianglePairsWithTheReason) {
    // Two hollow faceted spheres: boundaries of 2 x 64 x 31 x 2 triangles and more each, some
    // 6.3e7 pairs, past the 2^20 csgray sums.
    const std::string shell = "difference() { sphere(5, $fn = 64); sphere(4, $fn = 64); }";
    const auto r = evaluate("minkowski() { " + shell + " " + shell + " }");
    EXPECT_FALSE(r.ok());
    EXPECT_NE(diagnosticsOf(r).find("part.scad:1:1: error: minkowski(): two non-convex operands "
                                    "whose boundaries have"),
              std::string::npos)
        << diagnosticsOf(r);
}

TEST(Minkowski2D, ExactCircleRoundsAShape) {
    // square(2) plus the circle of radius 1 about (5, 0): the square grown by 1 with round
    // corners, moved by 5 in x. Above the top edge (2 < y < 3) the corner circles give
    // x in [5 - h, 7 + h], h = sqrt(1 - (y - 2)^2).
    const csg::Scene scene =
        compiled("linear_extrude(1) minkowski() { square(2); translate([5, 0]) circle(1); }");
    expectRow(scene, 1.0, {{4, 8}}, 1e-12);
    for (double y : {2.25, 2.5, 2.9}) {
        const double h = std::sqrt(1.0 - (y - 2) * (y - 2));
        expectRow(scene, y, {{5 - h, 7 + h}}, 1e-12);
    }
    expectRow(scene, 3.001, {}, 0.0);
    // Two circles make one of the summed radius about the summed centre.
    const csg::Scene two = compiled(
        "linear_extrude(1) minkowski() { translate([1, 0]) circle(1); circle(2, $fn = 0); }");
    expectRow(two, 0.0, {{-2, 4}}, 1e-12);
    expectRow(two, 2.0, {{1 - std::sqrt(5.0), 1 + std::sqrt(5.0)}}, 1e-12);
}

TEST(Minkowski2D, PolygonsAddAsOpenScadsClipperSum) {
    // square(2) plus a square(1) turned 45 degrees about the origin (a diamond of half
    // diagonal sqrt(2)/2): an octagon; across the middle it spans x in [-s, 2 + s].
    const double s = std::sqrt(0.5);
    const csg::Scene scene = compiled(
        "linear_extrude(1) minkowski() { square(2); rotate(45) translate([-0.5, -0.5]) "
        "square(1); }");
    // On Clipper's 2^-16 grid (points truncated onto it).
    expectRow(scene, 1.0, {{-s, 2 + s}}, 2.0 / 65536);
    expectRow(scene, 2.0 + s - 0.1, {{-0.1, 2.1}}, 2.0 / 65536);  // the 45-degree sides
    // An L (non-convex) plus a small square: the notch fills only where the square reaches.
    const csg::Scene el = compiled(
        "linear_extrude(1) minkowski() { polygon([[0,0],[4,0],[4,1],[1,1],[1,4],[0,4]]); "
        "square(0.5); }");
    expectRow(el, 1.25, {{0, 4.5}}, 1e-12);
    expectRow(el, 1.75, {{0, 1.5}}, 1e-12);
    expectRow(el, 4.25, {{0, 1.5}}, 1e-12);
}

}  // namespace
