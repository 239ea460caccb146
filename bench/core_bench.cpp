// Rays per second of the two whole-scene queries, closest and spans, on one sphere, the
// 1000-part emblem grid and sphere layers of 10^3 .. 10^6 spheres; plus compile time per size.
// Benchmark names are <query>/<scene>[/<size>], so --benchmark_filter picks subsets:
//   core_bench --benchmark_filter='closest/'          every closest benchmark
//   core_bench --benchmark_filter='sphere_layer/1000$' the smallest layer only
// Counters: visits/ray and prims/ray are QueryStats::nodeVisits and ::primitiveTests per ray
// (averaged over every ray of the run); the BVH should make them grow as log n on the layers.
#include <benchmark/benchmark.h>

#include <optional>
#include <string>
#include <vector>

#include "bench/BenchScenes.h"

namespace csg::bench {
namespace {

constexpr size_t kLayerSizes[] = {1'000, 10'000, 100'000, 1'000'000};

// Counters every query benchmark reports, from the context's work counts and the scene cache.
void reportWork(benchmark::State& state, const BenchScene& scene, const QueryStats& stats) {
    const double rays = static_cast<double>(stats.rays);
    state.SetItemsProcessed(static_cast<int64_t>(stats.rays));
    state.counters["visits/ray"] = static_cast<double>(stats.nodeVisits) / rays;
    state.counters["prims/ray"] = static_cast<double>(stats.primitiveTests) / rays;
    state.counters["leaves"] = static_cast<double>(scene.leafCount);
    // Measured once per process, when the scene entered the cache.
    state.counters["compile_ms"] = 1e3 * scene.compileSeconds;
}

// Every ray of the scene through `query`, which returns a count of what the ray found (hits,
// spans); reports the work counters and that count per ray as counter `perRay`.
template <class Query>
void queryBenchmark(benchmark::State& state, const std::string& sceneKey, const char* perRay,
                    Query query) {
    const BenchScene& scene = cachedScene(sceneKey);
    QueryContext context;
    size_t found = 0;
    for (auto _ : state)
        for (const Ray& ray : scene.rays) found += query(scene.scene, ray, context);
    reportWork(state, scene, context.stats);
    state.counters[perRay] = static_cast<double>(found) / static_cast<double>(context.stats.rays);
}

void closestBenchmark(benchmark::State& state, const std::string& sceneKey) {
    queryBenchmark(state, sceneKey, "hits/ray",
                   [](const Scene& scene, const Ray& ray, QueryContext& context) {
                       const std::optional<Hit> hit = scene.closest(ray, context);
                       benchmark::DoNotOptimize(hit);
                       return size_t(hit.has_value());
                   });
}

void spansBenchmark(benchmark::State& state, const std::string& sceneKey) {
    queryBenchmark(state, sceneKey, "spans/ray",
                   [](const Scene& scene, const Ray& ray, QueryContext& context) {
                       const std::span<const Span> spans = scene.spans(ray, context);
                       benchmark::DoNotOptimize(spans.data());
                       return spans.size();
                   });
}

// Scene::compile alone: the tree is built before the timed loop (once per repetition), and
// each compiled scene is destroyed with the timer paused. Its CPU time is the process's: a large
// SAH build runs on several threads (BvhBuildOptions::threads).
void compileBenchmark(benchmark::State& state, const NodePtr& tree) {
    std::optional<Scene> scene;
    size_t leafCount = 0;
    for (auto _ : state) {
        scene = Scene::compile(tree);
        state.PauseTiming();
        leafCount = scene->leafCount();
        scene.reset();
        state.ResumeTiming();
    }
    state.counters["leaves"] = static_cast<double>(leafCount);
}

void registerAll() {
    // The benchmark's name is its query and its scene cache key.
    std::vector<std::string> sceneKeys = {"sphere", "emblem_grid"};
    for (size_t n : kLayerSizes) sceneKeys.push_back("sphere_layer/" + std::to_string(n));
    for (const std::string& key : sceneKeys)
        benchmark::RegisterBenchmark(("closest/" + key).c_str(), closestBenchmark, key);
    for (const std::string& key : sceneKeys)
        benchmark::RegisterBenchmark(("spans/" + key).c_str(), spansBenchmark, key);
    // The layers again through a 0.4-degree view: the same BVH with a small working set, which
    // separates the cost of the visits from the cost of the memory they touch.
    for (size_t n : kLayerSizes) {
        const std::string key = "sphere_layer_narrow/" + std::to_string(n);
        benchmark::RegisterBenchmark(("closest/" + key).c_str(), closestBenchmark, key);
    }
    benchmark::RegisterBenchmark(
        "compile/emblem_grid",
        [](benchmark::State& state) { compileBenchmark(state, emblemGridTree()); })
        ->Unit(benchmark::kMillisecond)
        ->MeasureProcessCPUTime();
    for (size_t n : kLayerSizes) {
        const std::string name = "compile/sphere_layer/" + std::to_string(n);
        benchmark::RegisterBenchmark(
            name.c_str(),
            [n](benchmark::State& state) { compileBenchmark(state, sphereLayerTree(n)); })
            ->Unit(benchmark::kMillisecond)
            ->MeasureProcessCPUTime();
    }
}

}  // namespace
}  // namespace csg::bench

int main(int argc, char** argv) {
    benchmark::Initialize(&argc, argv);
    if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
    csg::bench::registerAll();
    benchmark::RunSpecifiedBenchmarks();
    benchmark::Shutdown();
    return 0;
}
