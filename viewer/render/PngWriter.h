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
    uint8_t* row(int y) { return pixels.data() + size_t(y) * size_t(width) * 3; }
};

// Writes image to path as PNG. Returns an empty string on success, else the reason (the
// target is then untouched and no temporary file remains). Holds the filtered rows and their
// compressed form in memory meanwhile: about twice the pixels' bytes.
std::string writePng(const std::filesystem::path& path, const Rgb8Image& image);

}  // namespace viewer::render
