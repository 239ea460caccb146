// The image loop: square tiles handed out dynamically by csg::parallelFor to worker threads,
// each with its own Tracer (QueryContext, ray counters). The calling thread renders tiles too
// and reports progress after each of its own; no tile starts once cancellation is asked for.
#pragma once

#include <atomic>
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

// The sub-pixel position of sample (sx, sy) of an N x N grid in pixel (x, y), in [0, 1)^2:
// the stratum's centre when N = 1, else a deterministic hash-jittered point in its stratum.
void samplePosition(int x, int y, int sx, int sy, int n, double& u, double& v);

}  // namespace viewer::render
