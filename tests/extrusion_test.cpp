// OpenSCAD's 2-D shapes and their extrusions (primitives/Outline.h, primitives/Extrusion.h,
// io/Modules2D.cpp). The oracles are independent of the code under test:
//   - spans of rays derived by hand from the shapes' geometry;
//   - the torus primitive (its own quartic, primitives/Torus.h) for rotate_extrude of a circle;
//   - closed-form volumes: prism A h, frustum A h (1 + s + s^2) / 3, Pappus 2 pi R A;
//   - for random lines, point membership (inside(), a different code path from spans());
//   - OpenSCAD 2021's own STL of faceted extrusions (`openscad` on the PATH), through csgray's
//     compare command.
// Notation: t is the parameter of o + t d; rays along an axis have unit d.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include <nlohmann/json.hpp>

#include "CliRunner.h"
#include "MissingTool.h"
#include "csg/Scene.h"
#include "csg/Volume.h"
#include "io/Evaluate.h"
#include "tests/PartHelpers.h"
#include "tests/SeededRng.h"

namespace {

using csg::testing::compiled;
using csg::testing::diagnosticsOf;
using csg::testing::evaluate;
using csg::testing::expectSpans;
using csg::testing::Interval;
using csg::testing::spansOf;

using csg::Vec3;
constexpr double kPi = std::numbers::pi;

// linear_extrude(10) square(2) is the box [0,2]^2 x [0,10].
TEST(Extrusion, SquarePrismByHand) {
    const csg::Scene scene = compiled("linear_extrude(10) square(2);");
    expectSpans(scene, {1, 1, -5}, {0, 0, 1}, {{5, 15}}, 1e-14);
    expectSpans(scene, {-5, 1, 5}, {1, 0, 0}, {{5, 7}}, 1e-14);
    // Through the corner (0, 0) diagonally: x = y = t - 5 in [0, 2].
    expectSpans(scene, {-5, -5, 3}, {1, 1, 0}, {{5, 7}}, 1e-14);
    // Tangent to the side x = 2 (in its plane): no volume, so no span of positive length.
    for (const Interval& s : spansOf(scene, {2, -5, 5}, {0, 1, 0})) EXPECT_EQ(s.in, s.out);
    // center = true and OpenSCAD 2021's positional form: the first number is the height.
    expectSpans(compiled("linear_extrude(height = 4, center = true) square(2);"), {1, 1, -5},
                {0, 0, 1}, {{3, 7}}, 1e-14);
}

// A disc with a square hole: 2-D difference before the extrusion.
TEST(Extrusion, TwoDimensionalBooleansByHand) {
    const csg::Scene scene =
        compiled("linear_extrude(1) difference() { circle(2); square(2, center = true); }");
    // Along x at y = 0: the disc [-2, 2] minus the hole [-1, 1].
    expectSpans(scene, {-5, 0, 0.5}, {1, 0, 0}, {{3, 4}, {6, 7}}, 1e-14);
    // Along x at y = 1.5 (above the hole): the chord of the circle, +-sqrt(4 - 2.25).
    const double half = std::sqrt(4.0 - 2.25);
    expectSpans(scene, {-5, 1.5, 0.5}, {1, 0, 0}, {{5 - half, 5 + half}}, 1e-14);
    // Intersection and a transform in 2-D.
    const csg::Scene lens =
        compiled("linear_extrude(1) intersection() { circle(1); translate([1, 0]) circle(1); }");
    // Along y at x = 0.5: both circles give +-sqrt(1 - 0.25).
    const double h = std::sqrt(0.75);
    expectSpans(lens, {0.5, -5, 0.5}, {0, 1, 0}, {{5 - h, 5 + h}}, 1e-14);
}

// polygon(): even-odd over all paths, a hole by a nested path.
TEST(Extrusion, PolygonPathsEvenOdd) {
    const csg::Scene scene = compiled(
        "linear_extrude(1) polygon([[0,0],[10,0],[10,10],[0,10],[3,3],[7,3],[7,7],[3,7]],"
        " [[0,1,2,3],[4,5,6,7]]);");
    expectSpans(scene, {-1, 5, 0.5}, {1, 0, 0}, {{1, 4}, {8, 11}}, 1e-14);
    // The diagonal passes through four vertices, (0,0), (3,3), (7,7) and (10,10), crossing
    // the boundary at each: x = t - 1 in [0, 3] and [7, 10].
    expectSpans(scene, {-1, -1, 0.5}, {1, 1, 0}, {{1, 4}, {8, 11}}, 1e-14);
    // A pentagram's centre is empty under even-odd (OPENSCAD.md section 2).
    std::string star = "linear_extrude(1) polygon([";
    for (int k = 0; k < 5; ++k) {
        const double a = kPi / 2 + k * 4 * kPi / 5;
        star += (k ? "," : "") + std::string("[") + std::to_string(10 * std::cos(a)) + "," +
                std::to_string(10 * std::sin(a)) + "]";
    }
    star += "]);";
    const auto spans = spansOf(compiled(star), {0, 0, -5}, {0, 0, 1});
    EXPECT_TRUE(spans.empty());
}

// $fn makes circle() OpenSCAD's polygon: a hexagon with a vertex on +x.
TEST(Extrusion, FacetedCircleIsOpenScadsPolygon) {
    const csg::Scene hexagon = compiled("linear_extrude(1) circle(r = 1, $fn = 6);");
    expectSpans(hexagon, {-5, 0, 0.5}, {1, 0, 0}, {{4, 6}}, 1e-14);
    // Above the flat top (y = sin 60 = 0.866) the hexagon is missed; the round circle is not.
    EXPECT_TRUE(spansOf(hexagon, {-5, 0.9, 0.5}, {1, 0, 0}).empty());
    EXPECT_EQ(spansOf(compiled("linear_extrude(1) circle(1);"), {-5, 0.9, 0.5}, {1, 0, 0}).size(),
              1u);
}

// rotate_extrude of a circle of radius 1 at x = 2 is torus(2, 1): the same spans.
TEST(Extrusion, RevolvedCircleIsTheTorus) {
    const csg::Scene revolved = compiled("rotate_extrude() translate([2, 0]) circle(1);");
    const csg::Scene torus = compiled("torus(2, 1);");
    csg::testing::Rng rng(19);
    int compared = 0;
    for (int i = 0; i < 2000; ++i) {
        const Vec3 o(rng.uniform(-5, 5), rng.uniform(-5, 5), rng.uniform(-3, 3));
        Vec3 d(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1));
        if (i % 4 == 0) d.z = 0.0;          // level lines: r(t) turns back at its nearest point
        if (i % 7 == 0) d = Vec3(0, 0, 1);  // along the axis direction
        if (glm::length(d) < 0.1) continue;
        const auto a = spansOf(revolved, o, d), b = spansOf(torus, o, d);
        ASSERT_EQ(a.size(), b.size()) << "line " << i;
        for (size_t k = 0; k < a.size(); ++k) {
            EXPECT_NEAR(a[k].in, b[k].in, 1e-9) << "line " << i;
            EXPECT_NEAR(a[k].out, b[k].out, 1e-9) << "line " << i;
        }
        compared += int(a.size());
    }
    EXPECT_GT(compared, 500);
}

