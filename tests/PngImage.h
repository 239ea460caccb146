// A PNG file decoded to 8-bit RGB by libpng, for the tests that look at rendered pixels.
#pragma once

#include <png.h>

#include <cstdint>
#include <filesystem>
#include <vector>

namespace csg::testing {

struct RgbImage {
    int width = 0, height = 0;
    std::vector<uint8_t> rgb;  // row by row, 3 bytes a pixel
};

// The image, or an empty one (width 0) when the file cannot be read or decoded.
inline RgbImage readPng(const std::filesystem::path& path) {
    png_image image{};
    image.version = PNG_IMAGE_VERSION;
    if (!png_image_begin_read_from_file(&image, path.c_str())) return {};
    image.format = PNG_FORMAT_RGB;
    RgbImage out;
    out.rgb.resize(PNG_IMAGE_SIZE(image));
    if (!png_image_finish_read(&image, nullptr, out.rgb.data(), 0, nullptr)) {
        png_image_free(&image);
        return {};
    }
    out.width = int(image.width);
    out.height = int(image.height);
    return out;
}

}  // namespace csg::testing
