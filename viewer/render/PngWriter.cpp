#include "viewer/render/PngWriter.h"

#include <libdeflate.h>

#include <algorithm>
#include <array>
#include <cstring>
#include <memory>
#include <utility>

#include "primitives/base/AtomicFile.h"

namespace viewer::render {

namespace {

// libdeflate's level 2: of zlib's level 1 and libdeflate's levels 1-6 it compressed csg_grid's
// 1600x1600 rows in the least CPU time, with a smaller file than zlib's. Level 1 runs fewer
// instructions yet takes longer (not investigated); CPU time is what render is judged by, so
// it decided (bench/README.md, the image output path after 9546402, has every level's figures).
constexpr int kDeflateLevel = 2;

// The compressed stream is cut into IDAT chunks of at most this many bytes. Any size up to
// 2^31 - 1 is valid PNG; a bounded one keeps each chunk's length far from that limit for the
// largest images render accepts (2^28 pixels), and decoders handle many chunks routinely.
constexpr size_t kMaxIdatBytes = size_t(1) << 20;

struct CompressorDeleter {
    void operator()(libdeflate_compressor* c) const { libdeflate_free_compressor(c); }
};

void putBigEndian32(uint8_t* out, uint32_t v) {
    out[0] = uint8_t(v >> 24);
    out[1] = uint8_t(v >> 16);
    out[2] = uint8_t(v >> 8);
    out[3] = uint8_t(v);
}

// One chunk: its data's length, type, data, and the CRC-32 of type and data. False when the
// stream refused a byte.
bool writeChunk(std::FILE* stream, const char (&type)[5], const uint8_t* data, size_t size) {
    std::array<uint8_t, 8> head{};
    putBigEndian32(head.data(), uint32_t(size));
    std::memcpy(head.data() + 4, type, 4);
    uint32_t crc = libdeflate_crc32(0, head.data() + 4, 4);
    if (size > 0) crc = libdeflate_crc32(crc, data, size);
    std::array<uint8_t, 4> tail{};
    putBigEndian32(tail.data(), crc);
    return std::fwrite(head.data(), 1, head.size(), stream) == head.size() &&
           (size == 0 || std::fwrite(data, 1, size, stream) == size) &&
           std::fwrite(tail.data(), 1, tail.size(), stream) == tail.size();
}

// out[i] = current[i] - above[i] (mod 256). The fixed-size blocks through a local array let
// the compiler vectorize at -O2 without an overlap check (out is a third buffer): a block
// takes a few vector instructions instead of several per byte (bench/README.md).
void upFilterRow(uint8_t* out, const uint8_t* current, const uint8_t* above, size_t size) {
    constexpr size_t kBlock = 32;
    size_t i = 0;
    for (; i + kBlock <= size; i += kBlock) {
        std::array<uint8_t, kBlock> block;
        for (size_t j = 0; j < kBlock; ++j) block[j] = uint8_t(current[i + j] - above[i + j]);
        std::memcpy(out + i, block.data(), kBlock);
    }
    for (; i < size; ++i) out[i] = uint8_t(current[i] - above[i]);
}

// The scanlines as PNG compresses them, made in the pixels' own buffer: each row preceded by its
// filter type byte. Every row but the first uses Up (each byte minus the one above), the first
// None (Up against the all-zero row above it would give the same bytes). Up alone instead of an
// adaptive choice among the five filters per row: libpng's adaptive choice cost more than the
// compression on csg_grid at 1600x1600 and gave a slightly larger file. Last row first, each
// row filtered into `row` and moved one byte per row further down, so the row above is still
// whole when its neighbour below is filtered.
void filterRowsInPlace(std::vector<uint8_t>& pixels, int width, int height) {
    const size_t stride = size_t(width) * 3;
    pixels.resize(size_t(height) * (stride + 1));  // within the reserve, if there is one
    std::vector<uint8_t> row(stride);
    for (int y = height - 1; y >= 0; --y) {
        uint8_t* current = pixels.data() + size_t(y) * stride;
        uint8_t* out = pixels.data() + size_t(y) * (stride + 1);
        if (y == 0) {
            std::memmove(out + 1, current, stride);
            out[0] = 0;  // None
            break;
        }
        upFilterRow(row.data(), current, current - stride, stride);
        std::memcpy(out + 1, row.data(), stride);
        out[0] = 2;  // Up
    }
}

bool hasPixels(const Rgb8Image& image) {
    return image.width > 0 && image.height > 0 &&
           image.pixels.size() == size_t(image.width) * size_t(image.height) * 3;
}

}  // namespace

std::string writePng(const std::filesystem::path& path, const Rgb8Image& image) {
    Rgb8Image copy;
    copy.width = image.width;
    copy.height = image.height;
    if (hasPixels(image)) copy.reserveFilterBytes();
    copy.pixels = image.pixels;  // within the reserve: filtering will not move it again
    return writePng(path, std::move(copy));
}

std::string writePng(const std::filesystem::path& path, Rgb8Image&& image) {
    const std::string prefix = "cannot write '" + path.string() + "': ";
    if (!hasPixels(image)) return prefix + "the image has no pixels";

    // Compress before creating the file, so that running out of memory leaves nothing behind.
    const int width = image.width, height = image.height;
    std::vector<uint8_t> filtered = std::move(image.pixels);
    image.pixels.clear();
    filterRowsInPlace(filtered, width, height);
    const std::unique_ptr<libdeflate_compressor, CompressorDeleter> compressor(
        libdeflate_alloc_compressor(kDeflateLevel));
    if (!compressor) return prefix + "out of memory";
    const size_t bound = libdeflate_zlib_compress_bound(compressor.get(), filtered.size());
    // Not value-initialized: deflate writes only what it needs of its bound, and only those
    // pages are touched (first touches of fresh memory ran at ~0.2 GB/s on the benchmark
    // machine, bench/README.md).
    const std::unique_ptr<uint8_t[]> compressed(new uint8_t[bound]);
    const size_t compressedSize = libdeflate_zlib_compress(
        compressor.get(), filtered.data(), filtered.size(), compressed.get(), bound);
    if (compressedSize == 0) return prefix + "compression failed";  // not within its own bound

    csg::AtomicFile file(path);
    if (!file.ok()) return file.error();
    std::FILE* stream = file.stream();

    static constexpr std::array<uint8_t, 8> kSignature = {0x89, 'P',  'N',  'G',
                                                          '\r', '\n', 0x1a, '\n'};
    // IHDR: width, height, 8 bits per sample, colour type 2 (RGB), deflate, adaptive
    // filtering (the only method), no interlace.
    std::array<uint8_t, 13> header{};
    putBigEndian32(header.data(), uint32_t(width));
    putBigEndian32(header.data() + 4, uint32_t(height));
    header[8] = 8;
    header[9] = 2;
    // sRGB: the pixels are sRGB-encoded; rendering intent 0 (perceptual).
    const std::array<uint8_t, 1> intent = {0};
    bool written =
        std::fwrite(kSignature.data(), 1, kSignature.size(), stream) == kSignature.size() &&
        writeChunk(stream, "IHDR", header.data(), header.size()) &&
        writeChunk(stream, "sRGB", intent.data(), intent.size());
    for (size_t at = 0; written && at < compressedSize; at += kMaxIdatBytes)
        written = writeChunk(stream, "IDAT", compressed.get() + at,
                             std::min(kMaxIdatBytes, compressedSize - at));
    written = written && writeChunk(stream, "IEND", nullptr, 0);
    if (!written) {
        file.fail(prefix + "short write");
        return file.error();
    }
    if (!file.commit()) return file.error();
    return {};
}

}  // namespace viewer::render
