// Polygon meshes (issue 18): rays per second through an imported triangle mesh at growing sizes,
// and the time to load a large STL. The mesh is a UV sphere of radius 1 (n triangles: 2 s
// (r - 1) for s sectors and r rings, s = 2 r), written once per size as a binary STL in the
// temporary directory and imported through the part language (`import("sphere_n.stl");`), so
// the figures include everything a part pays: the reader, welding, sheets, the BVH, the
// compiled scene's leaf.
//   mesh_bench --benchmark_filter='closest/'      rays per second of closest() per size
//   mesh_bench --benchmark_filter='load/'         reading + building the 10^6-triangle mesh
// Rays: one per pixel of a 128 x 128 camera 4 units away whose frame circumscribes the
// sphere's silhouette (78.5 % hit), as core_bench's `sphere` scene.
#include <benchmark/benchmark.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>

#include "bench/BenchScenes.h"
#include "io/Evaluate.h"
#include "io/mesh/MeshFile.h"
#include "primitives/Polyhedron.h"

namespace csg::bench {
namespace {

// Ring counts giving 960 .. 1 046 528 triangles (4 r (r - 1)), each size about 4 times the last.
constexpr int kRings[] = {16, 32, 64, 128, 256, 512};

std::filesystem::path stlPath(int rings) {
    return std::filesystem::temp_directory_path() /
           ("csgray_mesh_bench_" + std::to_string(getpid()) + "_" + std::to_string(rings) + ".stl");
}

// The UV sphere's triangles as a binary STL (little-endian host).
void writeSphereStl(const std::filesystem::path& path, int rings) {
    const int sectors = 2 * rings;
    auto at = [&](int ring, int k) {
        const double polar = M_PI * ring / rings, az = 2 * M_PI * (k % sectors) / sectors;
        return Vec3(std::sin(polar) * std::cos(az), std::sin(polar) * std::sin(az),
                    std::cos(polar));
    };
    std::vector<std::array<Vec3, 3>> triangles;
    for (int i = 0; i < rings; ++i)
        for (int k = 0; k < sectors; ++k) {
            const Vec3 a = at(i, k), b = at(i, k + 1), c = at(i + 1, k + 1), d = at(i + 1, k);
            if (i > 0) triangles.push_back({a, d, b});
            if (i + 1 < rings) triangles.push_back({b, d, c});
        }
    std::ofstream out(path, std::ios::binary);
    char header[80] = "csgray mesh_bench sphere";
    out.write(header, 80);
    const uint32_t n = uint32_t(triangles.size());
    out.write(reinterpret_cast<const char*>(&n), 4);
    for (const auto& t : triangles) {
        float f[12] = {};
        for (int c = 0; c < 3; ++c)
            for (int k = 0; k < 3; ++k) f[3 + 3 * c + k] = float(t[c][k]);
        out.write(reinterpret_cast<const char*>(f), sizeof f);
        out.write("\0\0", 2);
    }
}

struct MeshScene {
    Scene scene;
    std::vector<Ray> rays;
    size_t triangles = 0;
    double loadSeconds = 0.0;  // evaluate (read, weld, BVH) + compile
};

const MeshScene& cachedMeshScene(int rings) {
    static std::map<int, MeshScene> cache;
    auto it = cache.find(rings);
    if (it != cache.end()) return it->second;
    const std::filesystem::path file = stlPath(rings);
    writeSphereStl(file, rings);
    MeshScene& s = cache[rings];
    const auto start = std::chrono::steady_clock::now();
    io::EvaluateResult r = io::evaluateString("import(\"" + file.string() + "\");", "bench.scad");
    if (!r.ok()) std::abort();
    s.scene = Scene::compile(r.model->root);
    s.loadSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    s.triangles = std::get<Polyhedron>(r.model->root->primitive).triangleCount();
    s.rays = singleSphereCamera().pixelRays(128, 128);
    std::filesystem::remove(file);
    return s;
}

template <class Query>
void meshQuery(benchmark::State& state, int rings, const char* perRay, Query query) {
    const MeshScene& s = cachedMeshScene(rings);
    QueryContext context;
    size_t found = 0;
    for (auto _ : state)
        for (const Ray& ray : s.rays) found += query(s.scene, ray, context);
    state.SetItemsProcessed(int64_t(context.stats.rays));
    state.counters["triangles"] = double(s.triangles);
    state.counters["load_ms"] = 1e3 * s.loadSeconds;
    state.counters[perRay] = double(found) / double(context.stats.rays);
}

void closestBenchmark(benchmark::State& state, int rings) {
    meshQuery(state, rings, "hits/ray", [](const Scene& scene, const Ray& ray, QueryContext& c) {
        const std::optional<Hit> hit = scene.closest(ray, c);
        benchmark::DoNotOptimize(hit);
        return size_t(hit.has_value());
    });
}

void spansBenchmark(benchmark::State& state, int rings) {
    meshQuery(state, rings, "spans/ray", [](const Scene& scene, const Ray& ray, QueryContext& c) {
        const std::span<const Span> spans = scene.spans(ray, c);
        benchmark::DoNotOptimize(spans.data());
        return spans.size();
    });
}

// Reading the STL and building the primitive (weld, sheets, BVH, orientation), the part's whole
// load but for the language around it.
void loadBenchmark(benchmark::State& state, int rings) {
    const std::filesystem::path file = stlPath(rings);
    writeSphereStl(file, rings);
    size_t triangles = 0;
    double readSeconds = 0.0;
    for (auto _ : state) {
        const auto start = std::chrono::steady_clock::now();
        io::PolygonMeshReadResult read = io::readPolygonMesh(file);
        readSeconds +=
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        const Polyhedron mesh = Polyhedron::make(std::move(read.mesh->positions), read.mesh->faces);
        triangles = mesh.triangleCount();
        benchmark::DoNotOptimize(mesh.data.get());
    }
    std::filesystem::remove(file);
    state.counters["triangles"] = double(triangles);
    state.counters["read_ms"] = 1e3 * readSeconds / double(state.iterations());
}

void registerAll() {
    for (const int rings : kRings) {
        const std::string size = std::to_string(2 * 2 * rings * (rings - 1));
        benchmark::RegisterBenchmark(("closest/sphere_mesh/" + size).c_str(), closestBenchmark,
                                     rings)
            ->Unit(benchmark::kMillisecond);
        benchmark::RegisterBenchmark(("spans/sphere_mesh/" + size).c_str(), spansBenchmark, rings)
            ->Unit(benchmark::kMillisecond);
    }
    benchmark::RegisterBenchmark(
        ("load/sphere_mesh/" + std::to_string(4 * kRings[5] * (kRings[5] - 1))).c_str(),
        loadBenchmark, kRings[5])
        ->Unit(benchmark::kMillisecond)
        ->Iterations(3);
}

}  // namespace
}  // namespace csg::bench

int main(int argc, char** argv) {
    csg::bench::registerAll();
    benchmark::Initialize(&argc, argv);
    if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
    benchmark::RunSpecifiedBenchmarks();
    benchmark::Shutdown();
    return 0;
}
