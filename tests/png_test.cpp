// PNG output (viewer/render/PngWriter.h): images written by our own chunk writer and libdeflate
// come back byte for byte through viewer/render/PngReader, which decodes with libpng (an
// independent decoder that checks the zlib stream, its Adler-32 and every critical chunk's CRC).
// Failed writes leave no file.
#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <utility>
#include <vector>

#include "tests/SeededRng.h"
#include "tests/TempDir.h"
#include "viewer/render/PngReader.h"
#include "viewer/render/PngWriter.h"

namespace viewer::render {
namespace {

namespace fs = std::filesystem;

using csg::testing::TempDir;

Rgb8Image randomImage(int width, int height, uint64_t seed) {
    csg::testing::Rng rng(seed);
    Rgb8Image image(width, height);
    for (uint8_t& byte : image.pixels) byte = uint8_t(rng.index(256));
    return image;
}

// Smooth ramps in x and y with a diagonal band, the kind of content Up filtering turns into
// long runs: what a render mostly is.
Rgb8Image gradientImage(int width, int height) {
    Rgb8Image image(width, height);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            uint8_t* p = image.row(y) + size_t(x) * 3;
            p[0] = uint8_t(x * 255 / std::max(1, width - 1));
            p[1] = uint8_t(y * 255 / std::max(1, height - 1));
            p[2] = (x + y) % 64 < 32 ? 40 : 200;
        }
    return image;
}

std::string fileBytes(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// The number of chunks of the given type, walking the file by the chunks' lengths.
int countChunks(const fs::path& path, const std::string& type) {
    const std::string bytes = fileBytes(path);
    int count = 0;
    for (size_t at = 8; at + 8 <= bytes.size();) {
        uint32_t length = 0;
        for (int i = 0; i < 4; ++i) length = length << 8 | uint8_t(bytes[at + i]);
        if (bytes.compare(at + 4, 4, type) == 0) ++count;
        at += 12 + size_t(length);
    }
    return count;
}

// Written from a const image, and again from a copy that writePng filters in place (with the
// spare bytes a render reserves, and without): the same file, which decodes to the pixels.
void expectRoundTrip(const Rgb8Image& written, const fs::path& path) {
    ASSERT_EQ(writePng(path, written), "");
    Rgb8Image read;
    ASSERT_EQ(readPng(path, read), "") << path;
    ASSERT_EQ(read.width, written.width);
    ASSERT_EQ(read.height, written.height);
    EXPECT_TRUE(read.pixels == written.pixels)
        << written.width << "x" << written.height << " decodes to other bytes";
    for (const bool reserve : {true, false}) {
        Rgb8Image spent(written.width, written.height);
        if (reserve) spent.reserveFilterBytes();
        spent.pixels = written.pixels;
        const fs::path again = fs::path(path).replace_extension(".inplace.png");
        ASSERT_EQ(writePng(again, std::move(spent)), "");
        EXPECT_TRUE(spent.pixels.empty());
        EXPECT_EQ(fileBytes(again), fileBytes(path)) << written.width << "x" << written.height;
        fs::remove(again);
    }
}

TEST(PngWriter, RandomImagesOfManyShapesDecodeToTheSameBytes) {
    const TempDir dir("io_png_test_random");
    // 1x1, single rows and columns, odd widths (rows not a multiple of 4 bytes), a 1600-pixel
    // row, and 1600x300 of noise: 1.44 MB that does not compress, so the stream spans more
    // than one IDAT chunk.
    const std::vector<std::pair<int, int>> sizes = {{1, 1},  {1, 40},   {40, 1},    {3, 5},
                                                    {17, 9}, {255, 7},  {1600, 1},  {1600, 4},
                                                    {2, 2},  {1601, 3}, {1600, 300}};
    uint64_t seed = 1;
    for (const auto& [w, h] : sizes)
        expectRoundTrip(randomImage(w, h, seed++),
                        dir.path / ("r" + std::to_string(w) + "x" + std::to_string(h) + ".png"));
    EXPECT_GT(countChunks(dir.path / "r1600x300.png", "IDAT"), 1);
    EXPECT_EQ(countChunks(dir.path / "r1x1.png", "IDAT"), 1);
}

TEST(PngWriter, GradientsDecodeToTheSameBytes) {
    const TempDir dir("io_png_test_gradient");
    for (const auto& [w, h] : std::vector<std::pair<int, int>>{{256, 64}, {1, 256}, {1600, 9}})
        expectRoundTrip(gradientImage(w, h),
                        dir.path / ("g" + std::to_string(w) + "x" + std::to_string(h) + ".png"));
}

TEST(PngWriter, CompressesAFlatImage) {
    // A uniform 1000x1000 image (3 MB of pixels) must compress to almost nothing: a writer
    // that stored the rows uncompressed, or filtered them into noise, would fail this.
    const TempDir dir("io_png_test_flat");
    Rgb8Image image(1000, 1000);
    for (size_t i = 0; i < image.pixels.size(); ++i) image.pixels[i] = uint8_t(50 + i % 3 * 60);
    const fs::path path = dir.path / "flat.png";
    expectRoundTrip(image, path);
    EXPECT_LT(fs::file_size(path), 20000u);
}

TEST(PngWriter, ReplacesAnExistingFile) {
    const TempDir dir("io_png_test_replace");
    const fs::path path = dir.path / "out.png";
    std::ofstream(path) << "an older file";
    expectRoundTrip(randomImage(5, 3, 7), path);
    EXPECT_EQ(std::distance(fs::directory_iterator(dir.path), fs::directory_iterator()), 1)
        << "no temporary file is left beside the image";
}

TEST(PngWriter, AnUnwritablePathGivesTheReasonAndNoFile) {
    const TempDir dir("io_png_test_unwritable");
    const fs::path missing = dir.path / "no_such_dir" / "out.png";
    const std::string error = writePng(missing, randomImage(4, 4, 3));
    EXPECT_NE(error, "");
    EXPECT_NE(error.find("no_such_dir"), std::string::npos) << error;
    EXPECT_FALSE(fs::exists(missing));
    EXPECT_TRUE(fs::is_empty(dir.path)) << "nothing is left in the directory";

    // A directory in the file's place: the directory stays and no temporary file remains.
    const fs::path taken = dir.path / "taken.png";
    fs::create_directories(taken);
    EXPECT_NE(writePng(taken, randomImage(4, 4, 4)), "");
    EXPECT_TRUE(fs::is_directory(taken));
    EXPECT_EQ(std::distance(fs::directory_iterator(dir.path), fs::directory_iterator()), 1);
}

TEST(PngWriter, AnImageWithoutPixelsIsRefused) {
    const TempDir dir("io_png_test_empty");
    const fs::path path = dir.path / "empty.png";
    EXPECT_NE(writePng(path, Rgb8Image()), "");
    Rgb8Image inconsistent(4, 4);
    inconsistent.pixels.resize(10);
    EXPECT_NE(writePng(path, inconsistent), "");
    EXPECT_FALSE(fs::exists(path));
}

}  // namespace
}  // namespace viewer::render
