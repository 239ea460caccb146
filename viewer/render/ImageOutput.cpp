#include "viewer/render/ImageOutput.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdio>

#include "io/AtomicFile.h"
#include "viewer/render/Color.h"
#include "viewer/render/ExrOutput.h"

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
    // The 8-bit code of a linear value is the number of code boundaries below it: boundary k
    // is the linear value whose sRGB encoding is (k + 0.5) / 255, where rounding moves from
    // code k to k + 1. Counting them gives exactly linearToSrgb8 without a pow() per channel.
    static const std::array<float, 255> boundaries = [] {
        std::array<float, 255> b{};
        for (int k = 0; k < 255; ++k) {
            // The float nearest the exact boundary, nudged so that the float comparison below
            // agrees with linearToSrgb8 on every float (checked by the test Output.*).
            float f = float(srgbToLinear((k + 0.5) / 255.0));
            while (linearToSrgb8(f) <= k) f = std::nextafter(f, 2.0f);
            while (f > 0.0f && linearToSrgb8(std::nextafter(f, 0.0f)) > k)
                f = std::nextafter(f, 0.0f);
            b[k] = f;
        }
        return b;
    }();
    // The count is started from a table indexed by the top 16 bits of the float (sign,
    // exponent, 7 mantissa bits): positive floats order as their bits do, so the code of the
    // smallest float of each bucket is a lower bound, and at most a few boundaries lie inside
    // one bucket. Floats from 1.0 (bucket kOne) up encode as 255.
    constexpr uint32_t kOne = std::bit_cast<uint32_t>(1.0f) >> 16;
    static const std::array<uint8_t, kOne> bucketStart = [] {
        std::array<uint8_t, kOne> s{};
        for (uint32_t i = 0; i < kOne; ++i) {
            const float first = std::bit_cast<float>(i << 16);
            s[i] = uint8_t(std::upper_bound(boundaries.begin(), boundaries.end(), first) -
                           boundaries.begin());
        }
        return s;
    }();
    io::Rgb8Image out(image.width, image.height);
    for (size_t i = 0; i < image.rgb.size(); ++i) {
        const float v = image.rgb[i];
        // NaN (never expected) encodes as 0, like a negative value.
        if (!(v > 0.0f)) {
            out.pixels[i] = 0;
            continue;
        }
        const uint32_t bucket = std::bit_cast<uint32_t>(v) >> 16;
        if (bucket >= kOne) {
            out.pixels[i] = 255;
            continue;
        }
        unsigned code = bucketStart[bucket];
        while (code < 255 && boundaries[code] <= v) ++code;
        out.pixels[i] = uint8_t(code);
    }
    return out;
}

std::string writeImage(const std::filesystem::path& path, ImageFormat format,
                       const LinearImage& image) {
    if (format == ImageFormat::Pfm) return writePfm(path, image);
    if (format == ImageFormat::Exr) return writeExr(path, image);
    return io::writePng(path, encodeSrgb(image));
}

}  // namespace viewer::render
