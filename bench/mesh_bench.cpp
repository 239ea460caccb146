// Polygon meshes (issue 18): rays per second through an imported triangle mesh at growing sizes,
// and the time to load a large STL. The mesh is a UV sphere of radius 1 (n triangles: 2 s
// (r - 1) for s sectors and r rings, s = 2 r), written once per size as a binary STL in the
// temporary directory and imported through the part language (`import("sphere_n.stl");`), so
// the figures include everything a part pays: the reader, welding, sheets, the BVH, the
// compiled scene's leaf.
//   mesh_bench --benchmark_filter='closest/'      rays per second of closest() per size
//   mesh_bench --benchmark_filter='load/'         reading + building the 10^6-triangle mesh
//   mesh_bench --benchmark_filter='sphere_mesh_'  the lecture's polygon methods (Snyder's,
//                                                 Marchal's): closest() per size, and leaks
//   mesh_bench --benchmark_filter='leaks/'        lines through vertices and edges whose spans
//                                                 differ from a one-ulp move's, per method
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
#include <random>
#include <span>

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
        // The poles exactly on the axis: sin(pi) is 1.2e-16, which would leave each pole
        // triangle its own apex and the mesh open by that much there.
        if (ring == 0 || ring == rings) return Vec3(0.0, 0.0, ring == 0 ? 1.0 : -1.0);
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
    NodePtr root;
    Scene scene;
    std::vector<Ray> rays;
    size_t triangles = 0;
    double loadSeconds = 0.0;  // evaluate (read, weld, BVH) + compile
};

const MeshScene& cachedMeshScene(int rings, PolygonMethod method = PolygonMethod::Watertight) {
    static std::map<std::pair<int, PolygonMethod>, MeshScene> cache;
    auto it = cache.find({rings, method});
    if (it != cache.end()) return it->second;
    if (method != PolygonMethod::Watertight) {
        // The same mesh, compiled with another method.
        const MeshScene& watertight = cachedMeshScene(rings);
        MeshScene& s = cache[{rings, method}];
        s.root = watertight.root;
        s.scene = Scene::compile(s.root, {.polygonMethod = method});
        s.rays = watertight.rays;
        s.triangles = watertight.triangles;
        s.loadSeconds = watertight.loadSeconds;
        return s;
    }
    const std::filesystem::path file = stlPath(rings);
    writeSphereStl(file, rings);
    MeshScene& s = cache[{rings, method}];
    const auto start = std::chrono::steady_clock::now();
    io::EvaluateResult r = io::evaluateString("import(\"" + file.string() + "\");", "bench.scad");
    if (!r.ok()) std::abort();
    s.root = r.model->root;
    s.scene = Scene::compile(s.root);
    s.loadSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    s.triangles = std::get<Polyhedron>(r.model->root->primitive).triangleCount();
    s.rays = singleSphereCamera().pixelRays(128, 128);
    std::filesystem::remove(file);
    return s;
}

template <class Query>
void meshQuery(benchmark::State& state, int rings, const char* perRay, Query query,
               PolygonMethod method = PolygonMethod::Watertight) {
    const MeshScene& s = cachedMeshScene(rings, method);
    QueryContext context;
    size_t found = 0;
    for (auto _ : state)
        for (const Ray& ray : s.rays) found += query(s.scene, ray, context);
    state.SetItemsProcessed(int64_t(context.stats.rays));
    state.counters["triangles"] = double(s.triangles);
    state.counters["load_ms"] = 1e3 * s.loadSeconds;
    state.counters[perRay] = double(found) / double(context.stats.rays);
}

void closestBenchmark(benchmark::State& state, int rings, PolygonMethod method) {
    meshQuery(
        state, rings, "hits/ray",
        [](const Scene& scene, const Ray& ray, QueryContext& c) {
            const std::optional<Hit> hit = scene.closest(ray, c);
            benchmark::DoNotOptimize(hit);
            return size_t(hit.has_value());
        },
        method);
}

