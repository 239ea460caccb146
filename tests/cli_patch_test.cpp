// Bezier patches end to end through the csgray command line: probe reports a surface's
// crossings as zero-length spans with normals facing the ray's origin, the teapot sample
// renders, and commands that need a volume reject a surface at its file:line:col.
#include <png.h>

#include <cmath>

#include "CliRunner.h"

namespace {

using namespace cli;

TEST(CliPatch, ProbeListsEachCrossingOfASurfaceWithTheNormalTowardTheOrigin) {
    ScratchDir dir;
    // A flat patch in z = 1 over [0, 3]^2, written with its normal along +z (u along x).
    std::string points = "[";
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j)
            points += "[" + std::to_string(i) + ", " + std::to_string(j) + ", 1]" +
                      (i == 3 && j == 3 ? "]" : ", ");
    writeFile(dir / "flat.scad", "bezier_patch(" + points + ");\n");
    for (double sign : {1.0, -1.0}) {
        const RunResult r =
            runCsgray({"probe", (dir / "flat.scad").string(), "--origin",
                       sign > 0 ? "1,2,5" : "1,2,-3", "--dir", sign > 0 ? "0,0,-1" : "0,0,1"},
                      dir.path());
        ASSERT_EQ(r.exitCode, 0) << r.err;
        const auto json = nlohmann::json::parse(r.out);
        ASSERT_EQ(json.at("spans").size(), 1u) << r.out;
        const auto& span = json.at("spans")[0];
        EXPECT_NEAR(span.at("in").at("t").get<double>(), 4.0, 1e-12);
        EXPECT_EQ(span.at("in").at("t"), span.at("out").at("t"));
        EXPECT_EQ(span.at("in").at("point"), span.at("out").at("point"));
        // The side facing the origin: +z from above, -z from below.
        EXPECT_NEAR(span.at("in").at("normal")[2].get<double>(), sign, 1e-12) << r.out;
        EXPECT_NEAR(span.at("out").at("normal")[2].get<double>(), sign, 1e-12) << r.out;
    }
}

TEST(CliPatch, ExportAndCompareRejectASurfaceAtItsLine) {
    ScratchDir dir;
    std::string points = "[";
    for (int k = 0; k < 16; ++k)
        points += "[" + std::to_string(k / 4) + ", " + std::to_string(k % 4) + ", 0]" +
                  (k == 15 ? "]" : ", ");
    writeFile(dir / "sheet.scad", "cube(1);\n  bezier_patch(" + points + ");\n");
    const RunResult r = runCsgray(
        {"export", (dir / "sheet.scad").string(), "-o", (dir / "out.obj").string()}, dir.path());
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_NE(r.err.find("sheet.scad:2:3: error: export: a surface (solid=false) has no volume"),
              std::string::npos)
        << r.err;
    EXPECT_FALSE(fs::exists(dir / "out.obj"));
    writeFile(dir / "mesh.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    const RunResult c = runCsgray(
        {"compare", (dir / "sheet.scad").string(), (dir / "mesh.obj").string()}, dir.path());
    EXPECT_EQ(c.exitCode, 1);
    EXPECT_NE(c.err.find("sheet.scad:2:3: error: compare: a surface"), std::string::npos) << c.err;
}

TEST(CliPatch, TheTeapotRenders) {
    ScratchDir dir;
    const fs::path png = dir / "teapot.png";
    const RunResult r = runCsgray(
        {"render", samplePath("teapot.scad").string(), "-o", png.string(), "--size", "96x72"},
        dir.path());
    ASSERT_EQ(r.exitCode, 0) << r.err;
    png_image image{};
    image.version = PNG_IMAGE_VERSION;
    ASSERT_TRUE(png_image_begin_read_from_file(&image, png.c_str()));
    image.format = PNG_FORMAT_RGB;
    std::vector<uint8_t> rgb(PNG_IMAGE_SIZE(image));
    ASSERT_TRUE(png_image_finish_read(&image, nullptr, rgb.data(), 0, nullptr));
    ASSERT_EQ(image.width, 96u);
    ASSERT_EQ(image.height, 72u);
    // The corner is background; the teapot (red) covers a good part of the frame but not all.
    int teapot = 0;
    for (size_t i = 0; i < rgb.size(); i += 3)
        teapot += !(rgb[i] == rgb[0] && rgb[i + 1] == rgb[1] && rgb[i + 2] == rgb[2]);
    const double fraction = double(teapot) / (96 * 72);
    EXPECT_GT(fraction, 0.15);
    EXPECT_LT(fraction, 0.8);
    // Both sides are shaded: no pixel of the teapot is black (a normal facing away from the
    // eye would light the inside of the spout and the lid gap as black).
    int black = 0;
    for (size_t i = 0; i < rgb.size(); i += 3) black += rgb[i] + rgb[i + 1] + rgb[i + 2] == 0;
    EXPECT_EQ(black, 0);
}

}  // namespace
