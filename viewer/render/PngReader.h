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

// Reads path's samples as stored, the way OpenSCAD's lodepng decode to 8-bit RGBA gives them
// (surface(file = "x.png") needs its luminance bit for bit): palette and grey expanded to RGB,
// 16-bit samples cut to their high byte, no gamma or colour management, alpha ignored (not
// composed: OpenSCAD reads R, G, B as they are). An image of more than maxPixels pixels is
// refused from its header, before anything is decoded. Same return convention as readPng.
std::string readPngSamples(const std::filesystem::path& path, Rgb8Image& image, uint64_t maxPixels);

}  // namespace viewer::render
