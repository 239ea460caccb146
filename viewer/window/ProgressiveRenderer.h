// Progressive rendering for the window: one request (part, camera, size, effects) is rendered
// at one ray per 8x8 block, then 4x4, 2x2 and 1x1 (the thesis' "Resolution" idea), each level
// a whole image from the same renderer as `csgray render` (render::renderImage on all cores),
// so the finest level is exactly what `csgray render` writes for that camera. A new request
// cancels the level in flight (workers check between tiles) and starts again at 8x8.
//
// The control thread owns the rendering; the window's thread only posts requests and takes
// finished levels, so the event loop never waits for a ray.
#pragma once

#include <atomic>
#include <condition_variable>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

#include "viewer/cli/LoadPart.h"
#include "viewer/render/EffectsPlan.h"
#include "viewer/render/PngWriter.h"
#include "viewer/render/RayCounts.h"

namespace viewer::window {

// The effects the user switched on (S, M, T keys); the plan still drops what the part cannot
// show.
struct EffectToggles {
    bool shadows = true;
    bool reflection = true;
    bool refraction = true;
};

struct RenderRequest {
    std::shared_ptr<const LoadedPart> part;  // never null
    render::Camera camera;
    int width = 0, height = 0;  // the full-resolution image, pixels
    EffectToggles effects;
};

// One finished refinement level.
struct ProgressiveFrame {
    uint64_t request = 0;     // which request (they count up from 1)
    int blockSize = 8;        // pixels of the full image per ray along each axis: 8, 4, 2 or 1
    render::Rgb8Image image;  // sRGB, ceil(width / blockSize) x ceil(height / blockSize)
    render::RayCounts rays;
    double renderSeconds = 0.0;  // this level alone
    double sinceRequest = 0.0;   // from the request to this level being ready
    std::string plan;            // the effects the plan simulates, e.g. "shadows reflection"
};

// The effects plan for the toggles: makeEffectsPlan, then reflection and refraction removed
// from every material when switched off.
render::EffectsPlan planFor(const LoadedPart& part, const render::Camera& camera,
                            const EffectToggles& effects);
// "shadows specular reflection" (what the plan casts or shades), or "ambient only".
std::string describePlan(const render::EffectsPlan& plan);

class ProgressiveRenderer {
public:
    // onFrame runs on the control thread after each level (e.g. to wake the event loop); it
    // must not call back into this object. threads >= 1.
    ProgressiveRenderer(int threads, std::function<void()> onFrame);
    ~ProgressiveRenderer();
    ProgressiveRenderer(const ProgressiveRenderer&) = delete;
    ProgressiveRenderer& operator=(const ProgressiveRenderer&) = delete;

    // Replaces the current request (cancelling its level in flight). Returns its number.
    uint64_t start(RenderRequest request);
    // Makes the renderer stop after the coarsest level of each request until release(): at
    // start-up, the finer levels would only take the cores that SDL and the X server need to
    // open the window the first level is waiting for.
    void hold();
    void release();
    // The latest finished level not taken yet, if any.
    std::optional<ProgressiveFrame> take();

private:
    void run(std::stop_token stop);

    int threads_;
    std::function<void()> onFrame_;
    std::mutex mutex_;
    std::condition_variable_any wake_;
    std::optional<RenderRequest> pending_;
    uint64_t requestCount_ = 0;
    std::atomic<bool> cancel_{false};
    bool held_ = false;  // guarded by mutex_
    std::optional<ProgressiveFrame> latest_;
    std::jthread thread_;  // last: it starts after everything it uses exists
};

}  // namespace viewer::window
