// What OpenSCAD's faceting costs a ray (issue 18): rays per second of closest and spans through
// parts read by the language with --curves auto, where $fn makes each sphere and cylinder a
// convex polyhedron answered slab by slab, against the same parts with --curves exact (the
// quadrics). Scenes, at doubling facet counts:
//   sphere/exact, sphere/<n>       sphere(1, $fn = n): n (n/2 - 1) + 2 planes, n = 8 .. 128,
//                                  through core_bench's single-sphere camera (128 x 128 rays)
//   cylinders/exact, cylinders/<n> a union of 1000 cylinder(r = 0.3, h = 0.8, center = true,
//                                  $fn = n), n + 2 planes, on a 10 x 10 x 10 grid at unit
//                                  spacing, each turned by [13 i, 17 j, 7 k] degrees, through
//                                  the emblem grid's camera
// Benchmark names are <query>/<scene>; counters as in core_bench (visits/ray, prims/ray, and
// planes: the planes of one faceted solid).
#include <benchmark/benchmark.h>

#include <chrono>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>

#include "bench/BenchScenes.h"
#include "io/Evaluate.h"
#include "primitives/ConvexPolytope.h"

namespace csg::bench {
namespace {

constexpr int kFacetCounts[] = {8, 16, 32, 64, 128};

struct FacetScene {
    Scene scene;
    std::vector<Ray> rays;
    size_t planes = 0;  // of one faceted solid; 0 for the exact scenes
};

// "sphere/64" -> the part's text and camera; "exact" as the count keeps the quadrics.
std::unique_ptr<FacetScene> buildScene(const std::string& key) {
    const std::string kind = key.substr(0, key.find('/'));
    const std::string count = key.substr(key.find('/') + 1);
    const bool exact = count == "exact";
    const std::string fn = exact ? "" : ", $fn = " + count;
    std::string text;
    PinholeCamera camera;
    if (kind == "sphere") {
        text = "sphere(1" + fn + ");";
        camera = singleSphereCamera();
    } else if (kind == "cylinders") {
        text =
            "for (i = [0:9], j = [0:9], k = [0:9]) translate([i, j, k])\n"
            "    rotate([13 * i, 17 * j, 7 * k]) cylinder(r = 0.3, h = 0.8, center = true" +
            fn + ");";
        camera = emblemGridCamera();
    } else {
        throw std::invalid_argument("no facet benchmark scene named " + key);
    }
    io::EvaluateOptions options;
    options.curves = exact ? io::CurveMode::Exact : io::CurveMode::Auto;
    io::EvaluateResult result = io::evaluateString(text, key, options);
    if (!result.ok()) throw std::runtime_error("cannot evaluate the scene " + key);
    auto scene = std::make_unique<FacetScene>();
    scene->scene = Scene::compile(result.model->root);
    scene->rays = camera.pixelRays(128, 128);
    if (const auto* p = std::get_if<ConvexPolytope>(&scene->scene.leafPrimitive(0)))
        scene->planes = p->planeCount();
    return scene;
}

const FacetScene& cachedScene(const std::string& key) {
    static std::map<std::string, std::unique_ptr<FacetScene>> cache;
    auto& slot = cache[key];
    if (!slot) slot = buildScene(key);
    return *slot;
}

template <class Query>
void queryBenchmark(benchmark::State& state, const std::string& key, const char* perRay,
                    Query query) {
    const FacetScene& scene = cachedScene(key);
    QueryContext context;
    size_t found = 0;
    for (auto _ : state)
        for (const Ray& ray : scene.rays) found += query(scene.scene, ray, context);
    const double rays = static_cast<double>(context.stats.rays);
    state.SetItemsProcessed(static_cast<int64_t>(context.stats.rays));
    state.counters["visits/ray"] = static_cast<double>(context.stats.nodeVisits) / rays;
    state.counters["prims/ray"] = static_cast<double>(context.stats.primitiveTests) / rays;
    state.counters["planes"] = static_cast<double>(scene.planes);
    state.counters[perRay] = static_cast<double>(found) / rays;
}

void registerAll() {
    std::vector<std::string> keys;
    for (const char* kind : {"sphere", "cylinders"}) {
        keys.push_back(std::string(kind) + "/exact");
        for (int n : kFacetCounts) keys.push_back(std::string(kind) + "/" + std::to_string(n));
    }
    for (const std::string& key : keys)
        benchmark::RegisterBenchmark(("closest/" + key).c_str(), [key](benchmark::State& state) {
            queryBenchmark(state, key, "hits/ray",
                           [](const Scene& s, const Ray& r, QueryContext& c) {
                               const std::optional<Hit> hit = s.closest(r, c);
                               benchmark::DoNotOptimize(hit);
                               return size_t(hit.has_value());
                           });
        });
    for (const std::string& key : keys)
        benchmark::RegisterBenchmark(("spans/" + key).c_str(), [key](benchmark::State& state) {
            queryBenchmark(state, key, "spans/ray",
                           [](const Scene& s, const Ray& r, QueryContext& c) {
                               const std::span<const Span> spans = s.spans(r, c);
                               benchmark::DoNotOptimize(spans.data());
                               return spans.size();
                           });
        });
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
