// No heap allocation per ray through Bezier patch sets: a counting operator new watches the
// queries (and the normal at each hit) on the Utah teapot, for each intersection method.
#include <gtest/gtest.h>

#include <cstdio>
#include <random>

#include "csg/Scene.h"
#include "io/Evaluate.h"
#include "tests/CountingNew.h"

using csg::testing::allocations;

namespace csg {
namespace {

// "groebner" and "groebner-exact" are not here: their exact pass holds GMP numbers, on the heap
// (primitives/patch/GroebnerExact.h); "groebner" is allocation-free only where its float pass
// is certified. "groebner-float" is the float pass.
TEST(PatchAllocation, TeapotQueriesAllocateNothing) {
    for (const char* method : {"clip", "newton", "groebner-float", "resultant"}) {
        io::EvaluateOptions options;
        options.defines = {{"method", std::string("\"") + method + "\""}};
        const io::EvaluateResult r =
            io::evaluateFile(std::string(CSGRAY_SAMPLES) + "/teapot.scad", options);
        ASSERT_TRUE(r.ok()) << method;
        const Scene scene = Scene::compile(r.model->root);
        QueryContext ctx;
        auto runAll = [&] {
            std::mt19937_64 random(3);
            std::uniform_real_distribution<double> u(-1, 1);
            size_t hits = 0;
            for (int i = 0; i < 300; ++i) {
                const Vec3 o(8 * u(random), 8 * u(random), 8 * u(random));
                const Vec3 target(3 * u(random), 2 * u(random), 1.6 + 1.6 * u(random));
                const Ray ray{o, target - o, 0.0, kInfinity};
                hits += scene.spans(ray, ctx).size();
                if (const auto hit = scene.closest(ray, ctx)) {
                    ++hits;
                    hits += glm::length(scene.surface(ray, *hit).normal) > 0.5;
                }
                hits += scene.occluded(ray, ctx);
            }
            return hits;
        };
        const size_t warm = runAll();
        const long before = allocations.load();
        const size_t again = runAll();
        const long count = allocations.load() - before;
        std::printf("%-10s %zu span ends and hits, %ld allocations\n", method, again, count);
        EXPECT_EQ(warm, again) << method;
        EXPECT_GT(warm, 100u) << method;
        EXPECT_EQ(count, 0) << method;
    }
}

}  // namespace
}  // namespace csg
