#include "viewer/render/ImageOutput.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdio>
#include <limits>
#include <utility>

#include "primitives/base/AtomicFile.h"
#include "viewer/render/Color.h"
#include "viewer/render/ExrOutput.h"

namespace viewer::render {

namespace {

std::string writePfm(const std::filesystem::path& path, const LinearImage& image) {
    csg::AtomicFile file(path);
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

// The 8-bit code of a linear value is the number of code boundaries below it: boundary k is
// the linear value whose sRGB encoding is (k + 0.5) / 255, where rounding moves from code k to
// k + 1. Counting them gives exactly linearToSrgb8 without a pow() per channel.
class SrgbEncoder {
public:
    SrgbEncoder() {
        for (int k = 0; k < 255; ++k) {
            // The float nearest the exact boundary, nudged so that the float comparison below
            // agrees with linearToSrgb8 on every float (checked by the test Output.*).
            float f = float(srgbToLinear((k + 0.5) / 255.0));
            while (linearToSrgb8(f) <= k) f = std::nextafter(f, 2.0f);
            while (f > 0.0f && linearToSrgb8(std::nextafter(f, 0.0f)) > k)
                f = std::nextafter(f, 0.0f);
            boundaries_[k] = f;
        }
        boundaries_[255] = std::numeric_limits<float>::infinity();  // nothing passes code 255
        // Positive floats order as their bits do, so the code of a bucket's smallest float
        // (buckets: the top 16 bits, i.e. exponent and 7 mantissa bits) starts the count.
        for (uint32_t bucket = 0; bucket <= kOne; ++bucket)
            bucketStart_[bucket] =
                uint8_t(std::upper_bound(boundaries_.begin(), boundaries_.end() - 1,
                                         std::bit_cast<float>(bucket << 16)) -
                        boundaries_.begin());
    }

    uint8_t operator()(float v) const {
        // Clamped to [0, 1] first, without branches: negatives and NaN (never expected) to 0
        // (std::max(0, NaN) is its first argument), so they encode as 0; 1 and above to 1,
        // whose bucket starts at 255.
        const float c = std::min(std::max(0.0f, v), 1.0f);
        // A bucket spans at most 1/128 of its smallest value, less than one code step anywhere
        // on the curve (a step is at least 2.4 / (1.055 * 255) ~ 1/112 of the value on the
        // power part, 1/code on the linear part), so at most one boundary lies inside it: one
        // comparison finishes the count. (Checked on all 2^32 floats against the earlier
        // encoder, which counted boundaries in a loop: the same bytes.)
        const unsigned start = bucketStart_[std::bit_cast<uint32_t>(c) >> 16];
        return uint8_t(start + (c >= boundaries_[start] ? 1u : 0u));
    }

private:
    static constexpr uint32_t kOne = std::bit_cast<uint32_t>(1.0f) >> 16;
    std::array<float, 256> boundaries_{};
    std::array<uint8_t, kOne + 1> bucketStart_{};
};

}  // namespace

void encodeSrgb(const float* linear, size_t count, uint8_t* out) {
    static const SrgbEncoder encode;
    for (size_t i = 0; i < count; ++i) out[i] = encode(linear[i]);
}

Rgb8Image encodeSrgb(const LinearImage& image) {
    Rgb8Image out(image.width, image.height);
    encodeSrgb(image.rgb.data(), image.rgb.size(), out.pixels.data());
    return out;
}

PixelStore pixelStoreFor(ImageFormat format) {
    return format == ImageFormat::Png ? PixelStore::Srgb8 : PixelStore::LinearFloat;
}

std::string writeImage(const std::filesystem::path& path, ImageFormat format,
                       RenderResult& render) {
    if (!render.srgb.pixels.empty() && format == ImageFormat::Png)
        return writePng(path, std::move(render.srgb));
    return writeImage(path, format, render.image);
}

std::string writeImage(const std::filesystem::path& path, ImageFormat format,
                       const LinearImage& image) {
    if (format == ImageFormat::Pfm) return writePfm(path, image);
    if (format == ImageFormat::Exr) return writeExr(path, image);
    return writePng(path, encodeSrgb(image));
}

}  // namespace viewer::render