// rotate_extrude of a rectangle: a tube; with angle = 90 only the first quadrant.
TEST(Extrusion, RevolvedRectangleAndWedgeByHand) {
    const csg::Scene tube = compiled("rotate_extrude() translate([1, 0]) square([1, 2]);");
    // Along x at z = 1: |x| in [1, 2].
    expectSpans(tube, {-5, 0, 1}, {1, 0, 0}, {{3, 4}, {6, 7}}, 1e-14);
    // Along z at radius 1.5: z in [0, 2].
    expectSpans(tube, {1.5, 0, -5}, {0, 0, 1}, {{5, 7}}, 1e-14);
    // Along x at y = 1.2, z = 1: r^2 = x^2 + 1.44 in [1, 4], so |x| <= sqrt(2.56) = 1.6.
    expectSpans(tube, {-5, 1.2, 1}, {1, 0, 0}, {{3.4, 6.6}}, 1e-14);
    const csg::Scene quarter =
        compiled("rotate_extrude(angle = 90) translate([1, 0]) square([1, 2]);");
    expectSpans(quarter, {-5, 0.5, 1}, {1, 0, 0}, {{5 + std::sqrt(0.75), 5 + std::sqrt(3.75)}},
                1e-14);
    EXPECT_TRUE(spansOf(quarter, {-5, -0.5, 1}, {1, 0, 0}).empty());
    // angle = -90 sweeps clockwise: the fourth quadrant.
    const csg::Scene clockwise =
        compiled("rotate_extrude(angle = -90) translate([1, 0]) square([1, 2]);");
    EXPECT_TRUE(spansOf(clockwise, {-5, 0.5, 1}, {1, 0, 0}).empty());
    EXPECT_EQ(spansOf(clockwise, {-5, -0.5, 1}, {1, 0, 0}).size(), 1u);
    // A profile wholly in x <= 0 is mirrored into x >= 0 (OPENSCAD.md section 4).
    expectSpans(compiled("rotate_extrude() translate([-2, 0]) square([1, 2]);"), {-5, 0, 1},
                {1, 0, 0}, {{3, 4}, {6, 7}}, 1e-14);
}

