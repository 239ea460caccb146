#include "viewer/render/TileRenderer.h"

#include <cstring>

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
struct TileWorker {
    TileWorker(const csg::Scene& scene, const EffectsPlan& plan, size_t tileChannels, int tile)
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

namespace {

// Where traceTile puts a tile's pixels: floats row by row (row y of the tile at
// floats + y * floatStride); for an Srgb8 image the floats are scratch and each row is also
// encoded to bytes + y * byteStride.
struct TileOut {
    float* floats;
    size_t floatStride;
    uint8_t* bytes;  // null: keep the floats
    size_t byteStride;
};

struct TileBox {
    int x0, y0, x1, y1;
};

TileBox tileBox(int index, int tilesX, int tile, int width, int height) {
    const int x0 = (index % tilesX) * tile, y0 = (index / tilesX) * tile;
    return {x0, y0, std::min(x0 + tile, width), std::min(y0 + tile, height)};
}

// columnX: scratch for the tile's width of image-plane x values.
void traceTile(Tracer& tracer, const RenderCamera& camera, int n, const TileBox& box,
               const TileOut& out, double* columnX) {
    const double sampleWeight = 1.0 / double(n * n);
    // One sample per pixel (n = 1) is camera.ray(x + 0.5, y + 0.5), its column's half
    // computed once per tile and its row's once per row: the same values, the same rays.
    if (n == 1)
        for (int x = box.x0; x < box.x1; ++x) columnX[x - box.x0] = camera.planeX(x + 0.5);
    for (int y = box.y0; y < box.y1; ++y) {
        float* row = out.floats + size_t(y - box.y0) * out.floatStride;
        const double rowY = camera.planeY(y + 0.5);
        for (int x = box.x0; x < box.x1; ++x) {
            csg::Vec3 sum(0.0);
            if (n == 1) {
                sum += tracer.tracePrimary(camera.rayThrough(columnX[x - box.x0], rowY));
            } else {
                for (int sy = 0; sy < n; ++sy) {
                    for (int sx = 0; sx < n; ++sx) {
                        double u, v;
                        samplePosition(x, y, sx, sy, n, u, v);
                        sum += tracer.tracePrimary(camera.ray(x + u, y + v));
                    }
                }
            }
            float* px = row + size_t(x - box.x0) * 3;
            for (int c = 0; c < 3; ++c) px[c] = float(sum[c] * sampleWeight);
        }
        if (out.bytes)
            encodeSrgb(row, size_t(box.x1 - box.x0) * 3,
                       out.bytes + size_t(y - box.y0) * out.byteStride);
    }
}

RenderResult blankImage(const ImageSettings& settings) {
    RenderResult result;
    // Every pixel is written before the image is used (an interrupted render's image is not);
    // resize's zero fill of fresh memory costs nothing measurable next to the render
    // (bench/README.md, image buffers on plain vectors).
    const size_t channels = size_t(settings.width) * size_t(settings.height) * 3;
    if (settings.store == PixelStore::Srgb8) {
        result.srgb.width = settings.width;
        result.srgb.height = settings.height;
        result.srgb.reserveFilterBytes();
        result.srgb.pixels.resize(channels);
    } else {
        result.image.width = settings.width;
        result.image.height = settings.height;
        result.image.rgb.resize(channels);
    }
    return result;
}

void addTracerCounts(const Tracer& tracer, RenderResult& result) {
    result.rays += tracer.rays;
    result.queries.rays += tracer.context.stats.rays;
    result.queries.nodeVisits += tracer.context.stats.nodeVisits;
    result.queries.primitiveTests += tracer.context.stats.primitiveTests;
    result.queries.slabCulls += tracer.context.stats.slabCulls;
}

}  // namespace

RenderResult renderImage(const csg::Scene& scene, const EffectsPlan& plan,
                         const RenderCamera& camera, const ImageSettings& settings,
                         const std::atomic<bool>* cancel, ProgressMeter* progress) {
    RenderResult result = blankImage(settings);
    const int width = settings.width, height = settings.height;
    const bool srgb = settings.store == PixelStore::Srgb8;
    const int tile = settings.tileSize;
    const int tilesX = (width + tile - 1) / tile;
    const int tilesY = (height + tile - 1) / tile;
    const int tileCount = tilesX * tilesY;

    std::vector<csg::WorkerSlot<TileWorker>> workers;
    workers.reserve(size_t(settings.threads));
    for (int t = 0; t < settings.threads; ++t)
        workers.emplace_back(scene, plan, srgb ? size_t(tile) * size_t(tile) * 3 : 0, tile);
    std::atomic<int> tilesDone{0};

    csg::parallelFor(
        uint64_t(tileCount), settings.threads,
        [&](int worker, uint64_t index) {
            TileWorker& own = workers[size_t(worker)].value;
            const TileBox box = tileBox(int(index), tilesX, tile, width, height);
            const TileOut out =
                srgb ? TileOut{own.tileFloats.data(), size_t(tile) * 3,
                               result.srgb.row(box.y0) + size_t(box.x0) * 3, size_t(width) * 3}
                     : TileOut{&result.image.rgb[(size_t(box.y0) * size_t(width) + box.x0) * 3],
                               size_t(width) * 3, nullptr, 0};
            traceTile(own.tracer, camera, settings.samplesPerAxis, box, out, own.columnX.data());
            const int done = tilesDone.fetch_add(1, std::memory_order_relaxed) + 1;
            // Worker 0 is the calling thread, the only one that may touch the meter.
            if (progress && worker == 0) progress->update(uint64_t(done), uint64_t(tileCount));
        },
        cancel);

    for (const csg::WorkerSlot<TileWorker>& w : workers) addTracerCounts(w.value.tracer, result);
    // A cancelled run leaves tiles undone (parallelFor starts none after it sees the flag).
    result.interrupted = tilesDone.load() < tileCount;
    if (progress)
        progress->finish(uint64_t(tilesDone.load()), uint64_t(tileCount), result.interrupted);
    return result;
}

struct alignas(64) TileSet::Worker : TileWorker {
    using TileWorker::TileWorker;
};

TileSet::TileSet(const csg::Scene& scene, const EffectsPlan& plan, const RenderCamera& camera,
                 const ImageSettings& settings)
    : camera_(camera),
      settings_(settings),
      tilesX_((settings.width + settings.tileSize - 1) / settings.tileSize),
      tilesY_((settings.height + settings.tileSize - 1) / settings.tileSize) {
    const size_t tileChannels = size_t(settings.tileSize) * size_t(settings.tileSize) * 3;
    // Worker is alignas(64), as WorkerSlot: its counters, written per ray, share no cache line.
    for (int t = 0; t < settings.threads; ++t)
        workers_.push_back(std::make_unique<Worker>(scene, plan, tileChannels, settings.tileSize));
}

TileSet::~TileSet() = default;

size_t TileSet::tileBytes(int index) const {
    const TileBox box =
        tileBox(index, tilesX_, settings_.tileSize, settings_.width, settings_.height);
    const size_t channels = size_t(box.x1 - box.x0) * size_t(box.y1 - box.y0) * 3;
    return settings_.store == PixelStore::Srgb8 ? channels : channels * sizeof(float);
}

void TileSet::render(int worker, int index, std::string& pixels) {
    Worker& own = *workers_[size_t(worker)];
    const TileBox box =
        tileBox(index, tilesX_, settings_.tileSize, settings_.width, settings_.height);
    const size_t rowChannels = size_t(box.x1 - box.x0) * 3;
    pixels.resize(tileBytes(index));
    if (settings_.store == PixelStore::Srgb8) {
        traceTile(own.tracer, camera_, settings_.samplesPerAxis, box,
                  {own.tileFloats.data(), rowChannels, reinterpret_cast<uint8_t*>(pixels.data()),
                   rowChannels},
                  own.columnX.data());
    } else {
        // The floats straight into the string's bytes: own.tileFloats is aligned for them.
        traceTile(own.tracer, camera_, settings_.samplesPerAxis, box,
                  {own.tileFloats.data(), rowChannels, nullptr, 0}, own.columnX.data());
        std::memcpy(pixels.data(), own.tileFloats.data(), pixels.size());
    }
}

RenderResult TileSet::blankResult() const {
    return blankImage(settings_);
}

bool TileSet::place(int index, std::string_view pixels, RenderResult& image) const {
    if (index < 0 || index >= count() || pixels.size() != tileBytes(index)) return false;
    const TileBox box =
        tileBox(index, tilesX_, settings_.tileSize, settings_.width, settings_.height);
    const size_t rowChannels = size_t(box.x1 - box.x0) * 3;
    for (int y = box.y0; y < box.y1; ++y) {
        const size_t at = (size_t(y) * size_t(settings_.width) + size_t(box.x0)) * 3;
        const size_t from = size_t(y - box.y0) * rowChannels;
        if (settings_.store == PixelStore::Srgb8)
            std::memcpy(&image.srgb.pixels[at], pixels.data() + from, rowChannels);
        else
            std::memcpy(&image.image.rgb[at], pixels.data() + from * sizeof(float),
                        rowChannels * sizeof(float));
    }
    return true;
}

void TileSet::addCounts(RenderResult& result) const {
    for (const std::unique_ptr<Worker>& w : workers_) addTracerCounts(w->tracer, result);
}

}  // namespace viewer::render
