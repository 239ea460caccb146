#include "viewer/render/TileRenderer.h"

#include "primitives/base/ParallelFor.h"
#include "viewer/render/ImageOutput.h"
#include "viewer/render/Tracer.h"

namespace viewer::render {

namespace {

// A 64-bit mix (splitmix64's finalizer): the jitter of a sample depends only on where it is,
// so a render is the same for any thread count and tile order.
uint64_t mix(uint64_t z) {
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
}

double unitFromBits(uint64_t bits) {
    return double(bits >> 11) * 0x1.0p-53;  // [0, 1) with every value a multiple of 2^-53
}

// What one worker thread owns: its Tracer, for an Srgb8 render its tile's floats, and the
// image-plane x of its tile's pixel centres.
struct Worker {
    Worker(const csg::Scene& scene, const EffectsPlan& plan, size_t tileChannels, int tile)
        : tracer(scene, plan), tileFloats(tileChannels), columnX(size_t(tile)) {}
    Tracer tracer;
    std::vector<float> tileFloats;  // rows of `tile` pixels
    std::vector<double> columnX;    // RenderCamera::planeX(x + 0.5), x from the tile's left
};

}  // namespace

void samplePosition(int x, int y, int sx, int sy, int n, double& u, double& v) {
    if (n == 1) {
        u = v = 0.5;
        return;
    }
    const uint64_t key = (uint64_t(uint32_t(x)) << 32 | uint32_t(y)) * 0x9e3779b97f4a7c15ull ^
                         (uint64_t(sy) * n + sx);
    const uint64_t h = mix(key);
    u = (sx + unitFromBits(h)) / n;
    v = (sy + unitFromBits(mix(h))) / n;
}

RenderResult renderImage(const csg::Scene& scene, const EffectsPlan& plan,
                         const RenderCamera& camera, const ImageSettings& settings,
                         const std::atomic<bool>* cancel, ProgressMeter* progress) {
    RenderResult result;
    const int width = settings.width, height = settings.height;
    const bool srgb = settings.store == PixelStore::Srgb8;
    // Every pixel is written before the image is used (an interrupted render's image is not);
    // resize's zero fill of fresh memory costs nothing measurable next to the render
    // (bench/README.md, image buffers on plain vectors).
    const size_t channels = size_t(width) * size_t(height) * 3;
    if (srgb) {
        result.srgb.width = width;
        result.srgb.height = height;
        result.srgb.pixels.resize(channels);
    } else {
        result.image.width = width;
        result.image.height = height;
        result.image.rgb.resize(channels);
    }

    const int tile = settings.tileSize;
    const int tilesX = (width + tile - 1) / tile;
    const int tilesY = (height + tile - 1) / tile;
    const int tileCount = tilesX * tilesY;
    const int n = settings.samplesPerAxis;
    const double sampleWeight = 1.0 / double(n * n);

    std::vector<csg::WorkerSlot<Worker>> workers;
    workers.reserve(size_t(settings.threads));
    for (int t = 0; t < settings.threads; ++t)
        workers.emplace_back(scene, plan, srgb ? size_t(tile) * size_t(tile) * 3 : 0, tile);
    std::atomic<int> tilesDone{0};

    csg::parallelFor(
        uint64_t(tileCount), settings.threads,
        [&](int worker, uint64_t index) {
            Worker& own = workers[size_t(worker)].value;
            const int x0 = int(index % tilesX) * tile, y0 = int(index / tilesX) * tile;
            const int x1 = std::min(x0 + tile, width), y1 = std::min(y0 + tile, height);
            // One sample per pixel (n = 1) is camera.ray(x + 0.5, y + 0.5), its column's half
            // computed once per tile and its row's once per row: the same values, the same rays.
            if (n == 1)
                for (int x = x0; x < x1; ++x) own.columnX[size_t(x - x0)] = camera.planeX(x + 0.5);
            for (int y = y0; y < y1; ++y) {
                float* row = srgb ? &own.tileFloats[size_t(y - y0) * size_t(tile) * 3]
                                  : &result.image.rgb[(size_t(y) * size_t(width) + x0) * 3];
                const double rowY = camera.planeY(y + 0.5);
                for (int x = x0; x < x1; ++x) {
                    csg::Vec3 sum(0.0);
                    if (n == 1) {
                        sum += own.tracer.tracePrimary(
                            camera.rayThrough(own.columnX[size_t(x - x0)], rowY));
                    } else {
                        for (int sy = 0; sy < n; ++sy) {
                            for (int sx = 0; sx < n; ++sx) {
                                double u, v;
                                samplePosition(x, y, sx, sy, n, u, v);
                                sum += own.tracer.tracePrimary(camera.ray(x + u, y + v));
                            }
                        }
                    }
                    float* px = row + size_t(x - x0) * 3;
                    for (int c = 0; c < 3; ++c) px[c] = float(sum[c] * sampleWeight);
                }
                if (srgb) encodeSrgb(row, size_t(x1 - x0) * 3, result.srgb.row(y) + size_t(x0) * 3);
            }
            const int done = tilesDone.fetch_add(1, std::memory_order_relaxed) + 1;
            // Worker 0 is the calling thread, the only one that may touch the meter.
            if (progress && worker == 0) progress->update(uint64_t(done), uint64_t(tileCount));
        },
        cancel);

    for (const csg::WorkerSlot<Worker>& w : workers) {
        const Tracer& tracer = w.value.tracer;
        result.rays += tracer.rays;
        result.queries.rays += tracer.context.stats.rays;
        result.queries.nodeVisits += tracer.context.stats.nodeVisits;
        result.queries.primitiveTests += tracer.context.stats.primitiveTests;
    }
    // A cancelled run leaves tiles undone (parallelFor starts none after it sees the flag).
    result.interrupted = tilesDone.load() < tileCount;
    if (progress)
        progress->finish(uint64_t(tilesDone.load()), uint64_t(tileCount), result.interrupted);
    return result;
}

}  // namespace viewer::render
