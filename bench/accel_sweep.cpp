// The spatial structures of --accel side by side (issue 21; bench/README.md, "Spatial
// structures"): for spheres spread over a layer (core_bench's sphere_layer), the same spheres
// in 16 clusters, and a terrain mesh over the layer (its triangles organized, one leaf), at
// 10^3 .. 10^6 spheres or triangles, per structure: compile time, the structure's memory,
// primary (closest), shadow (occluded) and secondary (closest from a hit) rays per second, and
// BVH slots / grid cells visited and primitives solved per primary ray. A plain program, run by
// hand; it prints a Markdown table. The smoke pass runs it on the smallest layer.
//
//   accel_sweep [--accel sah,median,...] [--sizes 1000,10000,...]
//               [--scenes uniform,clustered,terrain] [--image N] [--repeats K]
//
// Rays: core_bench's sphere_layer camera, N x N pixels (default 128); shadow rays run from one
// light, above the layer, to every primary hit point (t in [0, 1 - 1e-9], so they stop short
// of the hit's own surface), tried cached-object first as the renderer does; secondary rays are
// the mirror reflections of the primary rays at their hits, started off the surface as the
// renderer starts them (viewer/render/SecondaryOrigin.h): rays that begin inside the
// structure, among the objects, and scatter. A rate is per CPU second of this thread, the median
// of K timed passes (default 5) of at least 0.2 s each; the compile is timed in CPU seconds of
// every thread (a large SAH build uses several) and in wall seconds.
// The terrain's SAH BVH is built with the mesh (Polyhedron::make, timed apart and printed under
// the table), so its SAH row's compile time leaves that out; the other structures over its
// faces are built by Scene::compile. Its visits/ray count the union's work only (none: the
// mesh is one leaf), and prims/ray its solves.
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <sstream>
#include <string>
#include <vector>

#include "bench/BenchScenes.h"
#include "viewer/render/SecondaryOrigin.h"

