// The adaptive octree of dual contouring (csg/mesh/DualContour.h): flat blocks merge into one
// vertex each, the mesh stays a closed oriented manifold, exact on boxes, and the same for any
// thread count.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "csg/mesh/DualContour.h"
#include "csg/mesh/MeshCheck.h"
#include "csg/mesh/Tessellate.h"
#include "tests/BoxPlanes.h"
#include "tests/MeshTopologyText.h"
#include "tests/SeededRng.h"

namespace csg {
namespace {

// A slab of 80 x 80 x 20 cells. The uniform contour puts a vertex in each of the ~2 x 80^2 +
// 4 x 80 x 20 cells its faces cross (~19 200) and two triangles per crossed edge (~38 000
// triangles). The octree keeps fine cells only along the 12 edges (a block holding a crease
// never merges, and the blocks next to one are at most as wide as their distance to it), so
// each face of n x n cells keeps a band of ~O(n) cells plus ~n^2 / 16^2 blocks of ~4 triangles
// each: well under a quarter of the uniform count at n = 80. The planes stay exact: every
// vertex on a face plane, every corner of the box a vertex, the volume exact.
TEST(Octree, SlabFacesMergeAndStayExact) {
    const Vec3 lo(0.1, 0.2, 0.3), hi(4.1, 4.2, 1.3);
    const Scene scene = Scene::compile(leaf(Box{lo, hi}));
    const double h = 0.05;
    DualContourStats uniformStats, octreeStats;
    const TriangleMesh uniform = tessellateAt(scene, h, 0, nullptr, &uniformStats);
    const TriangleMesh octree = tessellateAt(scene, h, 0, nullptr, &octreeStats, nullptr, 0.25 * h);
    EXPECT_EQ(uniformStats.octreeLeaves, 0u);
    EXPECT_GT(octreeStats.octreeLeaves, 0u);
    EXPECT_FALSE(octreeStats.octreeFallback);
    EXPECT_LT(octree.triangles.size() * 4, uniform.triangles.size())
        << octree.triangles.size() << " vs " << uniform.triangles.size();

    EXPECT_TRUE(checkTopology(octree).closedManifold());
    EXPECT_NEAR(signedVolume(octree), 4.0 * 4.0 * 1.0, 1e-9);
    for (const Vec3& p : octree.positions) ASSERT_LT(offBoxSurface(p, lo, hi), 1e-9) << p.x;
    for (int corner = 0; corner < 8; ++corner) {
        const Vec3 c{corner & 1 ? hi.x : lo.x, corner & 2 ? hi.y : lo.y, corner & 4 ? hi.z : lo.z};
        double nearest = INFINITY;
        for (const Vec3& p : octree.positions) nearest = std::min(nearest, glm::length(p - c));
        EXPECT_LT(nearest, 1e-9) << "corner " << corner;
    }
}

// Random unions and differences of spheres, boxes and cylinders at coarse and fine spacings,
// merged with a loose flatness (half a cell) so many blocks merge next to curved and creased
// parts: every mesh is a closed oriented manifold by the merging itself, not by the uniform
// fallback, and the merged mesh is smaller than the uniform one.
NodePtr randomPart(testing::Rng& rng) {
    std::vector<NodePtr> parts;
    for (int i = 0; i < 6; ++i) {
        const Vec3 at = rng.inBox(Vec3(-1.0), Vec3(1.0));
        const Vec3 axis = rng.unit();
        const double angle = rng.uniform(-std::numbers::pi, std::numbers::pi);
        const Mat4 place = glm::rotate(glm::translate(Mat4(1.0), at), angle, axis);
        if (i % 3 == 2) {
            const Vec3 half = rng.inBox(Vec3(0.1), Vec3(0.8));
            parts.push_back(transformed(place, leaf(Box{-half, half})));
        } else if (i % 3 == 1) {
            const double height = rng.uniform(0.3, 1.5);
            const double radius = rng.uniform(0.1, 0.6);
            parts.push_back(transformed(place, leaf(Cylinder{height, radius, radius})));
        } else {
            parts.push_back(transformed(place, leaf(Sphere{rng.uniform(0.1, 0.7)})));
        }
    }
    return subtract(uniteAll({parts[0], parts[1], parts[2], parts[3]}), unite(parts[4], parts[5]));
}

TEST(Octree, RandomCsgIsAlwaysManifold) {
    testing::Rng rng(23);
    uint64_t merged = 0, octreeTriangles = 0, uniformTriangles = 0;
    for (int trial = 0; trial < 40; ++trial) {
        const Scene scene = Scene::compile(randomPart(rng));
        const double h = 0.03 + 0.12 * (trial % 4) / 3.0;
        DualContourStats stats;
        const TriangleMesh mesh = tessellateAt(scene, h, 0, nullptr, &stats, nullptr, 0.5 * h);
        const MeshTopology t = checkTopology(mesh);
        ASSERT_TRUE(t.closedManifold()) << "trial " << trial << " h " << h << ": " << describe(t);
        if (!mesh.empty()) {
            EXPECT_GT(signedVolume(mesh), 0.0) << trial;
        }
        // A merge that broke the mesh falls back to the uniform contour, which the topology
        // check above cannot see: this is what fails when merging goes wrong.
        EXPECT_FALSE(stats.octreeFallback) << "trial " << trial << " h " << h;
        merged += stats.octreeLeaves;
        octreeTriangles += mesh.triangles.size();
        uniformTriangles += tessellateAt(scene, h, 0).triangles.size();
    }
    EXPECT_GT(merged, 1000u);
    EXPECT_LT(octreeTriangles, uniformTriangles);
}

// Issue 7's "no self-intersections" for the uniform contour. These parts have cells crossed by
// two or three sheets (walls thinner than a cell, whose edges keep only their first crossing),
// sheet vertices clamped a hair inside a face with their fans folded flat onto it, and
// ambiguous faces whose two curves bend over creases: before DualContour's unfolding step and
// its ambiguous-face rule (bendsTowardCorner), 22 of the 40 meshes crossed themselves (5 with
// the unfolding alone, all at ambiguous faces). No cell may be left folded at its mass points
// either (DualContourStats::unfoldFailures).
TEST(Octree, UniformRandomCsgHasNoSelfIntersections) {
    testing::Rng rng(23);
    uint64_t unfolded = 0;
    for (int trial = 0; trial < 40; ++trial) {
        const Scene scene = Scene::compile(randomPart(rng));
        const double h = 0.03 + 0.12 * (trial % 4) / 3.0;
        DualContourStats stats;
        const TriangleMesh mesh = tessellateAt(scene, h, 0, nullptr, &stats);
        const SelfIntersections s = findSelfIntersections(mesh);
        EXPECT_EQ(s.pairs, 0u) << "trial " << trial << " h " << h << ": " << s.coplanarPairs
                               << " coplanar, one at " << s.example.x << "," << s.example.y << ","
                               << s.example.z;
        EXPECT_EQ(stats.unfoldFailures, 0u) << "trial " << trial;
        unfolded += stats.unfoldedCells;
    }
    // The unfolding had work to do (so the zero above is its result, not these parts' luck).
    EXPECT_GT(unfolded, 20u);
}

// The same for the octree. Its fans folded slivers flat onto their neighbours next to merged
// blocks (coplanar overlaps: 29 of these 40 meshes before the unfolding; 5 with the unfolding
// of fine cells alone): a block whose vertex's triangles cross or overlap, or that leaves a
// fine cell next to it folded at its mass points, is not merged in the next round. The merging
// itself must make the clean mesh, not the uniform fallback.
TEST(Octree, OctreeRandomCsgHasNoSelfIntersections) {
    testing::Rng rng(23);
    for (int trial = 0; trial < 40; ++trial) {
        const Scene scene = Scene::compile(randomPart(rng));
        const double h = 0.03 + 0.12 * (trial % 4) / 3.0;
        DualContourStats stats;
        const SelfIntersections s =
            findSelfIntersections(tessellateAt(scene, h, 0, nullptr, &stats, nullptr, 0.5 * h));
        EXPECT_EQ(s.pairs, 0u) << "trial " << trial << " h " << h << ": " << s.coplanarPairs
                               << " coplanar, one at " << s.example.x << "," << s.example.y << ","
                               << s.example.z;
        EXPECT_FALSE(stats.octreeFallback) << "trial " << trial;
    }
}

// Top blocks are merged on any worker, but numbered in block order, and the unfolding checks
// cells on any worker but moves them in order: the same mesh, bit for bit.
TEST(Octree, SameMeshForAnyThreadCount) {
    testing::Rng rng(5);
    uint64_t unfolded = 0;
    for (int trial = 0; trial < 3; ++trial) {
        const Scene scene = Scene::compile(randomPart(rng));
        const double h = 0.03;
        DualContourStats one, two;
        const TriangleMesh a = tessellateAt(scene, h, 1, nullptr, &one, nullptr, 0.25 * h);
        const TriangleMesh b = tessellateAt(scene, h, 2, nullptr, &two, nullptr, 0.25 * h);
        EXPECT_GT(one.octreeLeaves, 0u);
        EXPECT_EQ(one.octreeLeaves, two.octreeLeaves);
        EXPECT_EQ(one.unfoldedCells, two.unfoldedCells);
        unfolded += one.unfoldedCells;
        ASSERT_EQ(a.positions.size(), b.positions.size());
        ASSERT_EQ(a.triangles.size(), b.triangles.size());
        for (size_t i = 0; i < a.positions.size(); ++i) ASSERT_EQ(a.positions[i], b.positions[i]);
        for (size_t i = 0; i < a.triangles.size(); ++i) ASSERT_EQ(a.triangles[i], b.triangles[i]);
    }
    // The unfolding moved cells here (22 at this writing), so its moves are among what agrees.
    EXPECT_GT(unfolded, 0u);
}

}  // namespace
}  // namespace csg
