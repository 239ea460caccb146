// Simplification of a big grid mesh in blocks (csg/mesh/Simplify.h): slabs decimated on their own
// workers with their borders locked, then one pass over the whole mesh, must keep the rules a
// one-piece run keeps; and no collapse may make triangles cross. The small-mesh tests of
// Simplify are in mesh_test.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>
#include <optional>
#include <set>
#include <utility>

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
        EXPECT_EQ(findSelfIntersections(coarse).pairs, 0u);
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

// A sphere of radius r about the origin: an icosahedron subdivided `levels` times, vertices
// pushed onto the sphere, appended to mesh; facing outward, or inward when `inward` (the inner
// wall of a hollow ball).
void appendIcosphere(TriangleMesh& mesh, double r, int levels, bool inward) {
    const double t = (1.0 + std::sqrt(5.0)) / 2.0;
    std::vector<Vec3> p = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0},
                           {0, -1, t}, {0, 1, t}, {0, -1, -t}, {0, 1, -t},
                           {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
    std::vector<std::array<uint32_t, 3>> f = {
        {0, 11, 5},  {0, 5, 1},  {0, 1, 7},  {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
        {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
        {3, 8, 9},   {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
    for (Vec3& q : p) q = glm::normalize(q);
    for (int level = 0; level < levels; ++level) {
        std::map<std::pair<uint32_t, uint32_t>, uint32_t> middle;
        auto mid = [&](uint32_t a, uint32_t b) {
            const auto key = std::minmax(a, b);
            const auto [it, added] = middle.emplace(key, uint32_t(p.size()));
            if (added) p.push_back(glm::normalize(p[a] + p[b]));
            return it->second;
        };
        std::vector<std::array<uint32_t, 3>> next;
        for (const auto& [a, b, c] : f) {
            const uint32_t ab = mid(a, b), bc = mid(b, c), ca = mid(c, a);
            next.insert(next.end(), {{a, ab, ca}, {b, bc, ab}, {c, ca, bc}, {ab, bc, ca}});
        }
        f.swap(next);
    }
    const auto base = uint32_t(mesh.positions.size());
    for (const Vec3& q : p) mesh.positions.push_back(r * q);
    for (const auto& [a, b, c] : f)
        mesh.triangles.push_back(inward ? std::array<uint32_t, 3>{base + a, base + c, base + b}
                                        : std::array<uint32_t, 3>{base + a, base + b, base + c});
}

// A hollow ball whose wall (0.005) is thinner than the budget (0.02): a chord of the outer wall
// that the deviation rules allow (its sagitta within the budget) dips through the inner wall,
// which no rule that looks at the outer wall's own fans sees. The inner wall's chords bend away.
TEST(Simplify, CollapsesDoNotCrossAThinWall) {
    TriangleMesh shell;
    appendIcosphere(shell, 1.0, 4, false);
    appendIcosphere(shell, 0.995, 4, true);
    ASSERT_TRUE(checkTopology(shell).closedManifold());
    ASSERT_EQ(findSelfIntersections(shell).pairs, 0u);
    const double budget = 0.02;

    // Unchecked, the outer wall crosses the inner one (what the test is about).
    SimplifyStats unchecked;
    const TriangleMesh crossing = simplify(shell, budget, &unchecked, 1, false);
    EXPECT_GT(findSelfIntersections(crossing).pairs, 0u)
        << "the thin wall no longer tests anything";
    EXPECT_EQ(unchecked.refusedCrossing, 0u);

    SimplifyStats stats;
    const TriangleMesh coarse = simplify(shell, budget, &stats, 1);
    EXPECT_TRUE(checkTopology(coarse).closedManifold());
    const SelfIntersections x = findSelfIntersections(coarse);
    EXPECT_EQ(x.pairs, 0u) << x.coplanarPairs << " coplanar, one at " << x.example.x << ","
                           << x.example.y << "," << x.example.z;
    EXPECT_GT(stats.refusedCrossing, 0u);
    // Refusing collapses at the wall does not stop the coarsening elsewhere.
    EXPECT_LT(coarse.triangles.size(), shell.triangles.size() / 2);
}

// tessellate() coarsens a grid mesh only up to simplifyMaxTriangles (export's default: a
// million; --simplify lifts it): above it the grid's mesh is kept as it is and the result says
// so; with no cap the same mesh is coarsened.
TEST(Simplify, SkippedAboveTheTriangleCap) {
    const Scene scene = Scene::compile(leaf(Sphere{1.0}));
    TessellateOptions options;
    options.tolerance = 0.01;
    options.threads = 2;
    options.simplifyMaxTriangles = 1000;  // below the grid mesh of this sphere
    const TessellateResult capped = tessellate(scene, options);
    ASSERT_GT(capped.gridTriangles, 1000u);
    EXPECT_TRUE(capped.simplifySkipped);
    EXPECT_FALSE(capped.simplified);
    EXPECT_EQ(capped.mesh.triangles.size(), capped.gridTriangles);

    options.simplifyMaxTriangles = 0;  // no cap
    const TessellateResult free = tessellate(scene, options);
    EXPECT_FALSE(free.simplifySkipped);
    EXPECT_TRUE(free.simplified);
    EXPECT_EQ(free.gridTriangles, capped.gridTriangles);
    EXPECT_LT(free.mesh.triangles.size(), free.gridTriangles);
}

}  // namespace
}  // namespace csg
