// What a twist costs a ray (primitives/TwistedExtrusion.h): rays per second of spans and
// closest through linear_extrude parts read by the language, untwisted (the prism's exact
// crossing test) against twisted (root isolation with proven enclosures) and per-axis scaled.
// Scenes (height 10, seen from the side and above through 128 x 128 pixels, the part filling
// about half the frame):
//   square/<variant>   square(2, center = true)
//   star/<variant>     a 10-gon star of radii 2 and 0.8
//   circle/<variant>   circle(1) moved to x = 1.5 (an arc, its carrier an ellipse)
// with <variant> one of untwisted, twist90, twist720, scale (scale = [2, 0.5]) and
// twist90scale (both). Benchmark names are <query>/<scene>; counters as in core_bench.
#include <benchmark/benchmark.h>

#include <map>
#include <memory>
#include <stdexcept>
#include <string>

#include "bench/BenchScenes.h"
#include "io/Evaluate.h"

namespace csg::bench {
namespace {

struct TwistScene {
    Scene scene;
    std::vector<Ray> rays;
};

const std::map<std::string, std::string> kShapes = {
    {"square", "square(2, center = true);"},
    {"star",
     "polygon([for (i = [0:9]) (i % 2 ? 0.8 : 2) * [cos(36 * i), sin(36 * i)]]);"},
    {"circle", "translate([1.5, 0]) circle(1);"},
};
const std::map<std::string, std::string> kVariants = {
    {"untwisted", ""},
    {"twist90", ", twist = 90"},
    {"twist720", ", twist = 720"},
    {"scale", ", scale = [2, 0.5]"},
    {"twist90scale", ", twist = 90, scale = [2, 0.5]"},
};

std::unique_ptr<TwistScene> buildScene(const std::string& key) {
    const std::string shape = key.substr(0, key.find('/'));
    const std::string variant = key.substr(key.find('/') + 1);
    if (!kShapes.count(shape) || !kVariants.count(variant))
        throw std::invalid_argument("no twist benchmark scene named " + key);
    const std::string text = "linear_extrude(height = 10" + kVariants.at(variant) + ") " +
                             kShapes.at(shape);
    io::EvaluateOptions options;
    options.curves = io::CurveMode::Exact;
    io::EvaluateResult result = io::evaluateString(text, key, options);
    if (!result.ok()) throw std::runtime_error("cannot evaluate the scene " + key);
    auto scene = std::make_unique<TwistScene>();
    scene->scene = Scene::compile(result.model->root);
    PinholeCamera camera;
    camera.eye = Vec3(14.0, -18.0, 12.0);
    camera.lookAt = Vec3(0.0, 0.0, 5.0);
    camera.up = Vec3(0.0, 0.0, 1.0);
    camera.horizontalFovDegrees = 20.0;
    scene->rays = camera.pixelRays(128, 128);
    return scene;
}

const TwistScene& cachedScene(const std::string& key) {
    static std::map<std::string, std::unique_ptr<TwistScene>> cache;
    auto& slot = cache[key];
    if (!slot) slot = buildScene(key);
    return *slot;
}

template <class Query>
void queryBenchmark(benchmark::State& state, const std::string& key, const char* perRay,
                    Query query) {
    const TwistScene& scene = cachedScene(key);
    QueryContext context;
    size_t found = 0;
    for (auto _ : state)
        for (const Ray& ray : scene.rays) found += query(scene.scene, ray, context);
    const double rays = static_cast<double>(context.stats.rays);
    state.SetItemsProcessed(static_cast<int64_t>(context.stats.rays));
    state.counters["prims/ray"] = static_cast<double>(context.stats.primitiveTests) / rays;
    state.counters[perRay] = static_cast<double>(found) / rays;
}

void registerAll() {
    std::vector<std::string> keys;
    for (const auto& [shape, text] : kShapes)
        for (const char* variant : {"untwisted", "twist90", "twist720", "scale", "twist90scale"})
            keys.push_back(shape + "/" + variant);
    for (const std::string& key : keys)
        benchmark::RegisterBenchmark(("spans/" + key).c_str(), [key](benchmark::State& state) {
            queryBenchmark(state, key, "spans/ray",
                           [](const Scene& s, const Ray& r, QueryContext& c) {
                               const std::span<const Span> spans = s.spans(r, c);
                               benchmark::DoNotOptimize(spans.data());
                               return spans.size();
                           });
        });
    for (const std::string& key : keys)
        benchmark::RegisterBenchmark(("closest/" + key).c_str(), [key](benchmark::State& state) {
            queryBenchmark(state, key, "hits/ray",
                           [](const Scene& s, const Ray& r, QueryContext& c) {
                               const std::optional<Hit> hit = s.closest(r, c);
                               benchmark::DoNotOptimize(hit);
                               return size_t(hit.has_value());
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
