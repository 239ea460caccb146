#include "viewer/window/ProgressiveRenderer.h"

#include <chrono>

#include "viewer/render/ImageOutput.h"
#include "viewer/render/RenderCamera.h"
#include "viewer/render/TileRenderer.h"

namespace viewer::window {

namespace {

using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point start) {
    return std::chrono::duration<double>(Clock::now() - start).count();
}

constexpr int kBlockSizes[] = {8, 4, 2, 1};

}  // namespace

render::EffectsPlan planFor(const LoadedPart& part, const render::Camera& camera,
                            const EffectToggles& effects) {
    render::PlanSettings settings;
    settings.shadows = effects.shadows;
    render::EffectsPlan plan =
        render::makeEffectsPlan(part.model, part.model.root.get(), part.scene, camera, settings);
    // The tracer asks each material, so switching an effect off is clearing it there.
    for (render::PlannedMaterial& m : plan.materials) {
        m.reflection = m.reflection && effects.reflection;
        m.refraction = m.refraction && effects.refraction;
    }
    plan.reflection = plan.reflection && effects.reflection;
    plan.refraction = plan.refraction && effects.refraction;
    return plan;
}

std::string describePlan(const render::EffectsPlan& plan) {
    std::string text;
    auto add = [&text](bool on, const char* name) {
        if (!on) return;
        if (!text.empty()) text += ' ';
        text += name;
    };
    add(plan.direct, "diffuse");
    add(plan.specular, "specular");
    add(plan.shadowRays, "shadows");
    add(plan.reflection, "reflection");
    add(plan.refraction, "refraction");
    return text.empty() ? "ambient only" : text;
}

ProgressiveRenderer::ProgressiveRenderer(int threads, std::function<void()> onFrame)
    : threads_(std::max(threads, 1)),
      onFrame_(std::move(onFrame)),
      thread_([this](std::stop_token stop) { run(stop); }) {}

ProgressiveRenderer::~ProgressiveRenderer() {
    thread_.request_stop();
    cancel_ = true;
    wake_.notify_all();
    // jthread joins.
}

uint64_t ProgressiveRenderer::start(RenderRequest request) {
    std::lock_guard lock(mutex_);
    pending_ = std::move(request);
    cancel_ = true;
    wake_.notify_all();
    return ++requestCount_;
}

void ProgressiveRenderer::hold() {
    std::lock_guard lock(mutex_);
    held_ = true;
}

void ProgressiveRenderer::release() {
    std::lock_guard lock(mutex_);
    held_ = false;
    wake_.notify_all();
}

std::optional<ProgressiveFrame> ProgressiveRenderer::take() {
    std::lock_guard lock(mutex_);
    std::optional<ProgressiveFrame> frame = std::move(latest_);
    latest_.reset();
    return frame;
}

void ProgressiveRenderer::run(std::stop_token stop) {
    while (!stop.stop_requested()) {
        RenderRequest request;
        uint64_t number = 0;
        {
            std::unique_lock lock(mutex_);
            wake_.wait(lock, stop, [this] { return pending_.has_value(); });
            if (stop.stop_requested()) return;
            request = std::move(*pending_);
            pending_.reset();
            number = requestCount_;
            cancel_ = false;
        }
        const Clock::time_point requested = Clock::now();
        const render::EffectsPlan plan = planFor(*request.part, request.camera, request.effects);
        const std::string planText = describePlan(plan);
        for (const int block : kBlockSizes) {
            render::ImageSettings settings;
            settings.width = (request.width + block - 1) / block;
            settings.height = (request.height + block - 1) / block;
            settings.threads = threads_;
            // Small tiles at coarse levels, so every core gets work on a 100x75 image.
            settings.tileSize = block >= 4 ? 8 : 16;
            const Clock::time_point levelStart = Clock::now();
            const render::RenderResult result = render::renderImage(
                request.part->scene, plan,
                render::RenderCamera(request.camera, settings.width, settings.height), settings,
                &cancel_, nullptr);
            if (result.interrupted || cancel_) break;
            ProgressiveFrame frame;
            frame.request = number;
            frame.blockSize = block;
            frame.image = render::encodeSrgb(result.image);
            frame.rays = result.rays;
            frame.renderSeconds = secondsSince(levelStart);
            frame.sinceRequest = secondsSince(requested);
            frame.plan = planText;
            {
                std::lock_guard lock(mutex_);
                latest_ = std::move(frame);
            }
            if (onFrame_) onFrame_();
            if (block == kBlockSizes[0]) {
                std::unique_lock lock(mutex_);
                wake_.wait(lock, stop, [this] { return !held_ || pending_.has_value(); });
                if (stop.stop_requested() || pending_) break;
            }
        }
    }
}

}  // namespace viewer::window
