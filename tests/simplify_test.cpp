// Simplification of a big grid mesh in blocks (csg/mesh/Simplify.h): slabs decimated on their own
// workers with their borders locked, then one pass over the whole mesh, must keep the rules a
// one-piece run keeps. The small-mesh tests of Simplify are in mesh_test.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <map>
#include <optional>
#include <set>

#include "csg/Tree.h"
#include "csg/mesh/MeshCheck.h"
#include "csg/mesh/MeshDistance.h"
#include "csg/mesh/Simplify.h"
#include "csg/mesh/Tessellate.h"
#include "csg/mesh/TriangleBvh.h"

namespace csg {
namespace {

// Bit-exact key of a position (kept vertices are input vertices, not near them).
std::array<uint64_t, 3> key(const Vec3& p) {
    std::array<uint64_t, 3> k{};
    for (int a = 0; a < 3; ++a) std::memcpy(&k[size_t(a)], &p[a], sizeof(double));
    return k;
}

// A sphere with a box through it in another material: flat faces that coarsen, a curved
// surface that coarsens less, creases, and a material border, in ~400k grid triangles (two
// slabs, on one or two workers).
class SimplifyBlocks : public ::testing::Test {
protected:
    static void SetUpTestSuite() {
        scene_ = new Scene(Scene::compile(
            unite(leaf(Sphere{1.0}, Tags{.material = 1}),
                  leaf(Box{Vec3(0.0, -0.5, -0.45), Vec3(1.3, 0.55, 0.5)}, Tags{.material = 2}))));
        grid_ = new TriangleMesh(tessellateAt(*scene_, 0.012, 2));
    }
    static void TearDownTestSuite() {
        delete grid_;
        delete scene_;
    }
    static Scene* scene_;
    static TriangleMesh* grid_;
};
Scene* SimplifyBlocks::scene_ = nullptr;
TriangleMesh* SimplifyBlocks::grid_ = nullptr;

TEST_F(SimplifyBlocks, ManifoldWithinBudgetAndBordersKept) {
    const TriangleMesh& grid = *grid_;
    ASSERT_GT(grid.triangles.size(), 300'000u) << "too small for two blocks";
    ASSERT_TRUE(checkTopology(grid).closedManifold());
    DistanceOptions measure;
    measure.reach = 0.05;
    measure.goodEnough = 1e-3;
    const double gridError = meshToSurface(*scene_, grid, measure).max;
    ASSERT_LT(gridError, 2e-3);
    const double budget = 2e-3;

    // Input vertices where two materials meet, and every input position with its normal.
    std::vector<uint32_t> firstMaterial(grid.positions.size(), UINT32_MAX);
    std::set<std::array<uint64_t, 3>> border;
    std::map<std::array<uint64_t, 3>, Vec3> normalAt;
    for (size_t t = 0; t < grid.triangles.size(); ++t)
        for (const uint32_t v : grid.triangles[t]) {
            if (firstMaterial[v] == UINT32_MAX)
                firstMaterial[v] = grid.triangleMaterial[t];
            else if (firstMaterial[v] != grid.triangleMaterial[t])
                border.insert(key(grid.positions[v]));
        }
    for (size_t v = 0; v < grid.positions.size(); ++v)
        normalAt.emplace(key(grid.positions[v]), grid.normals[v]);
    ASSERT_GT(border.size(), 100u);

    std::optional<TriangleMesh> first;
    for (const int threads : {1, 2}) {
        SCOPED_TRACE(threads);
        SimplifyStats stats;
        const TriangleMesh coarse = simplify(grid, budget, &stats, threads);
        EXPECT_TRUE(stats.built);
        EXPECT_GE(stats.blocks, 2);
        EXPECT_EQ(stats.trianglesAfter, coarse.triangles.size());
        EXPECT_TRUE(checkTopology(coarse).closedManifold());
        EXPECT_LT(coarse.triangles.size(), grid.triangles.size() / 5);
        // The pass over the whole mesh coarsens the strips the blocks' locks held back.
        EXPECT_LT(coarse.triangles.size(), stats.trianglesAfterBlocks);
        // The blocks depend on the mesh, not on the workers: the same mesh either way.
        if (first) {
            EXPECT_EQ(coarse.positions, first->positions);
            EXPECT_EQ(coarse.triangles, first->triangles);
            EXPECT_EQ(coarse.triangleMaterial, first->triangleMaterial);
        } else {
            first = coarse;
        }

        // Kept vertices are input vertices, bit for bit, with their normals; every material
        // border vertex is kept.
        ASSERT_EQ(coarse.normals.size(), coarse.positions.size());
        std::set<std::array<uint64_t, 3>> kept;
        for (size_t v = 0; v < coarse.positions.size(); ++v) {
            const auto k = key(coarse.positions[v]);
            const auto it = normalAt.find(k);
            ASSERT_NE(it, normalAt.end()) << "vertex " << v << " is not an input vertex";
            ASSERT_EQ(coarse.normals[v], it->second);
            kept.insert(k);
        }
        for (const auto& k : border) ASSERT_TRUE(kept.count(k)) << "a material border vertex went";
        ASSERT_EQ(coarse.triangleMaterial.size(), coarse.triangles.size());

        // Within the budget of the exact surface, both ways (what tessellate() checks).
        const double to = meshToSurface(*scene_, coarse, measure).max;
        const TriangleBvh bvh(coarse);
        const double back = surfaceToMesh(*scene_, bvh, 64, measure).max;
        EXPECT_LE(to, gridError + budget);
        EXPECT_LE(back, gridError + budget);
    }
}

}  // namespace
}  // namespace csg
