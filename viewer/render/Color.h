// Colour conversions of the renderer. Shading happens in linear light; colours written in a
// part (material colours, background) are sRGB values as a user picks them on screen, the
// convention of OpenSCAD and of every colour picker, so they are decoded once before rendering
// and the image is encoded back to sRGB once when it is written.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "primitives/base/Math.h"

namespace viewer::render {

// The sRGB transfer function (IEC 61966-2-1), clamped to [0, 1].
inline double srgbToLinear(double c) {
    c = std::clamp(c, 0.0, 1.0);
    return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}
inline double linearToSrgb(double linear) {
    linear = std::clamp(linear, 0.0, 1.0);
    return linear <= 0.0031308 ? 12.92 * linear : 1.055 * std::pow(linear, 1.0 / 2.4) - 0.055;
}
inline uint8_t linearToSrgb8(double linear) {
    return uint8_t(std::lround(linearToSrgb(linear) * 255.0));
}
inline csg::Vec3 srgbToLinear(const csg::Vec3& c) {
    return {srgbToLinear(c.r), srgbToLinear(c.g), srgbToLinear(c.b)};
}

// The background when the part sets none: OpenSCAD's light cream (the preview's too).
inline constexpr csg::Vec3 kDefaultBackgroundSrgb{1.0, 1.0, 0.898};

}  // namespace viewer::render
