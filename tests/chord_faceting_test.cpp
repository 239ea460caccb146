// Faceting curves to a deviation (io/ChordFaceting.h) and the export that uses it
// (TessellateOptions::facetCurves). OpenSCAD's vertex layout, inscribed (faces up to R (1 - c)
// inside, c R the nearest face plane's distance) or balanced (scaled by 2 / (1 + c): faces
// R (1 - c) / (1 + c) off both ways). Fragment counts by hand: the least n >= 3 whose fit stands
// within the deviation; a cylinder's c is cos(pi / n); a sphere's c is the least plane distance
// of its rings' trapezoids and caps, found (python, from the 3-D vertices, n counted up from 3):
// balanced, n = 23 for R = 1 at 0.01 (c = 0.98221) and 31 for R = 10 at 0.05; inscribed, 31
// and 45 (the chord rule at half the deviation, used before, gave 32 and 45).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <utility>
#include <vector>

#include "csg/Tree.h"
#include "csg/mesh/MeshCheck.h"
#include "csg/mesh/MeshDistance.h"
#include "csg/mesh/PolyhedralBoundary.h"
#include "csg/mesh/Tessellate.h"
#include "io/ChordFaceting.h"
#include "primitives/ConvexPolytope.h"
#include "tests/PartHelpers.h"

