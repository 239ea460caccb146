#include "viewer/render/ImageOutput.h"

#include <bit>
#include <cstdio>

#include "io/AtomicFile.h"
#include "viewer/render/Color.h"

namespace viewer::render {

namespace {

std::string writePfm(const std::filesystem::path& path, const LinearImage& image) {
    io::AtomicFile file(path);
    if (!file.ok()) return file.error();
    // PFM: "PF" (colour), the size, then the scale whose sign gives the byte order (negative:
    // little-endian); rows run bottom to top.
    const double scale = std::endian::native == std::endian::little ? -1.0 : 1.0;
    std::fprintf(file.stream(), "PF\n%d %d\n%.1f\n", image.width, image.height, scale);
    const size_t rowFloats = size_t(image.width) * 3;
    for (int y = image.height - 1; y >= 0; --y) {
        const float* row = image.rgb.data() + size_t(y) * rowFloats;
        if (std::fwrite(row, sizeof(float), rowFloats, file.stream()) != rowFloats) {
            file.fail("cannot write '" + path.string() + "': short write");
            return file.error();
        }
    }
    if (!file.commit()) return file.error();
    return {};
}

}  // namespace

io::Rgb8Image encodeSrgb(const LinearImage& image) {
    io::Rgb8Image out(image.width, image.height);
    for (size_t i = 0; i < image.rgb.size(); ++i) out.pixels[i] = linearToSrgb8(image.rgb[i]);
    return out;
}

std::string writeImage(const std::filesystem::path& path, ImageFormat format,
                       const LinearImage& image) {
    if (format == ImageFormat::Pfm) return writePfm(path, image);
    return io::writePng(path, encodeSrgb(image));
}

}  // namespace viewer::render
