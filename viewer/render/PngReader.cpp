#include "viewer/render/PngReader.h"

#include <png.h>

#include <algorithm>
#include <csetjmp>
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

namespace {

// libpng's errors come back by longjmp to the reader's setjmp; the message is kept here.
void pngError(png_structp png, png_const_charp message) {
    auto* reason = static_cast<std::string*>(png_get_error_ptr(png));
    *reason = message;
    std::longjmp(png_jmpbuf(png), 1);
}
void pngWarning(png_structp, png_const_charp) {}

// The decoding, in a frame of its own whose locals are all set before setjmp: what libpng's
// longjmp returns to must not depend on objects changed after it. Owned objects live in the
// caller and are reached through the unchanging pointers. Returns false on a libpng error.
bool decodeSamples(png_structp png, png_infop info, FILE* file, uint64_t maxPixels, Rgb8Image* out,
                   std::vector<png_bytep>* rows, bool* tooLarge) {
    if (setjmp(png_jmpbuf(png))) return false;
    png_init_io(png, file);
    png_read_info(png, info);
    const png_uint_32 width = png_get_image_width(png, info);
    const png_uint_32 height = png_get_image_height(png, info);
    if (width == 0 || height == 0 || uint64_t(width) * uint64_t(height) > maxPixels) {
        *out = Rgb8Image();
        out->width = int(std::min<png_uint_32>(width, 1u << 30));
        out->height = int(std::min<png_uint_32>(height, 1u << 30));
        *tooLarge = true;
        return true;
    }
    // To 8-bit RGB, samples unchanged: lodepng's conversions (expansion, high byte of 16).
    png_set_expand(png);
    png_set_strip_16(png);
    png_set_strip_alpha(png);
    png_set_gray_to_rgb(png);
    png_set_interlace_handling(png);
    png_read_update_info(png, info);
    if (png_get_rowbytes(png, info) != size_t(width) * 3) png_error(png, "unexpected row size");
    *out = Rgb8Image(int(width), int(height));
    rows->resize(height);
    for (png_uint_32 y = 0; y < height; ++y) (*rows)[y] = out->row(int(y));
    png_read_image(png, rows->data());
    png_read_end(png, nullptr);
    return true;
}

}  // namespace

std::string readPngSamples(const std::filesystem::path& path, Rgb8Image& image,
                           uint64_t maxPixels) {
    image = Rgb8Image();
    std::unique_ptr<FILE, int (*)(FILE*)> file(std::fopen(path.c_str(), "rb"), std::fclose);
    if (!file) return "cannot open '" + path.string() + "'";
    std::string reason;
    png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &reason, pngError, pngWarning);
    if (!png) return "out of memory reading '" + path.string() + "'";
    png_infop info = png_create_info_struct(png);
    Rgb8Image out;
    std::vector<png_bytep> rows;
    bool tooLarge = false;
    const bool ok = info && decodeSamples(png, info, file.get(), maxPixels, &out, &rows, &tooLarge);
    png_destroy_read_struct(&png, info ? &info : nullptr, nullptr);
    if (!ok) return "'" + path.string() + "' is not a readable PNG: " + reason;
    if (tooLarge)
        return "'" + path.string() + "' is too large (" + std::to_string(out.width) + " x " +
               std::to_string(out.height) + " pixels; at most " + std::to_string(maxPixels) + ")";
    image = std::move(out);
    return {};
}

}  // namespace viewer::render
