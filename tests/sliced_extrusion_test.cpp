// OpenSCAD 2021's sliced linear_extrude, which --curves openscad builds for a twisted or
// unevenly scaled extrusion (io/ExtrusionMesh.h slicedExtrusionMesh, io/Faceting.h
// extrudeSlices):
//   (a) slice counts worked out by hand from OPENSCAD.md section 3's formulas;
//   (b) the triangles of small parts counted by hand, and what the other modes keep;
//   (c) Debian's openscad as the oracle: the same slices, the same side triangles (vertex for
//       vertex) and the same volume as its binary STL.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <set>
#include <string>
#include <vector>

#include "BinaryStl.h"
#include "MissingTool.h"
#include "PartHelpers.h"
#include "TempDir.h"
#include "TextFiles.h"
#include "io/Faceting.h"
#include "primitives/Polyhedron.h"

namespace csg {
namespace {

using io::CurveMode;
using io::extrudeSlices;
using io::FragmentSettings;
using testing::diagnosticsOf;
using testing::evaluate;

// ---- (a) the slice count ----

// OpenSCAD's defaults $fn = 0, $fa = 12, $fs = 2 unless a case says otherwise.
TEST(ExtrudeSlices, HelixByHand) {
    // square([2, 1]) at x in [1, 3]: rmax^2 = 3^2 + 1^2 = 10. Twist 90 over 10: 90 / 12 -> 8 by
    // angle; the helix (pi/2) sqrt(10 + (10 / (pi/2))^2) = 11.17 long, 11.17 / 2 -> 6 by length.
    EXPECT_EQ(extrudeSlices(10, 0, 10, 90, Vec2(1), {}), 6);
    EXPECT_EQ(extrudeSlices(10, 0, 10, -90, Vec2(1), {}), 6);  // |twist|
    // $fn decides: ceil(360 / 360 * 12); ceil(30 / 360 * 30) = ceil(2.5).
    EXPECT_EQ(extrudeSlices(16, 0, 10, 360, Vec2(1), {12, 12, 2}), 12);
    EXPECT_EQ(extrudeSlices(16, 0, 10, 30, Vec2(1), {30, 12, 2}), 3);
    // At least 3 slices a turn: 700 / 120 -> 6 beats ceil(700 / 360 * 1) = 2.
    EXPECT_EQ(extrudeSlices(16, 0, 10, 700, Vec2(1), {1, 12, 2}), 6);
    // A profile within GRID_FINE of the axis gets that least count, whatever $fn says.
    EXPECT_EQ(extrudeSlices(1e-14, 0, 10, 90, Vec2(1), {64, 12, 2}), 1);
    // Two unequal scales with a twist: OpenSCAD 2021 counts the plain helix.
    EXPECT_EQ(extrudeSlices(10, 1, 10, 90, Vec2(1, 2), {}), 6);
}

TEST(ExtrudeSlices, ConicalHelixByHand) {
    // The same square, twist 200 and scale 0.5: the plan of a vertex is the Archimedean spiral
    // r = a theta from theta = 3.4907 (200 degrees) to 6.9813 (its end where the scale would
    // reach 0), a = sqrt(10) / 6.9813 = 0.45297; its length 11.750 - 3.3153 = 8.4345, with the
    // height sqrt(8.4345^2 + 10^2) = 13.08: 7 slices by length (17 by angle, at least 2).
    EXPECT_EQ(extrudeSlices(10, 0, 10, 200, Vec2(0.5), {}), 7);
    EXPECT_EQ(extrudeSlices(10, 0, 10, -200, Vec2(0.5), {}), 7);
    // Scale 0 twist 90: the spiral from 0 to pi/2 with a = sqrt(10) / (pi/2) = 2.0132 is 4.186
    // long; sqrt(4.186^2 + 100) = 10.84: 6 slices (8 by angle).
    EXPECT_EQ(extrudeSlices(10, 0, 10, 90, Vec2(0), {}), 6);
    // $fn: ceil(200 * 20 / 360) = 12.
    EXPECT_EQ(extrudeSlices(10, 0, 10, 200, Vec2(0.5), {20, 12, 2}), 12);
}

TEST(ExtrudeSlices, DiagonalByHand) {
    // square(10), scale [1, 2], height 10: the corner (10, 10) moves by 10, the longest
    // diagonal path sqrt(10^2 + 10^2) = 14.14: 8 slices of $fs = 2 (OPENSCAD.md's check).
    EXPECT_EQ(extrudeSlices(200, 100, 10, 0, Vec2(1, 2), {}), 8);
    EXPECT_EQ(extrudeSlices(200, 100, 10, 0, Vec2(1, 2), {7.9, 12, 2}), 7);   // trunc($fn)
    EXPECT_EQ(extrudeSlices(200, 100, 10, 0, Vec2(1, 2), {0, 12, 0.3}), 48);  // 14.14 / 0.3
    // No twist and one scale: the frustum is one slice.
    EXPECT_EQ(extrudeSlices(200, 0, 10, 0, Vec2(0.5), {}), 1);
}

TEST(ExtrudeSlices, DegenerateSettingsSaturateInsteadOfOverflowing) {
    // $fa = 0 divides by zero in OpenSCAD (an undefined int conversion); here the count by
    // angle saturates and the count by length decides.
    EXPECT_EQ(extrudeSlices(10, 0, 10, 90, Vec2(1), {0, 0, 2}), 6);
    // Both 0: the saturated count, which the module refuses by its size.
    EXPECT_EQ(extrudeSlices(10, 0, 10, 90, Vec2(1), {0, 0, 0}),
              std::numeric_limits<int32_t>::max());
    EXPECT_EQ(extrudeSlices(10, 0, 10, 90, Vec2(1), {1e300, 12, 2}),
              std::numeric_limits<int32_t>::max());
}

// ---- (b) the mesh, by hand ----

// The one polyhedron a part of one extrusion becomes under --curves openscad.
const Polyhedron* onlyPolyhedron(const io::EvaluateResult& r) {
    if (!r.ok() || !r.model->root || r.model->root->op != Op::Leaf) return nullptr;
    return std::get_if<Polyhedron>(&r.model->root->primitive);
}

TEST(SlicedExtrusion, TrianglesByHand) {
    struct Case {
        const char* scad;
        size_t triangles, vertices;
    };
    const Case cases[] = {
        // 6 slices (above) of 4 edges, 2 triangles each, and two caps of 2: 52; 7 layers of 4.
        {"linear_extrude(10, twist = 90) translate([1, 0]) square([2, 1]);", 52, 28},
        // Scale 0: the last slice has one triangle an edge (the other has no area) and there
        // is no top: 2 + 5 * 8 + 4 = 46, the apex one vertex: 6 * 4 + 1.
        {"linear_extrude(10, twist = 90, scale = 0) translate([1, 0]) square([2, 1]);", 46, 25},
        // slices = 3.7 is 3 (its integer part): 3 * 8 + 4 = 28.
        {"linear_extrude(10, twist = 90, slices = 3.7) square([2, 1]);", 28, 16},
        // A square with a square hole, 8 slices given: (4 + 4) edges * 2 * 8 = 128 sides and
        // caps of 8 triangles each (a ring of 8 corners).
        {"linear_extrude(5, twist = 45, slices = 8) difference() { square(6, center = true); "
         "square(2, center = true); }",
         144, 72},
    };
    for (const Case& c : cases) {
        const io::EvaluateResult r = evaluate(c.scad, CurveMode::OpenScad);
        ASSERT_TRUE(r.ok()) << diagnosticsOf(r);
        EXPECT_TRUE(r.diagnostics.empty()) << diagnosticsOf(r);
        const Polyhedron* mesh = onlyPolyhedron(r);
        ASSERT_NE(mesh, nullptr) << c.scad << " did not become one polyhedron";
        EXPECT_EQ(mesh->triangleCount(), c.triangles) << c.scad;
        EXPECT_EQ(mesh->data->vertices.size(), c.vertices) << c.scad;
        EXPECT_TRUE(mesh->edges().manifold()) << c.scad;
    }
}

TEST(SlicedExtrusion, OtherModesKeepTheExactSolid) {
    const std::string scad = "linear_extrude(10, twist = 90, $fn = 8) square([2, 1]);";
    for (CurveMode mode : {CurveMode::Auto, CurveMode::Exact}) {
        const io::EvaluateResult r = evaluate(scad, mode);
        ASSERT_TRUE(r.ok()) << diagnosticsOf(r);
        ASSERT_EQ(r.model->root->op, Op::Leaf);
        EXPECT_TRUE(std::holds_alternative<Extrusion>(r.model->root->primitive))
            << io::curveModeName(mode);
    }
}

TEST(SlicedExtrusion, TooManySlicesIsAnErrorAtTheCall) {
    const io::EvaluateResult r = evaluate(
        "linear_extrude(10, twist = 90, slices = 1e9) square([2, 1]);", CurveMode::OpenScad);
    ASSERT_FALSE(r.ok());
    const std::string text = diagnosticsOf(r);
    EXPECT_NE(text.find("part.scad:1:1: error: linear_extrude(): 1000000000 slices"),
              std::string::npos)
        << text;
}

// ---- (c) against OpenSCAD 2021's own export ----

// OpenSCAD snaps 2-D vertices to Clipper's grid of 2^-16 (ClipperUtils' CLIPPER_SCALE), up to
// 2^-17 a coordinate, 1.08e-5 in length (which a layer's turn keeps), and its STL rounds to
// float (5e-7 at these sizes): 1.2e-5 holds both, and is far below the distance between two
// vertices of any case.
constexpr double kVertexMatch = 1.2e-5;

struct OpenScadCase {
    const char* name;
    const char* scad;
};

class AgainstOpenScad : public ::testing::TestWithParam<OpenScadCase> {};

// Every side triangle OpenSCAD writes (one whose corners are not all at one height) is a
// triangle of csgray's mesh, corner for corner, and the other way round; the counts and the
// volumes agree (the caps may be cut into other triangles: they are the same region).
TEST_P(AgainstOpenScad, SameSlicesAndSideTriangles) {
    const OpenScadCase& c = GetParam();
    if (!testing::haveOpenScad()) SKIP_OR_FAIL_IN_CI("openscad is not installed");
    testing::TempDir dir(std::string("csgray_sliced_") + c.name);
    const auto scad = dir.path / "part.scad", stl = dir.path / "part.stl";
    testing::writeFile(scad, c.scad);
    const std::string command = "openscad --export-format binstl -o " +
                                testing::shellQuote(stl.string()) + " " +
                                testing::shellQuote(scad.string()) + " >/dev/null 2>&1";
    ASSERT_EQ(std::system(command.c_str()), 0) << command;
    const std::vector<std::array<Vec3, 3>> theirs = testing::binaryStlTriangles(stl);
    ASSERT_FALSE(theirs.empty()) << "OpenSCAD's export";

    const io::EvaluateResult r = evaluate(c.scad, CurveMode::OpenScad);
    ASSERT_TRUE(r.ok()) << diagnosticsOf(r);
    const Polyhedron* mesh = onlyPolyhedron(r);
    ASSERT_NE(mesh, nullptr) << c.scad << " did not become one polyhedron";
    EXPECT_EQ(mesh->triangleCount(), theirs.size()) << c.scad;

    // Each of OpenSCAD's corners as the index of csgray's vertex at it.
    const std::vector<Vec3>& vertices = mesh->data->vertices;
    double worst = 0.0;
    const auto indexOf = [&](const Vec3& p) {
        size_t nearest = 0;
        double distance = kInfinity;
        for (size_t k = 0; k < vertices.size(); ++k) {
            const double far = glm::length(vertices[k] - p);
            if (far < distance) distance = far, nearest = k;
        }
        worst = std::max(worst, distance);
        return uint32_t(nearest);
    };
    const auto key = [](std::array<uint32_t, 3> t) {
        std::sort(t.begin(), t.end());
        return t;
    };
    const auto flat = [&](const std::array<Vec3, 3>& t) {
        return t[0].z == t[1].z && t[1].z == t[2].z;
    };
    std::multiset<std::array<uint32_t, 3>> theirSides, ourSides;
    double theirVolume = 0.0, ourVolume = 0.0;
    for (const auto& t : theirs) {
        theirVolume += glm::dot(t[0], glm::cross(t[1], t[2])) / 6.0;
        if (!flat(t)) theirSides.insert(key({indexOf(t[0]), indexOf(t[1]), indexOf(t[2])}));
    }
    for (const auto& t : mesh->data->triangles) {
        const std::array<Vec3, 3> corners{vertices[t[0]], vertices[t[1]], vertices[t[2]]};
        ourVolume += glm::dot(corners[0], glm::cross(corners[1], corners[2])) / 6.0;
        if (!flat(corners)) ourSides.insert(key(t));
    }
    EXPECT_LE(worst, kVertexMatch) << c.scad;
    EXPECT_EQ(theirSides.size(), ourSides.size()) << c.scad;
    EXPECT_TRUE(theirSides == ourSides) << c.scad << ": the side triangles differ";
    // Both meshes are wound outward; the vertices differ by kVertexMatch at most.
    EXPECT_NEAR(std::abs(ourVolume), std::abs(theirVolume), 1e-5 * std::abs(theirVolume)) << c.scad;
}

INSTANTIATE_TEST_SUITE_P(
    Cases, AgainstOpenScad,
    ::testing::Values(
        OpenScadCase{"helix", "linear_extrude(10, twist = 90) translate([1, 0]) square([2, 1]);"},
        OpenScadCase{"back_turn_conical",
                     "linear_extrude(10, twist = -200, scale = 0.5) translate([1, 0]) "
                     "square([2, 1]);"},
        OpenScadCase{"widening",
                     "linear_extrude(10, twist = 200, scale = 1.7) translate([1, 0]) "
                     "square([2, 1]);"},
        OpenScadCase{"uneven_twisted",
                     "linear_extrude(10, twist = 45, scale = [1, 2]) "
                     "translate([1, 0]) square([2, 1]);"},
        OpenScadCase{"uneven", "linear_extrude(10, scale = [0.5, 2]) square(10, center = true);"},
        OpenScadCase{"uneven_fs",
                     "linear_extrude(10, scale = [0.5, 2], $fs = 0.3) square(10, center = true);"},
        OpenScadCase{"faceted_circle",
                     "linear_extrude(10, twist = 360, $fn = 12) "
                     "translate([3, 0]) circle(1, $fn = 8);"},
        // A hole (its diagonals flip the other way) and $fa/$fs: 3616 triangles.
        OpenScadCase{"hole",
                     "linear_extrude(20, twist = 700, $fa = 5, $fs = 0.5) difference() "
                     "{ square(6, center = true); circle(2, $fn = 12); }"},
        OpenScadCase{"apex",
                     "linear_extrude(10, twist = 90, scale = 0) translate([1, 0]) "
                     "square([2, 1]);"},
        // Edges through the origin have equal diagonals: the tie rule decides.
        OpenScadCase{"centred_back",
                     "linear_extrude(10, twist = -90, center = true, "
                     "scale = 0.3) square([4, 4], center = true);"},
        OpenScadCase{"union_of_children",
                     "linear_extrude(8, twist = 120) { square([3, 1]); translate([2, 0]) "
                     "square([1, 3]); }"}),
    [](const ::testing::TestParamInfo<OpenScadCase>& test) { return test.param.name; });

}  // namespace
}  // namespace csg
