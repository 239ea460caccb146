// Hand-derived spans for the cases that break naive CSG: coincident faces, tangent rays,
// far-away and tiny parts, rays starting inside, rays through a cone's apex.
#include <gtest/gtest.h>

#include "csg/Scene.h"

namespace csg {
namespace {

Mat4 translation(const Vec3& v) {
    return glm::translate(Mat4(1.0), v);
}

std::vector<Span> spansOf(const NodePtr& tree, const Ray& ray) {
    const Scene scene = Scene::compile(tree);
    QueryContext ctx;
    const auto s = scene.spans(ray, ctx);
    return {s.begin(), s.end()};
}

TEST(Exact, BoxMinusACopySharingFacesLeavesOnlyTheUncutPart) {
    // A = [0,2]^3; B = [1,2] x [0,2] x [0,2] shares five of A's face planes.
    const NodePtr a = leaf(Box{Vec3(0), Vec3(2)}, {1, 0});
    const NodePtr b = leaf(Box{Vec3(1, 0, 0), Vec3(2)}, {2, 0});
    const auto alongX = spansOf(subtract(a, b), Ray{{-3, 1, 1}, {1, 0, 0}});
    ASSERT_EQ(alongX.size(), 1u);
    EXPECT_DOUBLE_EQ(alongX[0].in.t, 3.0);
    EXPECT_DOUBLE_EQ(alongX[0].out.t, 4.0);
    EXPECT_TRUE(alongX[0].out.flipped);  // the cut's face at x = 1 bounds the result
    // Along y through the cut region both boxes give the same span: nothing is left.
    EXPECT_TRUE(spansOf(subtract(a, b), Ray{{1.5, -3, 1}, {0, 1, 0}}).empty());
    // A minus itself is empty along any ray.
    EXPECT_TRUE(spansOf(subtract(a, a), Ray{{-3, 0.3, 1.7}, {1, 0.1, 0.05}}).empty());
}

TEST(Exact, FaceAdjacentBoxesUniteIntoOneSpanWithNoHitOnTheSharedFace) {
    // Unit boxes side by side, the second placed by a transform so its face's t is computed
    // in another frame; rays from far away make the two computations round differently.
    const NodePtr left = leaf(Box{Vec3(0), Vec3(1)}, {1, 0});
    const NodePtr right = transformed(translation({1, 0, 0}), leaf(Box{Vec3(0), Vec3(1)}, {2, 0}));
    for (double far : {3.0, 1e3, 1e6}) {
        const Ray ray{{-far, 0.5, 0.25}, {1, 1e-7, 2e-7}};
        const Scene scene = Scene::compile(unite(left, right));
        QueryContext ctx;
        const auto s = scene.spans(ray, ctx);
        ASSERT_EQ(s.size(), 1u) << "from " << far;
        EXPECT_EQ(s[0].in.leaf, 0u);
        EXPECT_EQ(s[0].out.leaf, 1u);
        EXPECT_NEAR(s[0].out.t - s[0].in.t, 2.0, 1e-9 * far);
        // A ray starting inside the left box meets the right box's far face first.
        const Ray inside{{0.5, 0.5, 0.5}, {1, 0, 0}};
        const std::optional<Hit> hit = scene.closest(inside, ctx);
        ASSERT_TRUE(hit);
        EXPECT_DOUBLE_EQ(hit->t, 1.5);
    }
}

TEST(Exact, TangentRaysOnSphereAndCylinderGiveNoSpan) {
    EXPECT_TRUE(spansOf(leaf(Sphere{1}), Ray{{-5, 1, 0}, {1, 0, 0}}).empty());
    EXPECT_TRUE(spansOf(leaf(Sphere{2}), Ray{{0, -7, 2}, {0, 3, 0}}).empty());
    EXPECT_TRUE(spansOf(leaf(Cylinder{2, 1, 1}), Ray{{-5, 1, 1}, {1, 0, 0}}).empty());
    // Grazing the rim of a cylinder's cap along the cap plane: an edge, not a volume.
    EXPECT_TRUE(spansOf(leaf(Cylinder{2, 1, 1}), Ray{{-5, 1, 2}, {1, 0, 0}}).empty());
    // Just inside the tangent, the span is short and real: 2 sqrt(1 - y^2).
    const double y = 1 - 1e-6;
    const auto s = spansOf(leaf(Sphere{1}), Ray{{-5, y, 0}, {1, 0, 0}});
    ASSERT_EQ(s.size(), 1u);
    EXPECT_NEAR(s[0].out.t - s[0].in.t, 2 * std::sqrt(1 - y * y), 1e-12);
}

TEST(Exact, FarAwayPartKeepsItsShape) {
    // A unit sphere 10^6 from the origin, seen from the origin: the span is its diameter.
    const Vec3 c(1e6, 1e6, 1e6);
    const auto s =
        spansOf(transformed(translation(c), leaf(Sphere{1})), Ray{{0, 0, 0}, glm::normalize(c)});
    ASSERT_EQ(s.size(), 1u);
    const double dist = glm::length(c);
    EXPECT_NEAR(s[0].in.t, dist - 1, 1e-9);
    EXPECT_NEAR(s[0].out.t, dist + 1, 1e-9);
    // A box of size 1 at 10^6 cut by a cylinder: the hole's walls are where they should be.
    const NodePtr part =
        transformed(translation({1e6, 0, 0}),
                    subtract(leaf(Box{Vec3(-1), Vec3(1)}),
                             transformed(translation({0, 0, -2}), leaf(Cylinder{4, 0.5, 0.5}))));
    // Along x at y = 0.3 the hole of radius 0.5 is a chord of half-length 0.4.
    const auto cut = spansOf(part, Ray{{0, 0.3, 0.25}, {1, 0, 0}});
    ASSERT_EQ(cut.size(), 2u);
    const double half = 0.4;
    EXPECT_NEAR(cut[0].out.t, 1e6 - half, 1e-9);
    EXPECT_NEAR(cut[1].in.t, 1e6 + half, 1e-9);
}

TEST(Exact, TinyPartScaledBy1eMinus6) {
    const Mat4 tiny = glm::scale(Mat4(1.0), Vec3(1e-6));
    const NodePtr part =
        transformed(tiny, subtract(leaf(Box{Vec3(-1), Vec3(1)}), leaf(Sphere{0.5})));
    // From 3 sizes away: ends at 2, 2.5, 3.5 and 4 micro-units, to 1e-9 of the part's size.
    const auto s = spansOf(part, Ray{{-3e-6, 0, 0}, {1, 0, 0}});
    ASSERT_EQ(s.size(), 2u);
    EXPECT_NEAR(s[0].in.t, 2e-6, 1e-15);
    EXPECT_NEAR(s[0].out.t, 2.5e-6, 1e-15);
    EXPECT_NEAR(s[1].in.t, 3.5e-6, 1e-15);
    EXPECT_NEAR(s[1].out.t, 4e-6, 1e-15);
    // And from 10^6 sizes away with a unit direction, the lengths still come out right.
    const auto far = spansOf(part, Ray{{-1, 0, 0}, {1, 0, 0}});
    ASSERT_EQ(far.size(), 2u);
    EXPECT_NEAR(far[0].out.t - far[0].in.t, 0.5e-6, 1e-15);
    EXPECT_NEAR(far[1].in.t - far[0].out.t, 1e-6, 1e-15);
}

TEST(Exact, RayStartingInsideBeginsWithAClipEnd) {
    const auto s = spansOf(leaf(Sphere{1}), Ray{{0, 0, 0}, {0, 0, 2}});
    ASSERT_EQ(s.size(), 1u);
    EXPECT_EQ(s[0].in.t, 0.0);
    EXPECT_FALSE(s[0].in.isSurface());
    EXPECT_DOUBLE_EQ(s[0].out.t, 0.5);  // |d| = 2: t is not a distance
    // A ray leaving the surface outward has nothing ahead of it.
    EXPECT_TRUE(spansOf(leaf(Sphere{1}), Ray{{0, 0, 1}, {0, 0, 1}}).empty());
}

TEST(Exact, UnboundedHalfSpaceSpansReachInfinity) {
    const NodePtr below = leaf(HalfSpace{Vec3(0, 0, 1), 0.0});
    const auto down = spansOf(below, Ray{{0, 0, 1}, {0, 0, -1}});
    ASSERT_EQ(down.size(), 1u);
    EXPECT_DOUBLE_EQ(down[0].in.t, 1.0);
    EXPECT_TRUE(down[0].in.isSurface());
    EXPECT_EQ(down[0].out.t, kInfinity);
    EXPECT_FALSE(down[0].out.isSurface());
    // Cut by a sphere, the half-space keeps its unbounded tail beyond the hole.
    const auto cut = spansOf(subtract(below, leaf(Sphere{1})), Ray{{0, 0, 5}, {0, 0, -1}});
    ASSERT_EQ(cut.size(), 1u);
    EXPECT_DOUBLE_EQ(cut[0].in.t, 6.0);
    EXPECT_TRUE(cut[0].in.flipped);
    EXPECT_EQ(cut[0].out.t, kInfinity);
}

TEST(Exact, RaysThroughAConeApex) {
    const NodePtr cone = leaf(Cylinder{1, 1, 0});  // apex at (0, 0, 1)
    const auto down = spansOf(cone, Ray{{0, 0, 3}, {0, 0, -1}});
    ASSERT_EQ(down.size(), 1u);
    EXPECT_NEAR(down[0].in.t, 2.0, 1e-12);
    EXPECT_DOUBLE_EQ(down[0].out.t, 3.0);
    // Horizontal through the apex: a single point, no volume.
    EXPECT_TRUE(spansOf(cone, Ray{{-3, 0, 1}, {1, 0, 0}}).empty());
    // Along a generator line: the line lies in the closed surface. Primitives report the
    // closed set, so this is the generator segment itself (t in [0, 1]), finite.
    const auto along = spansOf(cone, Ray{{-1, 0, 0}, {1, 0, 1}});
    ASSERT_EQ(along.size(), 1u);
    EXPECT_NEAR(along[0].in.t, 0.0, 1e-12);
    EXPECT_NEAR(along[0].out.t, 1.0, 1e-12);
    // The normal at the apex is defined: the axis, pointing away from the base.
    const Scene scene = Scene::compile(cone);
    QueryContext ctx;
    const Ray ray{{0, 0, 3}, {0, 0, -1}};
    const std::optional<Hit> hit = scene.closest(ray, ctx);
    ASSERT_TRUE(hit);
    const Vec3 n = scene.surface(ray, *hit).normal;
    EXPECT_TRUE(std::isfinite(n.x) && std::isfinite(n.y) && std::isfinite(n.z));
    EXPECT_NEAR(glm::length(n), 1.0, 1e-12);
}

}  // namespace
}  // namespace csg
