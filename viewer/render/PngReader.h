// PNG input for image textures: any PNG (grey, palette, 16-bit, alpha) decoded to 8-bit sRGB
// RGB through libpng's simplified API, which does the conversions libpng knows best.
#pragma once

#include <filesystem>
#include <string>

#include "viewer/render/PngWriter.h"

namespace viewer::render {

// Largest side accepted, in pixels: a texture is sampled, never a photo archive, and the
// bound keeps a hostile header from asking for gigabytes.
inline constexpr int kMaxTextureSide = 16384;

// Reads path into image (top row first, alpha dropped). Returns an empty string on success,
// else the reason ("cannot open ...", "not a PNG ...", "... too large"); image is then empty.
std::string readPng(const std::filesystem::path& path, Rgb8Image& image);

}  // namespace viewer::render
