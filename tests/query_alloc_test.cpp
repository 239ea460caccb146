// No heap allocation per ray in the steady state: a counting operator new watches the queries.
#include <gtest/gtest.h>

#include "csg/Scene.h"
#include "primitives/Polyhedron.h"
#include "tests/CountingNew.h"
#include "tests/TreeOracle.h"

using csg::testing::allocations;

namespace csg {
namespace {

TEST(QueryAllocation, SteadyStateQueriesAllocateNothing) {
    std::mt19937_64 rng(9);
    std::vector<NodePtr> parts;
    for (int i = 0; i < 200; ++i) parts.push_back(testing::randomTree(rng, 4));
    const Scene scene = Scene::compile(uniteAll(parts));
    QueryContext ctx;
    std::uniform_real_distribution<double> u(-1, 1);
    auto rayAt = [&](int i) {
        std::mt19937_64 r(i);
        return Ray{{8 * u(r), 8 * u(r), 8 * u(r)}, {u(r), u(r), u(r)}, 0.0, 50.0};
    };
    auto runAll = [&] {
        size_t spans = 0;
        for (int i = 0; i < 5000; ++i) {
            const Ray ray = rayAt(i);
            spans += scene.spans(ray, ctx).size();
            spans += scene.closest(ray, ctx).has_value();
            spans += scene.occluded(ray, ctx);
        }
        return spans;
    };
    const size_t warm = runAll();  // grows the context's scratch to its high-water mark
    const long before = allocations.load();
    const size_t again = runAll();
    EXPECT_EQ(allocations.load() - before, 0);
    EXPECT_EQ(warm, again);
    EXPECT_GT(warm, 1000u);  // the rays did meet the scene
}

// Every --accel structure, the grids' mailbox included: after the first rays (which size the
// context's stamps to the scene), no query allocates.
TEST(QueryAllocation, EveryStructureAllocatesNothing) {
    std::mt19937_64 rng(10);
    std::vector<NodePtr> parts;
    for (int i = 0; i < 300; ++i)
        parts.push_back(transformed(glm::translate(Mat4(1.0), Vec3(i % 10, (i / 10) % 10, i / 100)),
                                    testing::randomTree(rng, 2)));
    const NodePtr tree = uniteAll(parts);
    for (Accel accel :
         {Accel::Sah, Accel::Median, Accel::GoldsmithSalmon, Accel::Grid, Accel::NonUniformGrid}) {
        const Scene scene = Scene::compile(tree, {.accel = accel});
        QueryContext ctx;
        auto runAll = [&] {
            size_t found = 0;
            for (int i = 0; i < 2000; ++i) {
                std::mt19937_64 r(i);
                std::uniform_real_distribution<double> u(-1, 1);
                const Ray ray{{20 * u(r), 20 * u(r), 20 * u(r)}, {u(r), u(r), u(r)}, 0.0, 80.0};
                found += scene.spans(ray, ctx).size();
                found += scene.closest(ray, ctx).has_value();
                found += scene.occluded(ray, ctx);
            }
            return found;
        };
        const size_t warm = runAll();
        const long before = allocations.load();
        const size_t again = runAll();
        EXPECT_EQ(allocations.load() - before, 0) << accelName(accel);
        EXPECT_EQ(warm, again);
    }
}

// Meshes keep their crossings in per-thread scratch: after the first rays, none allocates, also
// on lines of more spans than LocalSpans holds (a comb of 40 slabs) and when asked for normals.
TEST(QueryAllocation, MeshQueriesAllocateNothing) {
    std::vector<Vec3> points;
    PolygonFaces faces;
    for (int slab = 0; slab < 40; ++slab) {
        const uint32_t base = uint32_t(points.size());
        for (int corner = 0; corner < 8; ++corner)
            points.emplace_back(1.5 * slab + (corner & 1), (corner >> 1) & 1, corner >> 2);
        for (const auto& quad : {std::array<uint32_t, 4>{0, 2, 3, 1},
                                 {4, 5, 7, 6},
                                 {0, 1, 5, 4},
                                 {2, 6, 7, 3},
                                 {0, 4, 6, 2},
                                 {1, 3, 7, 5}}) {
            for (uint32_t k : quad) faces.corners.push_back(base + k);
            faces.closeFace();
        }
    }
    const Polyhedron comb = Polyhedron::make(points, faces);
    ASSERT_EQ(comb.invalidReason(), nullptr);
    const Scene scene = Scene::compile(
        unite(leaf(comb), transformed(glm::translate(Mat4(1.0), Vec3(0, 3, 0)), leaf(comb))));
    QueryContext ctx;
    std::uniform_real_distribution<double> u(0, 1);
    auto runAll = [&] {
        size_t found = 0;
        for (int i = 0; i < 2000; ++i) {
            std::mt19937_64 r(i);
            // Along the comb (over 32 spans) or across it, from outside its box.
            const Ray ray = i % 2 ? Ray{{-1, 4 * u(r), u(r)}, {1, 0.01 * u(r), 0}, 0.0, 100.0}
                                  : Ray{{60 * u(r), -1, u(r)}, {u(r), 1, 0.1}, 0.0, 100.0};
            found += scene.spans(ray, ctx).size();
            if (const auto hit = scene.closest(ray, ctx)) {
                found += glm::length(scene.surface(ray, *hit).normal) > 0.5;
            }
            found += scene.occluded(ray, ctx);
        }
        return found;
    };
    const size_t warm = runAll();
    const long before = allocations.load();
    const size_t again = runAll();
    EXPECT_EQ(allocations.load() - before, 0);
    EXPECT_EQ(warm, again);
    EXPECT_GT(warm, 1000u);
}

}  // namespace
}  // namespace csg
