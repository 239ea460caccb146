// No heap allocation per ray in the steady state: a counting operator new watches the queries.
#include <gtest/gtest.h>

#include "csg/Scene.h"
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

}  // namespace
}  // namespace csg
