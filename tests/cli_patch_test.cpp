// Bezier patches end to end through the csgray command line: probe reports a surface's
// crossings as zero-length spans with normals facing the ray's origin, the teapot sample
// renders the silhouette its patches have by the textbook formula, and commands that need a
// volume reject a surface at its file:line:col.

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <vector>

#include "CliRunner.h"
#include "PngImage.h"

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

// The numbers of the sample's list `name = [...];`, in order (signs and decimals as written).
std::vector<double> listNumbers(const std::string& text, const std::string& name) {
    const size_t begin = text.find(name + " = [");
    const size_t end = text.find("];", begin);
    EXPECT_NE(begin, std::string::npos) << name;
    std::vector<double> numbers;
    for (size_t i = begin + name.size() + 3; i < end;) {
        const char c = text[i];
        if (std::isdigit(static_cast<unsigned char>(c)) || c == '-' || c == '.') {
            char* stop = nullptr;
            numbers.push_back(std::strtod(text.c_str() + i, &stop));
            i = size_t(stop - text.c_str());
        } else {
            ++i;
        }
    }
    return numbers;
}

using Point = std::array<double, 3>;

double dot(const Point& a, const Point& b) {
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
Point minus(const Point& a, const Point& b) {
    return {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
}
Point cross(const Point& a, const Point& b) {
    return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
Point unit(const Point& a) {
    const double n = std::sqrt(dot(a, a));
    return {a[0] / n, a[1] / n, a[2] / n};
}

// Which pixel centres of a width x height image see the teapot, found without csgray: each
// patch evaluated by the Bernstein formula on an n x n grid, every grid triangle projected by
// the sample's pinhole camera (eye, centre, up z, vertical fov), pixel centres tested against
// the projected triangles' edges.
std::vector<uint8_t> teapotCoverage(int width, int height, int n) {
    const std::string text = csg::testing::readFile(samplePath("teapot.scad"));
    const std::vector<double> points = listNumbers(text, "teapot_points");
    const std::vector<double> patches = listNumbers(text, "teapot_patches");
    EXPECT_EQ(points.size(), 306u * 3) << "Newell's 306 control points";
    EXPECT_EQ(patches.size(), 32u * 16) << "Newell's 32 patches";
    // camera(eye = [6.5, -9.0, 5.5], center = [0.2, 0, 1.4], fov = 32) in the sample.
    const Point eye{6.5, -9.0, 5.5};
    const Point forward = unit(minus({0.2, 0.0, 1.4}, eye));
    const Point right = unit(cross(forward, {0.0, 0.0, 1.0}));
    const Point up = cross(right, forward);
    const double halfHeight = std::tan(32.0 / 2 * M_PI / 180);
    const double aspect = double(width) / height;
    auto project = [&](const Point& p) {
        const Point q = minus(p, eye);
        const double depth = dot(q, forward);
        return std::array<double, 2>{
            (dot(q, right) / depth / (halfHeight * aspect) + 1) * width / 2,
            (1 - dot(q, up) / depth / halfHeight) * height / 2};
    };
    auto bernstein = [](double t) {
        const double s = 1 - t;
        return std::array<double, 4>{s * s * s, 3 * t * s * s, 3 * t * t * s, t * t * t};
    };
    std::vector<uint8_t> covered(size_t(width) * height, 0);
    auto fill = [&](const std::array<double, 2>& a, const std::array<double, 2>& b,
                    const std::array<double, 2>& c) {
        auto edge = [](const std::array<double, 2>& p, const std::array<double, 2>& q, double x,
                       double y) {
            return (q[0] - p[0]) * (y - p[1]) - (q[1] - p[1]) * (x - p[0]);
        };
        const int x0 = std::max(0, int(std::floor(std::min({a[0], b[0], c[0]}))));
        const int x1 = std::min(width - 1, int(std::ceil(std::max({a[0], b[0], c[0]}))));
        const int y0 = std::max(0, int(std::floor(std::min({a[1], b[1], c[1]}))));
        const int y1 = std::min(height - 1, int(std::ceil(std::max({a[1], b[1], c[1]}))));
        for (int y = y0; y <= y1; ++y)
            for (int x = x0; x <= x1; ++x) {
                const double e0 = edge(a, b, x + 0.5, y + 0.5), e1 = edge(b, c, x + 0.5, y + 0.5),
                             e2 = edge(c, a, x + 0.5, y + 0.5);
                if ((e0 >= 0 && e1 >= 0 && e2 >= 0) || (e0 <= 0 && e1 <= 0 && e2 <= 0))
                    covered[size_t(y) * width + x] = 1;
            }
    };
    for (size_t patch = 0; patch + 16 <= patches.size(); patch += 16) {
        std::vector<std::array<double, 2>> grid;
        for (int i = 0; i <= n; ++i)
            for (int j = 0; j <= n; ++j) {
                const auto bu = bernstein(double(i) / n), bv = bernstein(double(j) / n);
                Point p{0, 0, 0};
                for (int k = 0; k < 16; ++k)
                    for (int axis = 0; axis < 3; ++axis)
                        p[axis] +=
                            bu[k / 4] * bv[k % 4] * points[size_t(patches[patch + k]) * 3 + axis];
                grid.push_back(project(p));
            }
        for (int i = 0; i < n; ++i)
            for (int j = 0; j < n; ++j) {
                const auto& a = grid[i * (n + 1) + j];
                const auto& b = grid[i * (n + 1) + j + 1];
                const auto& c = grid[(i + 1) * (n + 1) + j];
                const auto& d = grid[(i + 1) * (n + 1) + j + 1];
                fill(a, b, d);
                fill(a, d, c);
            }
    }
    return covered;
}

TEST(CliPatch, TheTeapotRendersItsOwnSilhouette) {
    ScratchDir dir;
    const int width = 160, height = 120;
    const fs::path png = dir / "teapot.png";
    const RunResult r = runCsgray(
        {"render", samplePath("teapot.scad").string(), "-o", png.string(), "--size", "160x120"},
        dir.path());
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const csg::testing::RgbImage image = csg::testing::readPng(png);
    const std::vector<uint8_t>& rgb = image.rgb;
    ASSERT_EQ(image.width, width);
    ASSERT_EQ(image.height, height);

    // The oracle's chords: 48 x 48 cells a patch put a chord at most h^2 / (8 r) from the
    // surface; with cells h <= 0.065 (a body patch's quarter turn of radius 2 is 3.1 long) and
    // radii r >= 0.1 (the spout's lip, the lid's knob) that is 0.0053 units, under a tenth of a
    // pixel (the view is 2 tan 16 deg x 12.6 = 7.2 units over 120 pixels, 0.06 units each, at
    // the teapot's distance). So a pixel may disagree only where its centre lies that close to
    // the silhouette: on the oracle's outline (a pixel with a 4-neighbour of the other kind,
    // a band two pixels wide), and on at most a tenth of those (a band 2 x 0.09 pixel wide).
    // A render shifted by half a pixel disagrees on 113 of the 579 outline pixels, by a whole
    // pixel on 220; this one on none.
    const std::vector<uint8_t> oracle = teapotCoverage(width, height, 48);
    int disagree = 0, offOutline = 0, outline = 0, teapot = 0;
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const size_t i = size_t(y) * width + x;
            const uint8_t* px = &rgb[3 * i];
            // The corner is background (the camera leaves it empty in both).
            const bool rendered = !(px[0] == rgb[0] && px[1] == rgb[1] && px[2] == rgb[2]);
            bool onOutline = false;
            for (auto [dx, dy] : {std::pair{1, 0}, {-1, 0}, {0, 1}, {0, -1}}) {
                const int nx = x + dx, ny = y + dy;
                if (nx >= 0 && ny >= 0 && nx < width && ny < height &&
                    oracle[size_t(ny) * width + nx] != oracle[i])
                    onOutline = true;
            }
            teapot += oracle[i];
            outline += onOutline;
            if (rendered != bool(oracle[i])) {
                ++disagree;
                offOutline += !onOutline;
            }
        }
    EXPECT_GT(teapot, width * height / 10) << "the oracle sees too little teapot";
    EXPECT_EQ(offOutline, 0) << disagree << " pixels disagree";
    EXPECT_LE(disagree, outline / 10) << "of " << outline << " outline pixels";

    // Both sides are shaded: no pixel of the teapot is black (a normal facing away from the
    // eye would light the inside of the spout and the lid gap as black).
    int black = 0;
    for (size_t i = 0; i < rgb.size(); i += 3) black += rgb[i] + rgb[i + 1] + rgb[i + 2] == 0;
    EXPECT_EQ(black, 0);
}

}  // namespace
