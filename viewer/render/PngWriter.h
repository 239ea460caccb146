// PNG output: 8-bit RGB images marked sRGB, written atomically (primitives/base/AtomicFile.h), so a
// failed or interrupted write never leaves a broken image behind. The chunks are written here and
// the rows compressed by libdeflate in one piece (viewer/render/PngReader decodes through libpng).
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace viewer::render {

// Row-major 8-bit sRGB pixels, top row first, 3 bytes per pixel.
struct Rgb8Image {
    int width = 0;
    int height = 0;
    std::vector<uint8_t> pixels;  // size width * height * 3

    Rgb8Image() = default;
    Rgb8Image(int w, int h) : width(w), height(h), pixels(size_t(w) * size_t(h) * 3, 0) {}
    // Spare capacity for writePng's filter bytes, one per row, so that writing the image
    // in place does not move it.
    void reserveFilterBytes() {
        pixels.reserve(size_t(width) * size_t(height) * 3 + size_t(height));
    }
    uint8_t* row(int y) { return pixels.data() + size_t(y) * size_t(width) * 3; }
};

// Writes image to path as PNG. Returns an empty string on success, else the reason (the
// target is then untouched and no temporary file remains). Holds the filtered rows and their
// compressed form in memory meanwhile: about twice the pixels' bytes.
std::string writePng(const std::filesystem::path& path, const Rgb8Image& image);
// The same, filtering the rows in the image's own pixels, which it leaves empty, success or
// not: a render's image, written once, needs no copy, and no fresh pages but the compressed
// stream's (a first touch of fresh memory was ~5 % of a 1600x1600 render's CPU, bench/README.md).
// Pixels with `height` bytes of spare capacity (one filter byte per row) are not moved.
std::string writePng(const std::filesystem::path& path, Rgb8Image&& image);

}  // namespace viewer::render
