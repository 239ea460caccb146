// The options of `csgray render --help` no other test runs through the binary (issue 24): --aa,
// --no-shadows, --min-weight and --format, each against what the help says it does. Images are
// read back as PFM (linear floats) here; the scenes are tests/RenderScenes.h's.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "tests/RenderScenes.h"
#include "tests/TempDir.h"

namespace {

namespace fs = std::filesystem;
using csg::testing::facingMirrors;
using csg::testing::planeUnder;
using csg::testing::TempDir;

// The exit status of `csgray render PART -o OUT --quiet ARGS` in dir (stderr to dir/stderr).
int runRender(const fs::path& dir, const std::string& source, const std::string& out,
              const std::string& args) {
    std::ofstream(dir / "part.scad") << source;
    const std::string command = std::string(CSGRAY_EXE) + " render '" +
                                (dir / "part.scad").string() + "' -o '" + (dir / out).string() +
                                "' --quiet " + args + " 2>'" + (dir / "stderr").string() + "'";
    return std::system(command.c_str());
}

// A PFM's linear floats, rows top to bottom (the file stores them bottom to top).
struct Pfm {
    int width = 0, height = 0;
    std::vector<float> rgb;
    std::array<double, 3> at(int i, int j) const {
        const float* p = &rgb[(size_t(j) * width + i) * 3];
        return {p[0], p[1], p[2]};
    }
};

Pfm readPfm(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::string magic;
    double scale;
    Pfm p;
    in >> magic >> p.width >> p.height >> scale;
    in.get();
    if (magic != "PF" || scale >= 0 || p.width <= 0 || p.height <= 0) return {};
    std::vector<float> bottomUp(size_t(p.width) * p.height * 3);
    in.read(reinterpret_cast<char*>(bottomUp.data()), std::streamsize(bottomUp.size() * 4));
    const size_t row = size_t(p.width) * 3;
    p.rgb.resize(bottomUp.size());
    for (int j = 0; j < p.height; ++j)
        std::copy_n(&bottomUp[size_t(p.height - 1 - j) * row], row, &p.rgb[size_t(j) * row]);
    return p;
}

// --aa N: N x N stratified samples averaged. A lit square whose left edge x = 0.125 lies a
// quarter into pixel column 4 (which spans x in [0, 0.5] in planeUnder()'s 4 x 4 view of
// 8 x 8 pixels) and on a boundary of its 4 x 4 strata: 12 of the 16 samples see the square
// whatever the jitter inside a stratum, so the pixel is 3/4 square + 1/4 background, while
// one sample per pixel (its centre, x = 0.25) sees only the square. Square and background
// are read from pixels wholly inside them; float rounding of a 16-sample mean: 1e-6.
TEST(RenderCommand, AaAveragesStratifiedSamples) {
    const TempDir temp("render_aa");
    const std::string source =
        "camera(eye = [0, 0, 1], center = [0, 0, -9], up = [0, 1, 0], fov = 2 * atan(0.2), "
        "projection = \"orthographic\");\n"
        "material(color = [0.2, 0.3, 0.4], ambient = 1, diffuse = 0, specular = 0) "
        "translate([0.125, -10, -1]) cube([10, 20, 1]);\n";
    ASSERT_EQ(runRender(temp.path, source, "one.pfm", "--size 8x8"), 0);
    ASSERT_EQ(runRender(temp.path, source, "aa.pfm", "--size 8x8 --aa 4"), 0);
    const Pfm one = readPfm(temp.path / "one.pfm"), aa = readPfm(temp.path / "aa.pfm");
    ASSERT_EQ(aa.width, 8);
    ASSERT_EQ(one.width, 8);
    for (int j = 0; j < 8; ++j) {
        const std::array<double, 3> square = aa.at(6, j), background = aa.at(1, j);
        ASSERT_GT(std::abs(square[0] - background[0]), 0.1) << "the square must show";
        for (int c = 0; c < 3; ++c) {
            EXPECT_NEAR(aa.at(4, j)[c], 0.75 * square[c] + 0.25 * background[c], 1e-6) << j;
            EXPECT_NEAR(one.at(4, j)[c], one.at(6, j)[c], 1e-6) << j;
            EXPECT_NEAR(aa.at(3, j)[c], background[c], 1e-6) << j;
        }
    }
}

// --no-shadows: the plane of planeUnder() under an opaque bar, lit from straight above: with
// shadows the left half is black (ambient 0); without, every pixel is Lambert's cosine of the
// light over the plane, computed here, and the stats count no shadow ray.
TEST(RenderCommand, NoShadowsLightsEverySurfaceFacingTheLight) {
    const TempDir temp("render_noshadows");
    const std::string source =
        planeUnder("material(ambient = 0) translate([-10, -10, 2]) cube([10, 20, 1]);\n");
    ASSERT_EQ(runRender(temp.path, source, "on.pfm", "--size 8x8"), 0);
    ASSERT_EQ(runRender(temp.path, source, "off.pfm",
                        "--size 8x8 --no-shadows --stats '" + (temp.path / "s.json").string() + "'"),
              0);
    const Pfm on = readPfm(temp.path / "on.pfm"), off = readPfm(temp.path / "off.pfm");
    ASSERT_EQ(on.width, 8);
    ASSERT_EQ(off.width, 8);
    for (int j = 0; j < 8; ++j) {
        for (int i = 0; i < 8; ++i) {
            // The cosine at the pixel's centre (x, y, 0) of the light at (0, 0, 100).
            const double x = -2.0 + (i + 0.5) / 2.0, y = 2.0 - (j + 0.5) / 2.0;
            const double lambert = 100.0 / std::sqrt(x * x + y * y + 100.0 * 100.0);
            EXPECT_NEAR(off.at(i, j)[1], lambert, 1e-6) << i << "," << j;
            EXPECT_NEAR(on.at(i, j)[1], i < 4 ? 0.0 : lambert, 1e-6) << i << "," << j;
        }
    }
    const nlohmann::json stats = nlohmann::json::parse(std::ifstream(temp.path / "s.json"));
    EXPECT_EQ(stats["rays"]["shadow"], 0);
}

// --min-weight W: facing mirrors of reflect 0.5 cast a reflection while its weight 0.5^k is
// at least W: k <= 8 for the default 1/256, k <= 4 for W = 1/16.
TEST(RenderCommand, MinWeightEndsTheRayTree) {
    const TempDir temp("render_minweight");
    const std::string stats = "--stats '" + (temp.path / "s.json").string() + "'";
    ASSERT_EQ(runRender(temp.path, facingMirrors(0.5), "a.png", "--size 20x10 " + stats), 0);
    EXPECT_EQ(nlohmann::json::parse(std::ifstream(temp.path / "s.json"))["rays"]["reflection"],
              8 * 200);
    ASSERT_EQ(runRender(temp.path, facingMirrors(0.5), "b.png",
                        "--size 20x10 --min-weight 0.0625 " + stats),
              0);
    EXPECT_EQ(nlohmann::json::parse(std::ifstream(temp.path / "s.json"))["rays"]["reflection"],
              4 * 200);
}

// --format exr writes OpenEXR whatever the extension (its magic number 76 2f 31 01), and
// --format png a PNG (its 8-byte signature).
TEST(RenderCommand, FormatOverridesTheExtension) {
    const TempDir temp("render_format");
    const std::string source = "cube(1);\n";
    ASSERT_EQ(runRender(temp.path, source, "image.out", "--size 8x6 --format exr"), 0);
    std::string bytes(4, '\0');
    std::ifstream(temp.path / "image.out", std::ios::binary).read(bytes.data(), 4);
    EXPECT_EQ(bytes, std::string("\x76\x2f\x31\x01", 4));
    ASSERT_EQ(runRender(temp.path, source, "image.img", "--size 8x6 --format png"), 0);
    std::string png(8, '\0');
    std::ifstream(temp.path / "image.img", std::ios::binary).read(png.data(), 8);
    EXPECT_EQ(png, std::string("\x89PNG\r\n\x1a\n", 8));
}

}  // namespace
