// Writing a finished render: PNG (8-bit, sRGB-encoded from linear light, through
// viewer/render/PngWriter), PFM (32-bit float linear RGB, the simplest HDR format, for comparisons)
// or OpenEXR (the same floats, compressed; ExrOutput.h). All go through primitives/base/AtomicFile:
// a failed or interrupted write leaves no file.
#pragma once

#include <filesystem>
#include <string>

#include "viewer/render/PngWriter.h"
#include "viewer/render/TileRenderer.h"

namespace viewer::render {

enum class ImageFormat { Png, Pfm, Exr };

// Linear RGB to 8-bit sRGB (the transfer function, not a plain 2.2 power).
Rgb8Image encodeSrgb(const LinearImage& image);
// The same for `count` channel values, from linear to out.
void encodeSrgb(const float* linear, size_t count, uint8_t* out);

// Returns an empty string on success, else the reason (the target is then untouched).
std::string writeImage(const std::filesystem::path& path, ImageFormat format,
                       const LinearImage& image);

// What a render written in `format` needs kept of each pixel: PNG only its 8-bit encoding.
PixelStore pixelStoreFor(ImageFormat format);
// Writes a render made with pixelStoreFor(format): from its 8-bit pixels when it kept those,
// which are then spent (writePng filters in them); the counts are left as they were.
std::string writeImage(const std::filesystem::path& path, ImageFormat format, RenderResult& render);

}  // namespace viewer::render