// A profile on both sides of the axis is OpenSCAD's error (OPENSCAD.md section 4), judged on
// the profile, not on its leaves: a square across x = 0 with the x < 0 half cut away revolves
// into the cylinder of radius 5, and with the x > 0 half cut away into the same cylinder
// (mirrored), faceted or not.
TEST(Extrusion, RevolvedProfileMustKeepToOneSideOfTheAxis) {
    const io::EvaluateResult r = evaluate("rotate_extrude() translate([-1, 0]) square([3, 1]);");
    EXPECT_FALSE(r.ok());
    EXPECT_NE(diagnosticsOf(r).find("1:1: error: all points for rotate_extrude() must have the "
                                    "same X coordinate sign (range is -1.00 -> 2.00)"),
              std::string::npos)
        << diagnosticsOf(r);
    for (const char* fn : {"", "$fn = 64; "})
        for (const char* cut :
             {"translate([-6, -1]) square([6, 12])", "translate([0, -1]) square([6, 12])"}) {
            const std::string part = std::string(fn) +
                                     "rotate_extrude() difference() { translate([-5, 0]) "
                                     "square(10); " +
                                     cut + "; }";
            SCOPED_TRACE(part);
            // Along z at radius 2: z in [0, 10]; along x at z = 5: |x| <= 5 (the 64-gon's
            // apothem 5 cos(pi / 64) along x when faceted: its vertices are at +-5 on x).
            expectSpans(compiled(part), {2, 0, -5}, {0, 0, 1}, {{5, 15}}, 1e-12);
            expectSpans(compiled(part), {-10, 0, 5}, {1, 0, 0}, {{5, 15}}, 1e-12);
        }
}

// A profile of no height sweeps no volume, faceted or not: the empty solid, which a difference
// subtracts without effect (BOSL2's bottle_adapter_neck_to_neck revolves such a polygon with
// $fn = 8; the faceted revolution's bounding box was an error).
TEST(Extrusion, RevolvedFlatProfileIsEmpty) {
    for (const char* fn : {"", "$fn = 8; "}) {
        const std::string flat =
            std::string(fn) + "rotate_extrude() polygon([[0, 0], [10.7, 0], [10.7, 0], [0, 0]]);";
        const io::EvaluateResult r = evaluate(flat);
        ASSERT_TRUE(r.ok()) << fn << diagnosticsOf(r);
        EXPECT_EQ(r.model->root, nullptr) << fn;
        const csg::Scene cut =
            compiled(std::string(fn) + "difference() { cube(2, center = true); " +
                     "rotate_extrude() polygon([[0, 0], [3, 0], [3, 0]]); }");
        expectSpans(cut, {0, 0, -5}, {0, 0, 1}, {{4, 6}}, 1e-14);
    }
}

