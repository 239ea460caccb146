// Faceting curves to a deviation (io/ChordFaceting.h) and the export that uses it
// (TessellateOptions::facetCurves). Fragment counts are the chord rule's by hand: the least n
// with R (1 - cos(pi / n)) <= sagitta (python: ceil(pi / acos(1 - s / R))); a sphere's
// sagitta is half the deviation (across and along its rings).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "csg/Tree.h"
#include "csg/mesh/MeshCheck.h"
#include "csg/mesh/Tessellate.h"
#include "io/ChordFaceting.h"
#include "primitives/ConvexPolytope.h"

namespace csg {
namespace {

const ConvexPolytope& polytopeOf(const NodePtr& node) {
    return std::get<ConvexPolytope>(node->primitive);
}

TEST(ChordFaceting, FragmentsFollowTheChordRuleAtTheWorldRadius) {
    // sphere(1), deviation 0.01: sagitta 0.005, ceil(pi / acos(0.995)) = 32.
    const NodePtr sphere = io::facetToDeviation(leaf(Sphere{1.0}), 0.01);
    ASSERT_TRUE(sphere);
    EXPECT_EQ(polytopeOf(sphere).data->origin.fragments, 32u);
    // cylinder(r = 1), deviation 0.01: sagitta 0.01, ceil(pi / acos(0.99)) = 23.
    const NodePtr cylinder = io::facetToDeviation(leaf(Cylinder{2.0, 1.0, 1.0}), 0.01);
    ASSERT_TRUE(cylinder);
    EXPECT_EQ(polytopeOf(cylinder).data->origin.fragments, 23u);
    // Stretched threefold along y, the sphere is as long as a sphere of radius 3: at deviation
    // 0.03 (sagitta 0.015), ceil(pi / acos(1 - 0.005)) = 32 again; the transform is kept.
    const Mat4 stretch = glm::scale(Mat4(1.0), Vec3(1.0, 3.0, 1.0));
    const NodePtr stretched = io::facetToDeviation(transformed(stretch, leaf(Sphere{1.0})), 0.03);
    ASSERT_TRUE(stretched);
    EXPECT_EQ(polytopeOf(stretched).data->origin.fragments, 32u);
    EXPECT_EQ(stretched->parentFromNode, stretch);
}

TEST(ChordFaceting, FacesStandWithinTheDeviationAndCornersOnTheSphere) {
    const double r = 10.0, deviation = 0.05;
    const NodePtr node = io::facetToDeviation(leaf(Sphere{r}), deviation);
    ASSERT_TRUE(node);
    const ConvexPolytopeData& d = *polytopeOf(node).data;
    for (const Vec3& v : d.vertices) EXPECT_NEAR(glm::length(v), r, 1e-12 * r);
    // Each face's plane passes within the deviation of the sphere: the origin is at least
    // r - deviation from it (planes are n . p <= offset with unit n).
    for (const PolytopePlane& plane : d.planes) {
        EXPECT_GE(plane.offset / glm::length(plane.normal), r - deviation);
        EXPECT_LE(plane.offset / glm::length(plane.normal), r);
    }
}

TEST(ChordFaceting, LeavesThatStayCurvedGiveNothing) {
    EXPECT_FALSE(io::facetToDeviation(leaf(Torus{2.0, 0.5}), 0.01));
    EXPECT_FALSE(
        io::facetToDeviation(unite(leaf(Box{Vec3(0.0), Vec3(1.0)}), leaf(Torus{2.0, 0.5})), 0.01));
    EXPECT_TRUE(
        io::facetToDeviation(unite(leaf(Box{Vec3(0.0), Vec3(1.0)}), leaf(Sphere{1.0})), 0.01));
}

TEST(ChordFaceting, ACurvedPartExportsAsTheBoundaryOfItsFacetedLeaves) {
    // A ball of radius 10 with a cylinder bored through: exact curves, exported at T = 0.05.
    const NodePtr part =
        subtract(leaf(Sphere{10.0}), transformed(glm::translate(Mat4(1.0), Vec3(0.0, 0.0, -12.0)),
                                                 leaf(Cylinder{24.0, 3.0, 3.0})));
    const Scene scene = Scene::compile(part);
    TessellateOptions options;
    options.tolerance = 0.05;
    options.facetCurves = io::curveFaceter(part);
    const TessellateResult result = tessellate(scene, options);
    ASSERT_TRUE(result.exact);
    EXPECT_GT(result.facetDeviation, 0.0);
    EXPECT_LE(result.facetDeviation, 0.5 * options.tolerance);
    EXPECT_TRUE(result.toleranceMet);
    EXPECT_LE(result.error.max, options.tolerance);
    EXPECT_LE(result.backError.max, options.tolerance);
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
    EXPECT_NEAR(six / 6.0, exact, area * options.tolerance);
    // Far fewer triangles than a grid at that tolerance needs (its cells are ~T): the chord rule
    // gives the sphere ~60 fragments and 30 rings.
    EXPECT_LT(result.mesh.triangles.size(), 20'000u);
}

}  // namespace
}  // namespace csg
