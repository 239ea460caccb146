// Volumes by span integration against analytic volumes.
#include <gtest/gtest.h>

#include <numbers>

#include "csg/Volume.h"

namespace csg {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr int kResolution = 512;

double relativeError(const NodePtr& tree, double exact) {
    return std::abs(volume(Scene::compile(tree), kResolution) - exact) / exact;
}

TEST(Volume, Sphere) {
    EXPECT_LT(relativeError(leaf(Sphere{1.5}), 4.0 / 3 * kPi * 3.375), 1e-3);
}

TEST(Volume, BoxMinusSphere) {
    const NodePtr part = subtract(leaf(Box{Vec3(-1), Vec3(1)}), leaf(Sphere{0.8}));
    EXPECT_LT(relativeError(part, 8.0 - 4.0 / 3 * kPi * 0.512), 1e-3);
}

TEST(Volume, CylinderIntersectCone) {
    // Cylinder r = 1, h = 2 and cone r1 = 2, r2 = 0, h = 2: radius min(1, 2 - z), so the volume
    // is pi (z in [0,1]) + integral_1^2 pi (2 - z)^2 dz = pi + pi / 3.
    const NodePtr part = intersect(leaf(Cylinder{2, 1, 1}), leaf(Cylinder{2, 2, 0}));
    EXPECT_LT(relativeError(part, 4.0 / 3 * kPi), 1e-3);
}

TEST(Volume, RotatedPartHasTheSameVolume) {
    const Mat4 r = glm::rotate(Mat4(1.0), 0.7, glm::normalize(Vec3(1, 2, 3)));
    EXPECT_LT(relativeError(transformed(r, leaf(Cylinder{2, 1, 1})), 2 * kPi), 1e-3);
}

// Rows run on any number of threads and are added in row order: the same double for each.
TEST(Volume, TheSameForAnyThreadCount) {
    const Scene scene = Scene::compile(subtract(leaf(Box{Vec3(-1), Vec3(1)}), leaf(Sphere{0.8})));
    const double one = volume(scene, 256, 1);
    EXPECT_GT(one, 0.0);
    for (const int threads : {2, 3, 7}) EXPECT_EQ(volume(scene, 256, threads), one) << threads;
}

TEST(Volume, EmptySceneHasZeroVolume) {
    EXPECT_EQ(volume(Scene::compile(nullptr), 16), 0.0);
    EXPECT_EQ(volume(Scene::compile(subtract(leaf(Sphere{1}), leaf(Sphere{2}))), 16), 0.0);
}

}  // namespace
}  // namespace csg