namespace {

using namespace csg;
// CPU time in seconds, of this thread or of the whole process: the figures are taken on a shared
// machine, where wall time counts the other users' work too (as core_bench's rates, which are
// per CPU second). The queries run on this thread; a large SAH build also on other threads
// (BvhBuildOptions::threads), so the compile is timed by the process's clock, and by the wall's.
double clockSeconds(clockid_t clock) {
    timespec ts{};
    clock_gettime(clock, &ts);
    return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}
double cpuNow() {
    return clockSeconds(CLOCK_THREAD_CPUTIME_ID);
}
double processCpuNow() {
    return clockSeconds(CLOCK_PROCESS_CPUTIME_ID);
}
double wallNow() {
    return clockSeconds(CLOCK_MONOTONIC);
}

std::vector<std::string> split(const std::string& text) {
    std::vector<std::string> out;
    std::stringstream in(text);
    for (std::string item; std::getline(in, item, ',');) out.push_back(item);
    return out;
}

// Median over `repeats` passes of rays per second; each pass repeats the rays for >= 0.2 s.
template <class Query>
double raysPerSecond(size_t rayCount, int repeats, Query query) {
    std::vector<double> rates;
    for (int r = 0; r < repeats; ++r) {
        size_t done = 0;
        const double start = cpuNow();
        double elapsed = 0.0;
        do {
            query();
            done += rayCount;
            elapsed = cpuNow() - start;
        } while (elapsed < 0.2);
        rates.push_back(static_cast<double>(done) / elapsed);
    }
    std::sort(rates.begin(), rates.end());
    return rates[rates.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
    std::vector<std::string> accels = {"sah", "median", "goldsmith-salmon", "grid",
                                       "nonuniform-grid"};
    std::vector<size_t> sizes = {1000, 10000, 100000, 1000000};
    std::vector<std::string> scenes = {"uniform", "clustered", "terrain"};
    int image = 128, repeats = 5;
    for (int i = 1; i + 1 < argc; i += 2) {
        const std::string option = argv[i], value = argv[i + 1];
        if (option == "--accel") {
            accels = split(value);
        } else if (option == "--sizes") {
            sizes.clear();
            for (const std::string& s : split(value)) sizes.push_back(std::stoul(s));
        } else if (option == "--scenes") {
            scenes = split(value);
        } else if (option == "--image") {
            image = std::stoi(value);
        } else if (option == "--repeats") {
            repeats = std::stoi(value);
        } else {
            std::fprintf(stderr, "accel_sweep: unknown option %s\n", option.c_str());
            return 2;
        }
    }
    std::vector<Accel> structures;
    for (const std::string& name : accels) {
        const auto accel = parseAccel(name);
        if (!accel) {
            std::fprintf(stderr, "accel_sweep: unknown structure %s\n", name.c_str());
            return 2;
        }
        structures.push_back(*accel);
    }

    const std::vector<Ray> rays = bench::sphereLayerCamera().pixelRays(image, image);
    std::string meshNotes;
    const Vec3 light(30.0, 20.0, 150.0);
    std::printf(
        "| scene | items | structure | compile CPU ms | compile wall ms | structure MB | "
        "primary Mrays/s | shadow Mrays/s | secondary Mrays/s | visits/ray | prims/ray |\n");
    std::printf("|---|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|\n");
    for (const std::string& sceneName : scenes) {
        for (size_t n : sizes) {
            const double treeStart = processCpuNow();
            const NodePtr tree = sceneName == "clustered" ? bench::clusteredLayerTree(n)
                                 : sceneName == "terrain" ? bench::terrainMeshTree(n)
                                                          : bench::sphereLayerTree(n);
            if (sceneName == "terrain")
                meshNotes += "terrain " + std::to_string(n) +
                             ": the mesh made (welded, its SAH BVH built) in " +
                             std::to_string(1e3 * (processCpuNow() - treeStart)) + " ms of CPU\n";
            for (Accel accel : structures) {
                const double start = processCpuNow(), wallStart = wallNow();
                const Scene scene = Scene::compile(tree, {.accel = accel});
                const double compileSeconds = processCpuNow() - start;
                const double compileWallSeconds = wallNow() - wallStart;

                // The shadow rays, from the light to each primary hit, and the reflections there.
                QueryContext context;
                std::vector<Ray> shadows, reflections;
                for (const Ray& ray : rays) {
                    if (const auto hit = scene.closest(ray, context)) {
                        const SurfacePoint surface = scene.surface(ray, *hit);
                        shadows.push_back({light, surface.point - light, 0.0, 1.0 - 1e-9});
                        const Vec3 r = glm::reflect(glm::normalize(ray.d), surface.normal);
                        const Vec3 o = viewer::render::offsetRayOrigin(
                            surface.point, viewer::render::hitPointError(ray, hit->t),
                            surface.normal, r);
                        reflections.push_back({o, r, 0.0, kInfinity});
                    }
                }
                // Work per primary ray, from one pass.
                QueryContext counted;
                for (const Ray& ray : rays) (void)scene.closest(ray, counted);
                const double perRay = 1.0 / static_cast<double>(counted.stats.rays);

                size_t sink = 0;
                const double primary = raysPerSecond(rays.size(), repeats, [&] {
                    for (const Ray& ray : rays) sink += scene.closest(ray, context).has_value();
                });
                ObjectCache cache;
                const double shadow = raysPerSecond(shadows.size(), repeats, [&] {
                    for (const Ray& ray : shadows) sink += scene.occluded(ray, context, cache);
                });
                const double secondary = raysPerSecond(reflections.size(), repeats, [&] {
                    for (const Ray& ray : reflections)
                        sink += scene.closest(ray, context).has_value();
                });
                std::printf(
                    "| %s | %zu | %s | %.1f | %.1f | %.2f | %.3f | %.3f | %.3f | %.1f | %.2f |\n",
                    sceneName.c_str(), n, std::string(accelName(accel)).c_str(),
                    1e3 * compileSeconds, 1e3 * compileWallSeconds,
                    static_cast<double>(scene.structureBytes()) / 1e6, primary / 1e6, shadow / 1e6,
                    secondary / 1e6, static_cast<double>(counted.stats.nodeVisits) * perRay,
                    static_cast<double>(counted.stats.primitiveTests) * perRay);
                std::fflush(stdout);
                if (sink == 42) std::puts("");  // keep the queries from being optimized away
            }
        }
    }
    std::printf("\n%s", meshNotes.c_str());
    return 0;
}