namespace csg {
namespace {

const ConvexPolytope& polytopeOf(const NodePtr& node) {
    return std::get<ConvexPolytope>(node->primitive);
}

// The export of part at tolerance T with its curves faceted (as `csgray export` does it).
TessellateResult exportFaceted(const NodePtr& part, double tolerance) {
    TessellateOptions options;
    options.tolerance = tolerance;
    options.facetCurves = io::curveFaceter(part);
    return tessellate(Scene::compile(part), options);
}

TEST(ChordFaceting, FragmentsFollowTheChordRuleAtTheWorldRadius) {
    const FacetFit balanced = FacetFit::Balanced, inscribed = FacetFit::Inscribed;
    // sphere(1), deviation 0.01: balanced 23, inscribed 31.
    for (auto [fit, n] : {std::pair{balanced, 23u}, {inscribed, 31u}}) {
        const NodePtr sphere = io::facetToDeviation(leaf(Sphere{1.0}), 0.01, fit);
        ASSERT_TRUE(sphere);
        EXPECT_EQ(polytopeOf(sphere).data->origin.fragments, n);
    }
    // cylinder(r = 1), deviation 0.01: balanced, tan(pi / 2n)^2 <= 0.01, n >= pi / (2 atan 0.1)
    // = 15.76: 16; inscribed, 1 - cos(pi / n) <= 0.01, n >= pi / acos(0.99) = 22.2: 23.
    for (auto [fit, n] : {std::pair{balanced, 16u}, {inscribed, 23u}}) {
        const NodePtr cylinder = io::facetToDeviation(leaf(Cylinder{2.0, 1.0, 1.0}), 0.01, fit);
        ASSERT_TRUE(cylinder);
        EXPECT_EQ(polytopeOf(cylinder).data->origin.fragments, n);
    }
    // Stretched threefold along y, the sphere is as long as a sphere of radius 3: at deviation
    // 0.03, 0.03 / 3 = 0.01 / 1, so 23 again; the transform is kept.
    const Mat4 stretch = glm::scale(Mat4(1.0), Vec3(1.0, 3.0, 1.0));
    const NodePtr stretched =
        io::facetToDeviation(transformed(stretch, leaf(Sphere{1.0})), 0.03, balanced);
    ASSERT_TRUE(stretched);
    EXPECT_EQ(polytopeOf(stretched).data->origin.fragments, 23u);
    EXPECT_EQ(stretched->parentFromNode, stretch);
}

TEST(ChordFaceting, FacesAndCornersStandWithinTheDeviationBothWays) {
    const double r = 10.0, deviation = 0.05;
    const NodePtr node = io::facetToDeviation(leaf(Sphere{r}), deviation, FacetFit::Balanced);
    ASSERT_TRUE(node);
    const ConvexPolytopeData& d = *polytopeOf(node).data;
    EXPECT_EQ(d.origin.fragments, 31u);
    // Corners outside the sphere, faces' planes inside it (planes are n . p <= offset), each
    // within the deviation; balanced, the farthest corner and the nearest plane stand equally
    // far off.
    double farthestCorner = 0.0, nearestPlane = r;
    for (const Vec3& v : d.vertices) farthestCorner = std::max(farthestCorner, glm::length(v));
    for (const PolytopePlane& plane : d.planes)
        nearestPlane = std::min(nearestPlane, plane.offset / glm::length(plane.normal));
    EXPECT_GT(farthestCorner, r);
    EXPECT_LE(farthestCorner, r + deviation);
    EXPECT_LT(nearestPlane, r);
    EXPECT_GE(nearestPlane, r - deviation);
    EXPECT_NEAR(farthestCorner - r, r - nearestPlane, 1e-12 * r);
    // The cylinder's corners likewise, its side planes at r cos(pi / n) of the scaled radius.
    const NodePtr rod =
        io::facetToDeviation(leaf(Cylinder{5.0, r, r}), deviation, FacetFit::Balanced);
    ASSERT_TRUE(rod);
    const ConvexPolytopeData& c = *polytopeOf(rod).data;
    for (const Vec3& v : c.vertices) {
        EXPECT_GT(std::hypot(v.x, v.y), r);
        EXPECT_LE(std::hypot(v.x, v.y), r + deviation);
    }
    for (const PolytopePlane& plane : c.planes) {
        if (plane.normal.z == 0.0) {
            EXPECT_GE(plane.offset / glm::length(plane.normal), r - deviation);
        }
    }
}

// A capsule's end and body (a rounded box's corner and edge): sphere(1) alone takes 23
// fragments at 0.01 and cylinder(r = 1) 16 (above); with the sphere's centre on the end of the
// cylinder's axis they take one layout, the 23 both need rounded up to 26 (2 modulo 4: the
// sphere's 13 rings put one on its equator, where the cylinder's end ring meets it), with the
// sphere's scale, which keeps the cylinder's corners and faces within the deviation. A
// cylinder of another radius, or of the same radius elsewhere, keeps its own layout.
TEST(ChordFaceting, ASphereAndACylinderOfOneRadiusShareALayout) {
    const double deviation = 0.01;
    const NodePtr capsule = io::facetToDeviation(
        unite(leaf(Sphere{1.0}), leaf(Cylinder{2.0, 1.0, 1.0})), deviation, FacetFit::Balanced);
    ASSERT_TRUE(capsule);
    const ConvexPolytopeData& sphere = *polytopeOf(capsule->left).data;
    const ConvexPolytopeData& rod = *polytopeOf(capsule->right).data;
    EXPECT_EQ(sphere.origin.fragments, 26u);
    EXPECT_EQ(rod.origin.fragments, 26u);
    // The rod's end ring lies on the sphere's equator ring: the same points.
    int shared = 0;
    for (const Vec3& v : rod.vertices)
        for (const Vec3& w : sphere.vertices) shared += glm::length(v - w) <= 1e-12;
    EXPECT_EQ(shared, 26);
    for (const Vec3& v : rod.vertices) {
        EXPECT_GT(std::hypot(v.x, v.y), 1.0);
        EXPECT_LE(std::hypot(v.x, v.y), 1.0 + deviation);
    }
    for (const PolytopePlane& plane : rod.planes) {
        if (plane.normal.z == 0.0) {
            EXPECT_GE(plane.offset / glm::length(plane.normal), 1.0 - deviation);
        }
    }

    const NodePtr thinner = io::facetToDeviation(
        unite(leaf(Sphere{1.0}), leaf(Cylinder{2.0, 0.5, 0.5})), deviation, FacetFit::Balanced);
    const NodePtr alone =
        io::facetToDeviation(leaf(Cylinder{2.0, 0.5, 0.5}), deviation, FacetFit::Balanced);
    ASSERT_TRUE(thinner && alone);
    EXPECT_EQ(polytopeOf(thinner->left).data->origin.fragments, 23u);
    EXPECT_EQ(polytopeOf(thinner->right).data->origin.fragments,
              polytopeOf(alone).data->origin.fragments);
    const Mat4 aside = glm::translate(Mat4(1.0), Vec3(3.0, 0.0, 0.0));
    const NodePtr apart = io::facetToDeviation(
        unite(leaf(Sphere{1.0}), transformed(aside, leaf(Cylinder{2.0, 1.0, 1.0}))), deviation,
        FacetFit::Balanced);
    ASSERT_TRUE(apart);
    EXPECT_EQ(polytopeOf(apart->left).data->origin.fragments, 23u);
    EXPECT_EQ(polytopeOf(apart->right).data->origin.fragments, 16u);
}

TEST(ChordFaceting, LeavesThatStayCurvedGiveNothing) {
    const FacetFit fit = FacetFit::Balanced;
    // An algebraic surface has no faceting of its own.
    const io::EvaluateResult curved = csg::testing::evaluate(
        "surface(f = \"x^4 + y^4 + z^4 - 1\", bbox = [[-2, -2, -2], [2, 2, 2]]);");
    ASSERT_TRUE(curved.ok());
    EXPECT_FALSE(io::facetToDeviation(curved.model->root, 0.01, fit));
    EXPECT_FALSE(io::facetToDeviation(unite(leaf(Box{Vec3(0.0), Vec3(1.0)}), curved.model->root),
                                      0.01, fit));
    EXPECT_TRUE(
        io::facetToDeviation(unite(leaf(Box{Vec3(0.0), Vec3(1.0)}), leaf(Sphere{1.0})), 0.01, fit));
}

// A torus is the revolution of its tube's circle: half the deviation for the circle's chords
// (r = 0.5: ceil(pi / acos(1 - 0.005 / 0.5)) = 23), half for the balanced steps at R + r =
// 2.5 (the fewest n with 2.5 (1 - c) / (1 + c) <= 0.005, c = cos(pi / n): 50).
TEST(ChordFaceting, ATorusIsTheRevolutionOfItsTube) {
    const NodePtr faceted = io::facetToDeviation(leaf(Torus{2.0, 0.5}), 0.01, FacetFit::Balanced);
    ASSERT_TRUE(faceted);
    const auto* mesh = std::get_if<Polyhedron>(&faceted->primitive);
    ASSERT_TRUE(mesh);
    EXPECT_EQ(mesh->data->vertices.size(), 23u * 36u);
    ASSERT_GT(2.5 * (1.0 - std::cos(kPi / 35.0)) / (1.0 + std::cos(kPi / 35.0)), 0.005);
    ASSERT_LE(2.5 * (1.0 - std::cos(kPi / 36.0)) / (1.0 + std::cos(kPi / 36.0)), 0.005);
}

TEST(ChordFaceting, ACurvedPartExportsAsTheBoundaryOfItsFacetedLeaves) {
    // A ball of radius 10 with a cylinder bored through: exact curves, exported at T = 0.05.
    const NodePtr part =
        subtract(leaf(Sphere{10.0}), transformed(glm::translate(Mat4(1.0), Vec3(0.0, 0.0, -12.0)),
                                                 leaf(Cylinder{24.0, 3.0, 3.0})));
    const double tolerance = 0.05;
    const TessellateResult result = exportFaceted(part, tolerance);
    ASSERT_TRUE(result.exact);
    EXPECT_EQ(result.facetDeviation, 0.5 * tolerance);
    EXPECT_EQ(result.facetFit, FacetFit::Balanced);
    EXPECT_TRUE(result.toleranceMet);
    EXPECT_LE(result.error.max, tolerance);
    EXPECT_LE(result.backError.max, tolerance);
    EXPECT_TRUE(checkTopology(result.mesh).closedManifold());
    // The solid by formula: the ball less the bore, a cylinder of radius a through it with its
    // two spherical caps: 4/3 pi (r^2 - a^2)^(3/2) is what remains (the napkin ring).
    const double r = 10.0, a = 3.0;
    const double exact = 4.0 / 3.0 * std::numbers::pi * std::pow(r * r - a * a, 1.5);
    double six = 0.0;
    for (const auto& t : result.mesh.triangles)
        six += glm::dot(result.mesh.positions[t[0]],
                        glm::cross(result.mesh.positions[t[1]], result.mesh.positions[t[2]]));
    // Every point of the mesh is within T of the surface: the volumes differ by at most the
    // surface (outer sphere and bore, < 4 pi r^2 + 2 pi a 2 r) times T.
    const double area = 4.0 * std::numbers::pi * r * r + 2.0 * std::numbers::pi * a * 2.0 * r;
    EXPECT_NEAR(six / 6.0, exact, area * tolerance);
    // Far fewer triangles than a grid at that tolerance needs (its cells are ~T): balanced at
    // 0.025, the sphere has ~45 fragments and 23 rings.
    EXPECT_LT(result.mesh.triangles.size(), 20'000u);
}

// A pocket cut from x = 10 into sphere(10), flush with its side: the balanced sphere's equator
// ring (23 rings at this deviation, the middle one on the equator, a vertex on +x) stands
// outside it, so the pocket keeps a skin over it, points with no exact surface within reach.
// The export measures that, and takes the inscribed fit at the same deviation.
TEST(ChordFaceting, ASkinOverAFlushCutFallsBackToTheInscribedFit) {
    const NodePtr part =
        subtract(leaf(Sphere{10.0}), leaf(Box{Vec3(7.0, -3.0, -3.0), Vec3(10.0, 3.0, 3.0)}));
    const Scene scene = Scene::compile(part);
    const double tolerance = 0.05;
    const NodePtr skinned = io::facetToDeviation(part, 0.5 * tolerance, FacetFit::Balanced);
    ASSERT_TRUE(skinned);
    const std::optional<TriangleMesh> skin = polyhedralBoundary(Scene::compile(skinned), 0);
    ASSERT_TRUE(skin);
    DistanceOptions reach;
    reach.reach = reach.goodEnough = tolerance;
    EXPECT_GT(meshToSurface(scene, *skin, reach).unresolved, 0u);

    const TessellateResult result = exportFaceted(part, tolerance);
    ASSERT_TRUE(result.exact);
    EXPECT_EQ(result.facetFit, FacetFit::Inscribed);
    EXPECT_GE(result.facetDeviation, 0.5 * tolerance);  // or coarser, if the slack allowed it
    EXPECT_LE(result.error.max, tolerance);
    EXPECT_LE(result.backError.max, tolerance);
    EXPECT_EQ(result.error.unresolved, 0u);
    EXPECT_TRUE(checkTopology(result.mesh).closedManifold());
}

// A balanced sphere is cut at its poles' planes: the top and bottom faces lie in z = +-r, so a
// pocket cut flush with a pole (Debian's example012: letters cut from the top of sphere(20))
// keeps no skin there, and the export stays balanced.
TEST(ChordFaceting, ABalancedSphereStopsAtItsPoles) {
    const double r = 10.0, deviation = 0.025;
    const NodePtr faceted = io::facetToDeviation(leaf(Sphere{r}), deviation, FacetFit::Balanced);
    ASSERT_TRUE(faceted);
    const ConvexPolytope& sphere = polytopeOf(faceted);
    double top = -kInfinity, bottom = kInfinity;
    int onTop = 0;
    for (const Vec3& v : sphere.data->vertices) {
        top = std::max(top, v.z);
        bottom = std::min(bottom, v.z);
        onTop += v.z == r;
        // Every vertex stands outside the sphere, by no more than the deviation.
        EXPECT_GE(glm::length(v), r * (1.0 - 1e-15));
        EXPECT_LE(glm::length(v), r + deviation);
    }
    EXPECT_EQ(top, r);
    EXPECT_EQ(bottom, -r);
    EXPECT_GE(onTop, 3);  // a face, not a point
    // The exact sphere's pole is on the mesh, and its equator inside it.
    EXPECT_TRUE(sphere.inside(Vec3(0.0, 0.0, r * (1.0 - 1e-12))));
    EXPECT_FALSE(sphere.inside(Vec3(0.0, 0.0, r * (1.0 + 1e-12))));

    const double tolerance = 2.0 * deviation;
    const NodePtr part =
        subtract(leaf(Sphere{r}), leaf(Box{Vec3(-3.0, -3.0, 7.0), Vec3(3.0, 3.0, r)}));
    const TessellateResult result = exportFaceted(part, tolerance);
    ASSERT_TRUE(result.exact);
    EXPECT_EQ(result.facetFit, FacetFit::Balanced);
    EXPECT_LE(std::max(result.error.max, result.backError.max), tolerance);
    EXPECT_EQ(result.error.unresolved, 0u);
    EXPECT_TRUE(checkTopology(result.mesh).closedManifold());
}

// A faceter that overshoots: asked for deviation d, it facets at 1.8 d, so the first attempt
// (T/2) measures about 0.9 T (a sphere's sampled maximum sits at or a little under its
// deviation), over the margin 0.8 T but under the skin factor (3 d). The next attempt stays
// balanced, finer in proportion: d times 0.8 of the margin (0.64 T) over the distance measured,
// 0.7-0.8 of d (halving would give 0.5), which then measures within the margin. The slack rule
// then finds too little to gain for a coarser attempt.
TEST(ChordFaceting, AMissIsTriedFinerInProportionToIt) {
    const NodePtr ball = leaf(Sphere{10.0});
    const Scene scene = Scene::compile(ball);
    const auto faceter = io::curveFaceter(ball);
    std::vector<std::pair<double, FacetFit>> asked;
    TessellateOptions options;
    options.tolerance = 0.05;
    options.facetCurves = {[&](double deviation, FacetFit fit, double oneWayShare) {
                               asked.push_back({deviation, fit});
                               return faceter(1.8 * deviation, fit, oneWayShare);
                           },
                           faceter.mixedCurvature};
    const TessellateResult result = tessellate(scene, options);
    ASSERT_TRUE(result.exact);
    ASSERT_EQ(asked.size(), 2u);
    EXPECT_EQ(asked[0], std::pair(0.5 * options.tolerance, FacetFit::Balanced));
    EXPECT_EQ(asked[1].second, FacetFit::Balanced);
    EXPECT_GT(asked[1].first, 0.65 * asked[0].first);
    EXPECT_LT(asked[1].first, 0.8 * asked[0].first);
    EXPECT_EQ(result.facetDeviation, asked[1].first);
    EXPECT_LE(std::max(result.error.max, result.backError.max), 0.8 * options.tolerance);
}

// A lone sphere measures about its deviation, T/2, well under the margin (0.8 T): the export
// spends the slack on one coarser faceting, kept because it too measures within the margin.
TEST(ChordFaceting, TheSlackUnderTheMarginBuysACoarserFaceting) {
    const NodePtr ball = leaf(Sphere{10.0});
    const double tolerance = 0.05;
    const TessellateResult result = exportFaceted(ball, tolerance);
    ASSERT_TRUE(result.exact);
    EXPECT_EQ(result.facetFit, FacetFit::Balanced);
    EXPECT_GT(result.facetDeviation, 0.5 * tolerance);
    EXPECT_LE(result.facetDeviation, tolerance);
    EXPECT_LE(std::max(result.error.max, result.backError.max), 0.8 * tolerance);
    const std::optional<TriangleMesh> first = polyhedralBoundary(
        Scene::compile(io::facetToDeviation(ball, 0.5 * tolerance, FacetFit::Balanced)), 0);
    ASSERT_TRUE(first);
    EXPECT_LT(result.mesh.triangles.size(), first->triangles.size());
}

// Debian's example001: sphere(25) less three bores of radius 12.5 along x, y and z, whose rims
// meet the sphere at 60 degrees.
NodePtr sphereWithThreeBores() {
    const NodePtr bore = transformed(glm::translate(Mat4(1.0), Vec3(0.0, 0.0, -31.25)),
                                     leaf(Cylinder{62.5, 12.5, 12.5}));
    const auto turned = [&](Vec3 axis) {
        return transformed(glm::rotate(Mat4(1.0), 0.5 * kPi, axis), bore);
    };
    return subtract(subtract(subtract(leaf(Sphere{25.0}), bore), turned(Vec3(1.0, 0.0, 0.0))),
                    turned(Vec3(0.0, 1.0, 0.0)));
}

// Leaves curved one way only (cylinders) and both ways (spheres, tori) together make a mixed
// part; only there does the one-way share change a faceting.
TEST(ChordFaceting, TheOneWayShareFacetsCylindersFinerBesideSpheres) {
    const NodePtr cylinder = leaf(Cylinder{5.0, 3.0, 3.0});
    EXPECT_TRUE(io::mixedCurvature(subtract(leaf(Sphere{4.0}), cylinder)));
    EXPECT_TRUE(io::mixedCurvature(unite(leaf(Torus{2.0, 0.5}), cylinder)));
    EXPECT_FALSE(io::mixedCurvature(unite(cylinder, leaf(Cylinder{2.0, 1.0, 0.5}))));
    EXPECT_FALSE(io::mixedCurvature(subtract(leaf(Sphere{4.0}), leaf(Box{Vec3(0.0), Vec3(1.0)}))));
    EXPECT_FALSE(io::mixedCurvature(leaf(Sphere{4.0})));

    // The cylinder's vertices of a faceted tree's second leaf.
    const auto cylinderVertices = [](const NodePtr& faceted) {
        return polytopeOf(faceted->right).data->vertices.size();
    };
    const double d = 0.01;
    const NodePtr mixed = subtract(leaf(Sphere{4.0}), cylinder);
    const size_t whole = cylinderVertices(io::facetToDeviation(mixed, d, FacetFit::Balanced));
    const size_t half = cylinderVertices(io::facetToDeviation(mixed, d, FacetFit::Balanced, 0.5));
    // Balanced, r = 3: the fewest n with 3 (1 - c) / (1 + c) <= d, c = cos(pi / n), is 28 at
    // d = 0.01 and 39 at 0.005; each fragment is two vertices.
    EXPECT_EQ(whole, 2u * 28u);
    EXPECT_EQ(half, 2u * 39u);
    // Beside another cylinder, nothing changes.
    const NodePtr twoCylinders = unite(leaf(Cylinder{2.0, 1.0, 1.0}), cylinder);
    EXPECT_EQ(cylinderVertices(io::facetToDeviation(twoCylinders, d, FacetFit::Balanced, 0.5)),
              2u * 28u);
}

// example001 at T = 0.273 (Manifold's distance on it): balanced at T/2 its rims miss the margin
// (0.8 T). The next attempt keeps the deviation and facets the bores at half of it, which
// measures within the margin with fewer triangles than shrinking every leaf's deviation does.
TEST(ChordFaceting, ARimMissIsTriedWithTheOneWayLeavesFinerFirst) {
    const NodePtr part = sphereWithThreeBores();
    const Scene scene = Scene::compile(part);
    const auto faceter = io::curveFaceter(part);
    const double tolerance = 0.273;
    const auto exportWith = [&](bool honourShare, std::vector<double>* shares) {
        TessellateOptions options;
        options.tolerance = tolerance;
        options.facetCurves = {[&](double deviation, FacetFit fit, double oneWayShare) {
                                   if (shares) shares->push_back(oneWayShare);
                                   return faceter(deviation, fit, honourShare ? oneWayShare : 1.0);
                               },
                               faceter.mixedCurvature};
        return tessellate(scene, options);
    };
    std::vector<double> shares;
    const TessellateResult result = exportWith(true, &shares);
    ASSERT_TRUE(result.exact);
    ASSERT_GE(shares.size(), 2u);
    EXPECT_EQ(shares[0], 1.0);
    EXPECT_EQ(shares[1], tol::kFacetOneWayShare);
    EXPECT_EQ(result.facetDeviation, 0.5 * tolerance);
    EXPECT_EQ(result.facetOneWayShare, tol::kFacetOneWayShare);
    EXPECT_LE(std::max(result.error.max, result.backError.max), 0.8 * tolerance);
    EXPECT_TRUE(checkTopology(result.mesh).closedManifold());

    const TessellateResult allFiner = exportWith(false, nullptr);
    ASSERT_TRUE(allFiner.exact);
    EXPECT_LT(allFiner.facetDeviation, 0.5 * tolerance);
    EXPECT_LT(double(result.mesh.triangles.size()), 0.8 * double(allFiner.mesh.triangles.size()));
}

}  // namespace
}  // namespace csg