// scale = 0: a pyramid with its apex at (0, 0, 10); the section at height z is the square of
// side 2 (1 - z/10) about the axis.
TEST(Extrusion, ScaledToAnApexByHand) {
    const csg::Scene pyramid =
        compiled("linear_extrude(height = 10, scale = 0) square(2, center = true);");
    for (double z : {0.5, 2.0, 5.0, 9.0, 9.99}) {
        const double half = 1.0 - z / 10.0;
        expectSpans(pyramid, {-5, 0, z}, {1, 0, 0}, {{5 - half, 5 + half}}, 1e-13);
    }
    // Up the axis to the apex; at x = 0.5 up to the height where the half-side is 0.5.
    expectSpans(pyramid, {0, 0, -5}, {0, 0, 1}, {{5, 15}}, 1e-12);
    expectSpans(pyramid, {0.5, 0, -5}, {0, 0, 1}, {{5, 10}}, 1e-12);
    // A slanted line: from (-3, 0, 0) along (1, 0, 1): x = -3 + t, z = t; inside while
    // |x| <= 1 - z/10: enters where -3 + t = -(1 - t/10), t = 20/9, leaves where
    // -3 + t = 1 - t/10, t = 40/11.
    expectSpans(pyramid, {-3, 0, 0}, {1, 0, 1}, {{20.0 / 9, 40.0 / 11}}, 1e-13);
    // The side's normal: outward and up by the slope 1/10.
    const io::EvaluateResult r =
        evaluate("linear_extrude(height = 10, scale = 0) square(2, center = true);");
    csg::QueryContext ctx;
    const csg::Ray ray{{5, 0, 5}, {-1, 0, 0}, 0, csg::kInfinity};
    const auto spans = pyramid.spans(ray, ctx);
    ASSERT_EQ(spans.size(), 1u);
    const Vec3 n = pyramid.surface(ray, spans[0].in).normal;
    const Vec3 expected = glm::normalize(Vec3(1, 0, 0.1));
    for (int a = 0; a < 3; ++a) EXPECT_NEAR(n[a], expected[a], 1e-12);
}

// Volumes in closed form (the quadrature of csg::volume is the only error, ~1e-4 here).
TEST(Extrusion, VolumesInClosedForm) {
    struct Case {
        const char* part;
        double volume;
    };
    const double area = 4.0;  // square(2)
    const Case cases[] = {
        {"linear_extrude(3) square(2);", area * 3},
        {"linear_extrude(height = 3, scale = 0.5) square(2, center = true);",
         area * 3 * (1 + 0.5 + 0.25) / 3},
        {"linear_extrude(height = 3, scale = 2) square(2, center = true);",
         area * 3 * (1 + 2 + 4) / 3},
        {"linear_extrude(2) circle(1);", kPi * 2},
        // Pappus: 2 pi R A with R the profile's centroid radius.
        {"rotate_extrude() translate([2, 0]) circle(1);", 2 * kPi * 2 * kPi},
        {"rotate_extrude(angle = 90) translate([1, 0]) square([1, 2]);", 0.25 * 2 * kPi * 1.5 * 2},
    };
    for (const Case& c : cases) {
        const double v = csg::volume(compiled(c.part), 1024);
        EXPECT_NEAR(v, c.volume, 2e-3 * c.volume) << c.part;
    }
}

// Spans agree with point membership along random lines, for every kind of lift and outline
// segment (lines, arcs, and a union and difference of them).
TEST(Extrusion, SpansAgreeWithInsideOnRandomLines) {
    const char* parts[] = {
        "linear_extrude(2) difference() { circle(2); translate([0.5, 0]) square(1.5); }",
        "linear_extrude(height = 2, scale = 0.3) union() { circle(1); square(1.5); }",
        "rotate_extrude() translate([1, 0]) difference() { square([2, 2]); "
        "translate([1, 1]) circle(0.7); }",
        "rotate_extrude(angle = 250) translate([1, -1]) scale([1, 2]) circle(0.8);",
        // Level edges (discs swept by the profile's horizontal sides) and steep ones.
        "rotate_extrude() polygon([[0, 0], [2, 0], [2.5, 1], [2.5, 1.5], [1, 1.5], [1, 3], "
        "[0, 3]]);",
    };
    csg::testing::Rng rng(7);
    for (const char* part : parts) {
        const io::EvaluateResult r = evaluate(part);
        ASSERT_TRUE(r.ok()) << diagnosticsOf(r);
        const csg::Scene scene = csg::Scene::compile(r.model->root);
        int checked = 0;
        for (int i = 0; i < 300; ++i) {
            const Vec3 o(rng.uniform(-2, 2), rng.uniform(-2, 2), rng.uniform(-1, 2));
            const Vec3 d =
                glm::normalize(Vec3(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1)));
            const auto spans = spansOf(scene, o, d);
            for (const Interval& s : spans) {
                if (s.out - s.in < 1e-6) continue;
                EXPECT_TRUE(scene.inside(o + 0.5 * (s.in + s.out) * d)) << part << " line " << i;
                ++checked;
            }
            // Every point of the line is inside exactly when some span holds it (this finds
            // a span that was lost, which the midpoints above cannot).
            for (int k = 0; k < 40; ++k) {
                const double t = rng.uniform(-8, 8);
                bool inSpan = false, nearEnd = false;
                for (const Interval& s : spans) {
                    inSpan |= t >= s.in && t <= s.out;
                    nearEnd |= std::abs(t - s.in) < 1e-7 || std::abs(t - s.out) < 1e-7;
                }
                if (nearEnd) continue;
                EXPECT_EQ(scene.inside(o + t * d), inSpan) << part << " line " << i << " t " << t;
            }
        }
        EXPECT_GT(checked, 50) << part;
    }
}

