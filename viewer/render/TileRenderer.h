// The image loop: square tiles handed out dynamically by csg::parallelFor to worker threads,
// each with its own Tracer (QueryContext, ray counters). The calling thread renders tiles too
// and reports progress after each of its own; no tile starts once cancellation is asked for.
#pragma once

#include <atomic>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "csg/Scene.h"
#include "viewer/render/EffectsPlan.h"
#include "viewer/render/PngWriter.h"
#include "viewer/render/Progress.h"
#include "viewer/render/RayCounts.h"
#include "viewer/render/RenderCamera.h"

namespace viewer::render {

// What the workers keep of each pixel: linear float RGB (PFM, EXR, the viewer, tests), or only
// its 8-bit sRGB encoding (PNG), made per tile while the tile's floats are in cache, so that
// the float image (12 bytes a pixel, 30 MB at 1600x1600) is never made nor read back.
enum class PixelStore { LinearFloat, Srgb8 };

struct ImageSettings {
    int width = 800, height = 600;
    int samplesPerAxis = 1;  // --aa N: N x N stratified samples per pixel
    int threads = 1;         // >= 1
    int tileSize = 16;       // pixels per tile side
    PixelStore store = PixelStore::LinearFloat;
};

// Linear RGB, row-major, top row first, 3 floats per pixel.
struct LinearImage {
    int width = 0, height = 0;
    std::vector<float> rgb;
};

struct RenderResult {
    LinearImage image;         // when settings.store is LinearFloat
    Rgb8Image srgb;            // when it is Srgb8: encodeSrgb of the same pixels
    RayCounts rays;            // summed over threads
    csg::QueryStats queries;   // summed over threads
    bool interrupted = false;  // the image is incomplete and must not be written
};

// Renders every pixel unless *cancel becomes true (then interrupted is set). progress may be
// null.
RenderResult renderImage(const csg::Scene& scene, const EffectsPlan& plan,
                         const RenderCamera& camera, const ImageSettings& settings,
                         const std::atomic<bool>* cancel, ProgressMeter* progress);

// The same image's tiles one at a time, for a caller that hands them out itself (csgray's MPI
// ranks, the --resume journal): a tile's pixels are those renderImage makes, wherever and in
// whatever order it is rendered, so an image put together from tiles is byte-identical.
class TileSet {
public:
    // settings.threads workers, each with its own Tracer.
    TileSet(const csg::Scene& scene, const EffectsPlan& plan, const RenderCamera& camera,
            const ImageSettings& settings);
    ~TileSet();
    TileSet(const TileSet&) = delete;
    TileSet& operator=(const TileSet&) = delete;

    int count() const { return tilesX_ * tilesY_; }
    // The bytes render() makes for tile index: its pixels row by row, 3 bytes (Srgb8) or 3
    // floats (LinearFloat) each.
    size_t tileBytes(int index) const;
    // Renders tile index (in [0, count())) on worker's Tracer (worker in [0, threads)); only
    // one thread may use a worker at a time.
    void render(int worker, int index, std::string& pixels);
    // An image of the settings' size and store whose pixels are all still to be placed.
    RenderResult blankResult() const;
    // Copies pixels made by render(index) into image; false if they have the wrong size.
    bool place(int index, std::string_view pixels, RenderResult& image) const;
    // This process's ray and query counts so far, summed over its workers.
    void addCounts(RenderResult& result) const;

private:
    struct Worker;
    const RenderCamera& camera_;
    ImageSettings settings_;
    int tilesX_, tilesY_;
    std::vector<std::unique_ptr<Worker>> workers_;
};

// The sub-pixel position of sample (sx, sy) of an N x N grid in pixel (x, y), in [0, 1)^2:
// the stratum's centre when N = 1, else a deterministic hash-jittered point in its stratum.
void samplePosition(int x, int y, int sx, int sy, int n, double& u, double& v);

}  // namespace viewer::render