// Leaks: lines aimed exactly at the mesh's vertices and at the midpoints of its edges (exact
// in doubles: the STL's float corners sum without rounding), along a coordinate axis (either
// way) so that the line holds the point exactly, each answered as the same line with its origin
// moved by one ulp across it (off the vertex or edge, through a triangle's inside). A leak is a
// line whose spans differ from the moved line's (in count, or an end by more than 1e-9): a crossing
// counted twice or lost. Reported per 10^6 lines of each kind.
void leakBenchmark(benchmark::State& state, int rings, PolygonMethod method) {
    const MeshScene& s = cachedMeshScene(rings, method);
    const PolyhedronData& mesh = *std::get<Polyhedron>(s.root->primitive).data;
    std::mt19937_64 random(2026);
    constexpr int kLines = 1 << 15;
    QueryContext context;
    std::vector<Span> aimed;
    const auto leaks = [&](auto targetOf) {
        int count = 0;
        for (int n = 0; n < kLines; ++n) {
            const Vec3 target = targetOf();
            // Along the target's largest coordinate: the line crosses the unit sphere at
            // least 35 degrees from tangent there, so a one-ulp move changes the answer only
            // where a crossing is counted twice or lost, never by grazing the silhouette.
            const Vec3 size = glm::abs(target);
            const int axis =
                size.x >= size.y ? (size.x >= size.z ? 0 : 2) : (size.y >= size.z ? 1 : 2);
            Vec3 d(0.0);
            d[axis] = random() % 2 ? 1.0 : -1.0;
            const Vec3 o = target - 4.0 * d;
            const std::span<const Span> a = s.scene.spans(Ray{o, d, 0.0, 1e9}, context);
            aimed.assign(a.begin(), a.end());
            Vec3 moved = o;
            const int across = (axis + 1) % 3;
            moved[across] = std::nextafter(moved[across], kInfinity);
            const std::span<const Span> b = s.scene.spans(Ray{moved, d, 0.0, 1e9}, context);
            bool same = aimed.size() == b.size();
            for (size_t i = 0; same && i < b.size(); ++i)
                same = std::abs(aimed[i].in.t - b[i].in.t) <= 1e-9 &&
                       std::abs(aimed[i].out.t - b[i].out.t) <= 1e-9;
            count += !same;
        }
        return count;
    };
    int vertexLeaks = 0, edgeLeaks = 0;
    for (auto _ : state) {
        vertexLeaks = leaks([&] { return mesh.vertices[random() % mesh.vertices.size()]; });
        edgeLeaks = leaks([&] {
            const auto& t = mesh.triangles[random() % mesh.triangles.size()];
            const int k = int(random() % 3);
            return 0.5 * (mesh.vertices[t[size_t(k)]] + mesh.vertices[t[size_t(k + 1) % 3]]);
        });
    }
    state.counters["triangles"] = double(s.triangles);
    state.counters["vertex_leaks_per_1e6"] = 1e6 * vertexLeaks / kLines;
    state.counters["edge_leaks_per_1e6"] = 1e6 * edgeLeaks / kLines;
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
                                     rings, PolygonMethod::Watertight)
            ->Unit(benchmark::kMillisecond);
        benchmark::RegisterBenchmark(("spans/sphere_mesh/" + size).c_str(), spansBenchmark, rings)
            ->Unit(benchmark::kMillisecond);
        for (PolygonMethod method :
             {PolygonMethod::Watertight, PolygonMethod::Snyder, PolygonMethod::Marchal}) {
            const std::string name = polygonMethodName(method);
            if (method != PolygonMethod::Watertight)
                benchmark::RegisterBenchmark(
                    ("closest/sphere_mesh_" + name + "/" + size).c_str(),
                    [=](benchmark::State& state) { closestBenchmark(state, rings, method); })
                    ->Unit(benchmark::kMillisecond);
            benchmark::RegisterBenchmark(
                ("leaks/sphere_mesh_" + name + "/" + size).c_str(),
                [=](benchmark::State& state) { leakBenchmark(state, rings, method); })
                ->Unit(benchmark::kMillisecond)
                ->Iterations(1);
        }
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