// OpenSCAD's dimension rules: mixing warns and keeps the first child's dimension; a 2-D part
// is shown 1 unit thick; 3-D children of an extrusion are ignored with a warning.
TEST(Extrusion, DimensionRules) {
    io::EvaluateResult r = evaluate("union() { square(2); cube(1); }");
    ASSERT_TRUE(r.ok());
    EXPECT_NE(diagnosticsOf(r).find("Mixing 2D and 3D objects"), std::string::npos);
    EXPECT_TRUE(r.model->twoD);
    const csg::Scene flat = csg::Scene::compile(r.model->root);
    expectSpans(flat, {1, 1, -5}, {0, 0, 1}, {{4.5, 5.5}}, 1e-14);
    r = evaluate("linear_extrude(1) cube(1);");
    ASSERT_TRUE(r.ok());
    EXPECT_NE(diagnosticsOf(r).find("children are 3-D"), std::string::npos);
    EXPECT_FALSE(r.model->root);
    // A transform of a 2-D shape flattens it only when its x-y part does: scale([2, 2, 0])
    // doubles a square (OpenSCAD 2021 exports the 2 x 2 x 1 box), scale([2, 0]) drops it.
    expectSpans(compiled("linear_extrude(1) scale([2, 2, 0]) square(1);"), {-5, 1, 0.5}, {1, 0, 0},
                {{5, 7}}, 1e-14);
    r = evaluate("linear_extrude(1) scale([2, 0]) square(1);");
    ASSERT_TRUE(r.ok());
    EXPECT_NE(diagnosticsOf(r).find("no area and are dropped"), std::string::npos);
    EXPECT_FALSE(r.model->root);
    // A 3-D rotation of a 2-D shape uses only its x-y part (OPENSCAD.md section 2).
    const csg::Scene turned = compiled("linear_extrude(1) rotate([0, 0, 90]) square([2, 1]);");
    expectSpans(turned, {-5, 1, 0.5}, {1, 0, 0}, {{4, 5}}, 1e-14);
}

// With $fn (or --curves openscad) rotate_extrude is OpenSCAD's faceted solid, sector by
// sector: OpenSCAD 2021's STL lies on csgray's part, and the part on it, to rounding. Rounding
// here: CGAL's 2^-20 snapping and float STL coordinates (~1e-6 at these sizes); a profile that
// went through a 2-D boolean is snapped to Clipper's 2^-16 grid (1.5e-5 per coordinate).
TEST(Extrusion, FacetedRevolutionLiesOnOpenScadsMesh) {
    if (std::system("command -v openscad >/dev/null 2>&1") != 0)
        SKIP_OR_FAIL_IN_CI("openscad is not installed");
    struct Case {
        const char* part;
        double tolerance;
    };
    const Case cases[] = {
        {"rotate_extrude($fn = 8) translate([2, 0]) square([1, 2]);", 2e-6},
        {"rotate_extrude(angle = 100, $fn = 12) translate([3, 0]) square([1, 2]);", 2e-6},
        {"rotate_extrude(angle = 100, $fn = 12) translate([-3, 0]) square([1, 2]);", 2e-6},
        {"rotate_extrude(angle = -70, $fn = 30) translate([2, 1]) circle(1, $fn = 5);", 2e-6},
        {"rotate_extrude($fn = 12) translate([-3, 0]) difference() { square([1, 2]); "
         "translate([0.5, 1]) circle(0.3, $fn = 7); }",
         3e-5},
    };
    cli::ScratchDir dir;
    int index = 0;
    for (const Case& c : cases) {
        const std::string part = (dir / ("part" + std::to_string(index) + ".scad")).string();
        const std::string stl = (dir / ("part" + std::to_string(index++) + ".stl")).string();
        cli::writeFile(part, std::string(c.part) + "\n");
        const std::string command = "openscad --export-format binstl -o " + cli::shellQuote(stl) +
                                    " " + cli::shellQuote(part) + " >/dev/null 2>&1";
        ASSERT_EQ(std::system(command.c_str()), 0) << command;
        const cli::RunResult r = cli::runCsgray({"compare", part, stl, "--json"}, dir.path());
        ASSERT_FALSE(r.out.empty()) << r.err;
        const nlohmann::json j = nlohmann::json::parse(r.out);
        EXPECT_LE(j["meshToSurface"]["max"].get<double>(), c.tolerance) << c.part;
        EXPECT_LE(j["surfaceToMesh"]["max"].get<double>(), c.tolerance) << c.part;
    }
}

