// Extrusions as polyhedra (io/ExtrusionMesh.h) and their export as the exact boundary
// (io/ChordFaceting.h): volumes, corner counts and triangle counts by hand, the fill rules,
// segments in any order or either way round, chords on the curve within the deviation, a
// frustum's top, revolutions whole, in a wedge and on the axis, twisted and unevenly scaled
// extrusions within the deviation, and the extrusion it declines.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>

#include "PartHelpers.h"
#include "csg/mesh/MeshCheck.h"
#include "csg/mesh/MeshDistance.h"
#include "csg/mesh/Tessellate.h"
#include "csg/mesh/TriangleBvh.h"
#include "io/ChordFaceting.h"
#include "io/ExtrusionMesh.h"

namespace csg {
namespace {

using testing::diagnosticsOf;
using testing::evaluate;

constexpr double kPi = std::numbers::pi;

// The first leaf of a part's tree (the parts here are one extrusion, perhaps under groups).
const Node* firstLeaf(const NodePtr& node) {
    if (!node) return nullptr;
    if (node->op == Op::Leaf) return node.get();
    if (const Node* left = firstLeaf(node->left)) return left;
    return firstLeaf(node->right);
}

// The extrusion a part of one linear_extrude evaluates to.
Extrusion extrusionOf(const std::string& text) {
    const io::EvaluateResult r = evaluate(text);
    EXPECT_TRUE(r.ok()) << diagnosticsOf(r);
    const Node* leaf = r.ok() ? firstLeaf(r.model->root) : nullptr;
    EXPECT_TRUE(leaf && std::holds_alternative<Extrusion>(leaf->primitive)) << text;
    return leaf ? std::get<Extrusion>(leaf->primitive) : Extrusion{};
}

TriangleMesh meshOf(const Polyhedron& p) {
    TriangleMesh mesh;
    mesh.positions = p.data->vertices;
    mesh.triangles = p.data->triangles;
    return mesh;
}

double volumeOf(const Polyhedron& p) {
    return std::abs(signedVolume(meshOf(p)));
}

TEST(ExtrusionMesh, SquareWithAHoleIsItsPrism) {
    // polygon() with two paths is even-odd: a 10 x 10 square with a 4 x 4 hole, 3 high.
    const Extrusion e = extrusionOf(
        "linear_extrude(3) polygon([[0,0],[10,0],[10,10],[0,10],[3,3],[7,3],[7,7],[3,7]], "
        "[[0,1,2,3],[4,5,6,7]]);");
    const std::optional<Polyhedron> p = io::extrusionMesh(e, 0.01);
    ASSERT_TRUE(p);
    EXPECT_NEAR(volumeOf(*p), (100.0 - 16.0) * 3.0, 1e-9);
    // 8 corners at each end; each cap is V + 2H - 2 = 8 triangles, each of the 8 sides 2.
    EXPECT_EQ(p->data->vertices.size(), 16u);
    EXPECT_EQ(p->triangleCount(), 2u * 8u + 8u * 2u);
    const TriangleMesh mesh = meshOf(*p);
    EXPECT_TRUE(checkTopology(mesh).closedManifold());
}

TEST(ExtrusionMesh, NonzeroRuleUnitesOverlappingContours) {
    // Two overlapping squares in one nonzero outline (as a glyph's contours may overlap):
    // [0, 4]^2 and [2, 6]^2, area 16 + 16 - 4 = 28. polygon() is even-odd, so the nonzero
    // outline comes from text-like input: build it by hand from the even-odd one.
    Extrusion e = extrusionOf(
        "linear_extrude(2) polygon([[0,0],[4,0],[4,4],[0,4],[2,2],[6,2],[6,6],[2,6]], "
        "[[0,1,2,3],[4,5,6,7]]);");
    auto nonzero = std::make_shared<Outline>(*e.outline);
    nonzero->rule = FillRule::NonZero;
    e.outline = nonzero;
    const std::optional<Polyhedron> united = io::extrusionMesh(e, 0.01);
    ASSERT_TRUE(united);
    EXPECT_NEAR(volumeOf(*united), 28.0 * 2.0, 1e-9);
    // Even-odd, the overlap [2, 4]^2 drops out and leaves two L shapes that touch at (4, 2)
    // and (2, 4): their prisms share the vertical edges there, four faces on one edge, which is
    // no manifold, so the prism is declined (the exact leaf stays).
    const Extrusion evenOdd = extrusionOf(
        "linear_extrude(2) polygon([[0,0],[4,0],[4,4],[0,4],[2,2],[6,2],[6,6],[2,6]], "
        "[[0,1,2,3],[4,5,6,7]]);");
    EXPECT_FALSE(io::extrusionMesh(evenOdd, 0.01));
}

TEST(ExtrusionMesh, SegmentsInAnyOrderMakeTheSameRegion) {
    Extrusion e = extrusionOf(
        "linear_extrude(3) polygon([[0,0],[10,0],[10,10],[0,10],[3,3],[7,3],[7,7],[3,7]], "
        "[[0,1,2,3],[4,5,6,7]]);");
    auto shuffled = std::make_shared<Outline>(*e.outline);
    std::mt19937 rng(5);
    std::shuffle(shuffled->segments.begin(), shuffled->segments.end(), rng);
    shuffled->nodes.clear();
    shuffled->order.clear();
    shuffled->buildIndex();
    e.outline = shuffled;
    const std::optional<Polyhedron> p = io::extrusionMesh(e, 0.01);
    ASSERT_TRUE(p);
    EXPECT_NEAR(volumeOf(*p), (100.0 - 16.0) * 3.0, 1e-9);
}

// Under the even-odd rule a drawing may run its edges either way round a contour (a DXF's
// paths do): a lens of a line (0, 0) -> (4, 0) and a quadratic (0, 0) -> (4, 0) through the
// control point (2, 3), the walk taking the quadratic backwards. Its area is 2/3 of 4 x 1.5 = 4;
// the chords are inscribed, within 4.6 (the curve's length, less than 2 + 2 x 2.5) times the
// deviation. Under the nonzero rule the direction counts and the walk does not close.
TEST(ExtrusionMesh, EvenOddContoursMayRunEitherWay) {
    auto lens = std::make_shared<Outline>();
    lens->rule = FillRule::EvenOdd;
    lens->segments = {Segment2::line({0.0, 0.0}, {4.0, 0.0}),
                      Segment2::quadratic({0.0, 0.0}, {2.0, 3.0}, {4.0, 0.0})};
    lens->buildIndex();
    const double deviation = 0.001;
    const Extrusion e = Extrusion::plane(lens, "lens").linear(0.0, 2.0, Vec2(1.0));
    const std::optional<Polyhedron> p = io::extrusionMesh(e, deviation);
    ASSERT_TRUE(p);
    EXPECT_LT(volumeOf(*p), 4.0 * 2.0);
    EXPECT_GT(volumeOf(*p), (4.0 - 4.6 * deviation) * 2.0);
    EXPECT_TRUE(checkTopology(meshOf(*p)).closedManifold());

    auto nonzero = std::make_shared<Outline>(*lens);
    nonzero->rule = FillRule::NonZero;
    EXPECT_FALSE(io::extrusionMesh(Extrusion::plane(nonzero, "lens").linear(0.0, 2.0, Vec2(1.0)),
                                   deviation));
}

TEST(ExtrusionMesh, ChordsOfACircleLieOnItWithinTheDeviation) {
    // An exact circle of radius 5 (no $fn), 2 high, with the top scaled by 0.5: at deviation
    // 0.01 the chord rule asks ceil(pi / acos(1 - 0.01 / 5)) = 50 chords.
    const double r = 5.0, deviation = 0.01;
    const Extrusion e = extrusionOf("linear_extrude(2, scale = 0.5) circle(5);");
    const std::optional<Polyhedron> p = io::extrusionMesh(e, deviation);
    ASSERT_TRUE(p);
    const int n = int(std::ceil(kPi / std::acos(1.0 - deviation / r)));
    ASSERT_EQ(n, 50);
    EXPECT_EQ(p->data->vertices.size(), 2u * size_t(n));
    for (const Vec3& v : p->data->vertices) {
        const double radius = std::hypot(v.x, v.y);
        if (v.z == 0.0)
            EXPECT_NEAR(radius, r, 1e-8 * r);
        else
            EXPECT_NEAR(radius, 0.5 * r, 1e-8 * r) << "the top is the bottom scaled by 0.5";
    }
    // A frustum of regular n-gons: h / 3 (A0 + A1 + sqrt(A0 A1)), A = n/2 R^2 sin(2 pi / n).
    const double a0 = 0.5 * n * r * r * std::sin(2.0 * kPi / n), a1 = 0.25 * a0;
    EXPECT_NEAR(volumeOf(*p), 2.0 / 3.0 * (a0 + a1 + std::sqrt(a0 * a1)), 1e-6);
    // The chords' sagitta is within the deviation: the n-gon's area is within
    // perimeter * deviation of the circle's.
    EXPECT_LE(kPi * r * r - a0, 2.0 * kPi * r * deviation);
}

TEST(ExtrusionMesh, RevolutionsAreRingsOfTrapezoids) {
    // The square [2, 3] x [0, 1] revolved: a profile without curves leaves the whole deviation
    // 0.01 to the steps at the largest radius 3, ceil(pi / acos(1 - 0.01 / 3)) = 39 of them.
    // Each step is a sector of the annulus between the circles through the corners: the solid
    // is the prism of the annulus between two regular 39-gons, 39 / 2 sin(2 pi / 39)
    // (3^2 - 2^2) x 1.
    const double deviation = 0.01;
    const std::optional<Polyhedron> ring =
        io::extrusionMesh(extrusionOf("rotate_extrude() translate([2, 0]) square(1);"), deviation);
    ASSERT_TRUE(ring);
    EXPECT_EQ(ring->data->vertices.size(), 4u * 39u);
    EXPECT_NEAR(volumeOf(*ring), 19.5 * std::sin(2.0 * kPi / 39.0) * 5.0, 1e-9);
    EXPECT_TRUE(checkTopology(meshOf(*ring)).closedManifold());
    // A quarter of it: ceil(pi / 2 / (2 acos(1 - 0.01 / 3))) = 10 steps, each a sector of
    // 1/2 sin(pi / 20) (3^2 - 2^2), and the two end squares close it.
    const std::optional<Polyhedron> wedge = io::extrusionMesh(
        extrusionOf("rotate_extrude(angle = 90) translate([2, 0]) square(1);"), deviation);
    ASSERT_TRUE(wedge);
    EXPECT_EQ(wedge->data->vertices.size(), 4u * 11u);
    EXPECT_NEAR(volumeOf(*wedge), 10 * 0.5 * std::sin(kPi / 20.0) * 5.0, 1e-9);
    EXPECT_TRUE(checkTopology(meshOf(*wedge)).closedManifold());
    // A profile on the axis: the square [0, 2] x [0, 1] revolved is a 32-gon prism
    // (ceil(pi / acos(1 - 0.01 / 2)) = 32), its caps fans around the axis.
    const std::optional<Polyhedron> disc =
        io::extrusionMesh(extrusionOf("rotate_extrude() square([2, 1]);"), deviation);
    ASSERT_TRUE(disc);
    EXPECT_NEAR(volumeOf(*disc), 16.0 * std::sin(2.0 * kPi / 32.0) * 4.0, 1e-9);
    EXPECT_TRUE(checkTopology(meshOf(*disc)).closedManifold());
    // A curved profile shares the deviation: half for its chords, half for the steps. The
    // circle of radius 1 about (4, 0) has ceil(pi / acos(1 - 0.005)) = 32 chords, the steps at
    // radius 5 ceil(pi / acos(1 - 0.005 / 5)) = 71: 32 * 71 corners.
    const std::optional<Polyhedron> torus =
        io::extrusionMesh(extrusionOf("rotate_extrude() translate([4, 0]) circle(1);"), deviation);
    ASSERT_TRUE(torus);
    EXPECT_EQ(torus->data->vertices.size(), 32u * 71u);
}

TEST(ExtrusionMesh, BalancedRevolutionsStandAsFarOutsideAsInside) {
    // The ring above, balanced: the fewest steps n with 3 (1 - c) / (1 + c) <= 0.01, c =
    // cos(pi / n), i.e. tan(pi / 2n)^2 <= 0.01 / 3: n = 28, every ring scaled by 2 / (1 + c).
    const double deviation = 0.01;
    const std::optional<Polyhedron> ring =
        io::extrusionMesh(extrusionOf("rotate_extrude() translate([2, 0]) square(1);"), deviation,
                          csg::FacetFit::Balanced);
    ASSERT_TRUE(ring);
    ASSERT_EQ(ring->data->vertices.size(), 4u * 28u);
    const double c = std::cos(kPi / 28.0), s = 2.0 / (1.0 + c);
    ASSERT_GT(3.0 * (1.0 - std::cos(kPi / 27.0)) / (1.0 + std::cos(kPi / 27.0)), deviation);
    for (const Vec3& v : ring->data->vertices) {
        const double radius = std::hypot(v.x, v.y);
        EXPECT_NEAR(radius, s * (radius < 2.5 ? 2.0 : 3.0), 1e-12);
    }
    // The outer ring's corners stand 3 (s - 1) outside, its chords' middles 3 (1 - s c)
    // inside: both the deviation's worth or less, and equal.
    EXPECT_LE(3.0 * (s - 1.0), deviation);
    EXPECT_NEAR(3.0 * (s - 1.0), 3.0 * (1.0 - s * c), 1e-15);
    EXPECT_NEAR(volumeOf(*ring), 14.0 * std::sin(2.0 * kPi / 28.0) * s * s * 5.0, 1e-9);
    EXPECT_TRUE(checkTopology(meshOf(*ring)).closedManifold());
}

TEST(ExtrusionMesh, DeclinesAStraightApexAndMeshesTooLargeToMake) {
    // The apex would join the contours' sides in one vertex.
    EXPECT_FALSE(io::extrusionMesh(extrusionOf("linear_extrude(3, scale = 0) square(2);"), 0.01));
    // 3e8 slices of a billion turns; edges cut into 1e9 pieces by a millionfold scale: declined
    // before anything of that size is made.
    EXPECT_FALSE(
        io::extrusionMesh(extrusionOf("linear_extrude(10, twist = 1e9) square(5);"), 0.01));
    EXPECT_FALSE(
        io::extrusionMesh(extrusionOf("linear_extrude(10, scale = [1, 1e6]) square(5);"), 0.001));
}

// The largest distance between the mesh and the exact extrusion, both ways (MeshDistance.h,
// which samples a triangle's centroid, corners and edge middles, and the exact surface by rays),
// lines reaching `reach`, judged against `deviation`: samples above a share of it are measured
// again along the exact surface's normal (DistanceOptions::goodEnough), since a line along a
// triangle's normal meets a side that turns under it (a twisted side's helicoid tilts by 21
// degrees along the square's edge below) farther off than the surface lies.
double distanceBothWays(const Extrusion& exact, const Polyhedron& p, double reach,
                        double deviation) {
    const Scene scene = Scene::compile(leaf(exact));
    const TriangleMesh mesh = meshOf(p);
    DistanceOptions options;
    options.reach = reach;
    options.goodEnough = deviation;
    const double toSurface = meshToSurface(scene, mesh, options).max;
    return std::max(toSurface, surfaceToMesh(scene, TriangleBvh(mesh), 128, options).max);
}

// extrusionMesh(e, 0.02) of the 5 x 5 square twisted by 90 degrees over a height of 10 and
// scaled by `scale` to the top, in the 99 slices of whole edges the tests below work out by hand:
// layer j is the square turned by -90 j / 99 degrees and scaled by 1 + (scale - 1) j / 99 (turned
// back and scaled up, every corner lies on the square's edge); closed; the volume within the
// sides' area times d; within d of the solid both ways.
void expectNinetyNineSlicesOfWholeEdges(const Extrusion& e, double scale, double volume) {
    const std::optional<Polyhedron> p = io::extrusionMesh(e, 0.02);
    ASSERT_TRUE(p);
    EXPECT_EQ(p->data->vertices.size(), 100u * 4u);
    EXPECT_EQ(p->triangleCount(), 2u * 99u * 4u + 2u * 2u);
    for (const Vec3& v : p->data->vertices) {
        const double j = std::round(v.z * 9.9);
        EXPECT_NEAR(v.z, 10.0 * j / 99.0, 1e-12);
        const double a = kPi / 2.0 * j / 99.0, sigma = 1.0 + (scale - 1.0) * j / 99.0;
        const Vec2 back(std::cos(a) * v.x - std::sin(a) * v.y,
                        std::sin(a) * v.x + std::cos(a) * v.y);
        EXPECT_NEAR(std::max(std::abs(back.x), std::abs(back.y)) / sigma, 2.5, 1e-12);
    }
    EXPECT_TRUE(checkTopology(meshOf(*p)).closedManifold());
    EXPECT_NEAR(volumeOf(*p), volume, 20.0 * 10.0 * 0.02);
    EXPECT_LE(distanceBothWays(e, *p, 0.1, 0.02), 0.02);
}

// linear_extrude(10, twist = 90) of a 5 x 5 square at deviation d = 0.02 (ExtrusionMesh.cpp,
// slicedToDeviation): a twist alone, w = pi / 2, h = 10. Each side's line passes 2.5 from the
// axis and its points' e . q run over [-2.5, 2.5], so the smallest is 0, n = h, and the bounds
// are J = w^2 2.5 = 6.1685 and K = w. With n slices an edge's pieces may be 4 (d - J / (8 n^2)) n
// / w long: whole edges (5 long) first at n = 99 (q = 5.04; at 98, 4.99), 2 x 99 x 4 side
// triangles and two caps of 2: 796. Two pieces first at n = 50 would make 2 x 50 x 8 + 2 x 6 =
// 812, three at 34 836, and the old bound (the whole S_ll, J = w^2 rho = 8.72, a quarter of d to
// the slices) took 15 slices of 9 pieces per edge, 1 148.
TEST(ExtrusionMesh, ATwistedSquareTakesTheSlicesThatMakeTheFewestTriangles) {
    // The twist preserves each section's area: 25 x 10.
    expectNinetyNineSlicesOfWholeEdges(
        extrusionOf("linear_extrude(height = 10, twist = 90) square(5, center = true);"), 1.0,
        250.0);
}

// The same square twisted and scaled by 0.5 at d = 0.02: k = -0.5, v = 1, w = pi / 2, h = 10.
// Each edge passes 2.5 from the axis and reaches 2.5 along itself, so the normal parts give
// J = 2 w |k| 2.5 + w^2 2.5 = 10.0955 and K = v w = 1.5708: pieces may be 4 (d - J / (8 n^2)) n
// / K long, whole edges first at n = 99 (5.009; at 98, 4.959), 796 triangles as without the
// scale; two pieces first at n = 51 would make 828, three at 35 860. The whole derivatives
// (J = (2 |k| w + w^2) 2.5 sqrt 2 = 14.277, K = |k| + w = 2.0708) took 131 slices of whole
// edges, 1 052.
TEST(ExtrusionMesh, ATwistedFrustumCountsOnlyTheNormalParts) {
    // Sections 25 sigma^2: 250 (1 + k + k^2 / 3) = 145.83 over the height.
    expectNinetyNineSlicesOfWholeEdges(
        extrusionOf(
            "linear_extrude(height = 10, twist = 90, scale = 0.5) square(5, center = true);"),
        0.5, 250.0 * (1.0 - 0.5 + 0.25 / 3.0));
}

// The bounds hold across twists, scales (to an apex, and growing) and outlines far from the axis
// or around it, straight and curved: every mesh lies within its deviation of the exact solid,
// both ways.
TEST(ExtrusionMesh, TwistedAndScaledSidesStayWithinTheDeviation) {
    const struct {
        const char* scad;
        double deviation;
    } cases[] = {
        {"linear_extrude(height = 6, twist = -360, scale = 0) square([4, 2], center = true);",
         0.05},
        {"linear_extrude(height = 4, twist = 120, scale = 2.5) square([3, 1], center = true);",
         0.05},
        {"linear_extrude(height = 5, twist = 200, scale = 0.3) translate([3, 0]) square(1);", 0.03},
        {"linear_extrude(height = 3, twist = 45, scale = 1.5) translate([2, 1]) circle(1);", 0.02},
        {"linear_extrude(height = 8, twist = -90, scale = [0.5, 2]) square(2, center = true);",
         0.05},
    };
    for (const auto& c : cases) {
        const Extrusion e = extrusionOf(c.scad);
        const std::optional<Polyhedron> p = io::extrusionMesh(e, c.deviation);
        ASSERT_TRUE(p) << c.scad;
        EXPECT_TRUE(checkTopology(meshOf(*p)).closedManifold()) << c.scad;
        EXPECT_LE(distanceBothWays(e, *p, 5.0 * c.deviation, c.deviation), c.deviation) << c.scad;
    }
}

// Two scales make each side a hyperbolic paraboloid. A diamond (|x| + |y| <= 1.5) scaled by
// [1, 3] over 4, at d = 0.04: no twist, so J = 0; every edge runs along (+-1, +-1) / sqrt 2, so
// K = |(0, 2) e| = sqrt 2, and with n slices pieces may be 4 d n / K = 0.1131 n long. An edge
// is 1.5 sqrt 2 = 2.121 long: ceil(18.75 / n) pieces, 2 n x 4 p side triangles and two caps of
// 4 p - 2. One slice of 19 pieces would make 300, 2 of 10 236, 4 of 5 196, 10 of 2 172, and 19
// slices of whole edges 2 x 19 x 4 + 2 x 2 = 156, the fewest.
TEST(ExtrusionMesh, UnevenScalesTakeTheSlicesThatMakeTheFewestTriangles) {
    const Extrusion e = extrusionOf(
        "linear_extrude(height = 4, scale = [1, 3]) polygon([[1.5, 0], [0, 1.5], [-1.5, 0], [0, "
        "-1.5]]);");
    const std::optional<Polyhedron> p = io::extrusionMesh(e, 0.04);
    ASSERT_TRUE(p);
    EXPECT_EQ(p->data->vertices.size(), 20u * 4u);
    EXPECT_EQ(p->triangleCount(), 2u * 19u * 4u + 2u * 2u);
    // Layer j at z = 4 j / 19 is the diamond scaled by 1 + z / 2 in y.
    for (const Vec3& v : p->data->vertices) {
        const double j = std::round(v.z * 19.0 / 4.0);
        EXPECT_NEAR(v.z, 4.0 * j / 19.0, 1e-12);
        EXPECT_NEAR(std::abs(v.x) + std::abs(v.y / (1.0 + v.z / 2.0)), 1.5, 1e-12);
    }
    EXPECT_TRUE(checkTopology(meshOf(*p)).closedManifold());
    // Each section of the frustum is the diamond scaled by 1 + 2 z / 4 in y: area 4.5 (1 + z / 2),
    // 4.5 x (4 + 4) = 36 over the height.
    EXPECT_NEAR(volumeOf(*p), 36.0, 1e-9 * 36.0 + 0.04 * 4.0 * 4.0 * 3.0);
    EXPECT_LE(distanceBothWays(e, *p, 0.2, 0.04), 0.04);
}

// End to end: a part made of straight extrusions exports as its exact boundary, the fewest
// triangles its faces allow.
TEST(ExtrusionMesh, ExtrudedPartsExportAsTheirExactBoundary) {
    // A 2-D difference, extruded: a frame, 32 triangles as above, not a grid's thousands.
    const io::EvaluateResult r = evaluate(
        "linear_extrude(5) difference() { square(10, center = true); "
        "square(4, center = true); }");
    ASSERT_TRUE(r.ok()) << diagnosticsOf(r);
    const Scene scene = Scene::compile(r.model->root);
    TessellateOptions options;
    options.tolerance = 0.01;
    options.facetCurves = io::curveFaceter(r.model->root);
    const TessellateResult t = tessellate(scene, options);
    EXPECT_TRUE(t.exact);
    EXPECT_EQ(t.mesh.triangles.size(), 32u);
    EXPECT_NEAR(std::abs(signedVolume(t.mesh)), (100.0 - 16.0) * 5.0, 1e-9);
    EXPECT_LE(std::max(t.error.max, t.backError.max), 1e-9);
}

}  // namespace
}  // namespace csg
