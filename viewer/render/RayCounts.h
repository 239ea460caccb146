// Rays cast by kind: every ray the renderer gives to the scene is counted once, per thread,
// and the threads' counts are summed after the render (--stats).
#pragma once

#include <cstdint>

namespace viewer::render {

struct RayCounts {
    uint64_t primary = 0;     // one per sample
    uint64_t shadow = 0;      // occluded() toward a light
    uint64_t reflection = 0;  // mirror rays of materials with reflect > 0
    uint64_t refraction = 0;  // transmitted rays, total internal reflection included

    uint64_t total() const { return primary + shadow + reflection + refraction; }
    RayCounts& operator+=(const RayCounts& o) {
        primary += o.primary;
        shadow += o.shadow;
        reflection += o.reflection;
        refraction += o.refraction;
        return *this;
    }
};

}  // namespace viewer::render