// A faceted revolution is one polyhedron when its profile is straight lines, and sector wedges
// (box, half-spaces and the profile's prism) when it keeps an exact arc; either way the colour
// of the profile is the solid's, on its flat top too, which lies in the wedges' boxes' faces
// (the merge named the box there, and the top took the default colour).
TEST(Extrusion, AFacetedRevolutionIsTheProfilesColourAllOver) {
    const char* const parts[] = {
        "color(\"red\") rotate_extrude($fn = 12) translate([3, 0]) square(2);",
        "color(\"red\") rotate_extrude($fn = 12) translate([3, 0]) "
        "difference() { square(2); translate([1, 1]) circle(0.5, $fn = 0); }",
    };
    const char* const leaves[] = {"polyhedron", "halfspace"};
    for (int i = 0; i < 2; ++i) {
        const io::EvaluateResult r = evaluate(parts[i]);
        ASSERT_TRUE(r.ok()) << diagnosticsOf(r);
        const csg::Scene scene = csg::Scene::compile(r.model->root);
        bool found = false;
        for (uint32_t leaf = 0; leaf < scene.leafCount(); ++leaf)
            found = found || std::string(std::visit([](const auto& p) { return p.kName; },
                                                    scene.leafPrimitive(leaf))) == leaves[i];
        EXPECT_TRUE(found) << parts[i] << " has no " << leaves[i];
        csg::QueryContext ctx;
        // Down onto the top at radius 4, across the side at height 0.5.
        for (const csg::Ray& ray : {csg::Ray{{0.3, 4.0, 10.0}, {0, 0, -1}, 0.0, 100.0},
                                    csg::Ray{{0.3, -10.0, 0.5}, {0, 1, 0}, 0.0, 100.0}}) {
            const std::optional<csg::Hit> hit = scene.closest(ray, ctx);
            ASSERT_TRUE(hit) << parts[i];
            const auto& m = r.model->materials.at(scene.leafTags(hit->leaf).material);
            EXPECT_EQ(m.color, csg::Vec4(1, 0, 0, 1)) << parts[i] << " at t = " << hit->t;
        }
    }
}

// A 2-D part on the command line: info says so, render shows it, export and compare refuse it
// with OpenSCAD's message and write nothing.
TEST(Extrusion, TwoDimensionalPartOnTheCommandLine) {
    cli::ScratchDir dir;
    const std::string part = (dir / "flat.scad").string(), glb = (dir / "flat.glb").string();
    cli::writeFile(part, "difference() { circle(10); square(8, center = true); }\n");
    const cli::RunResult info = cli::runCsgray({"info", part}, dir.path());
    ASSERT_EQ(info.exitCode, 0) << info.err;
    EXPECT_EQ(nlohmann::json::parse(info.out)["dimensions"].get<int>(), 2);
    const cli::RunResult exported = cli::runCsgray({"export", part, "-o", glb}, dir.path());
    EXPECT_EQ(exported.exitCode, 1);
    EXPECT_NE(exported.err.find("not a 3-D object"), std::string::npos) << exported.err;
    EXPECT_FALSE(std::filesystem::exists(glb));
    const cli::RunResult solid =
        cli::runCsgray({"info", cli::samplePath("vase.scad").string()}, dir.path());
    ASSERT_EQ(solid.exitCode, 0) << solid.err;
    EXPECT_EQ(nlohmann::json::parse(solid.out)["dimensions"].get<int>(), 3);
}

}  // namespace
