#include "viewer/render/PngReader.h"

#include <png.h>

#include <cstdio>
#include <memory>

namespace viewer::render {

std::string readPng(const std::filesystem::path& path, Rgb8Image& image) {
    image = Rgb8Image();
    // Opened here, not by png_image_begin_read_from_file, so a missing file reads as such
    // rather than as libpng's generic message.
    std::unique_ptr<FILE, int (*)(FILE*)> file(std::fopen(path.c_str(), "rb"), std::fclose);
    if (!file) return "cannot open '" + path.string() + "'";

    png_image png{};
    png.version = PNG_IMAGE_VERSION;
    if (!png_image_begin_read_from_stdio(&png, file.get()))
        return "'" + path.string() + "' is not a readable PNG: " + png.message;
    if (png.width == 0 || png.height == 0 || png.width > kMaxTextureSide ||
        png.height > kMaxTextureSide) {
        png_image_free(&png);
        return "'" + path.string() + "' is too large (at most " + std::to_string(kMaxTextureSide) +
               " pixels a side)";
    }
    // 8-bit sRGB RGB; alpha is composed over black by libpng, which is what "dropped" means
    // for a texture whose alpha the renderer does not use.
    png.format = PNG_FORMAT_RGB;
    Rgb8Image out(int(png.width), int(png.height));
    if (!png_image_finish_read(&png, nullptr, out.pixels.data(), 0, nullptr))
        return "'" + path.string() + "' is not a readable PNG: " + png.message;
    image = std::move(out);
    return {};
}

}  // namespace viewer::render
