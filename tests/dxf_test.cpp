// DXF drawings (io/DxfFile.h, io/DxfModules.h): import(), linear_extrude(file =),
// rotate_extrude(file =), dxf_dim() and dxf_cross(). The oracles are independent of csgray:
//   - small DXF files written here, whose spans along probe lines are worked out by hand
//     (squares, a circle, a bulge's semicircle, a block inserted rotated and scaled, a ring);
//   - OpenSCAD's 1/1024 grid, by hand (a coordinate snaps to round(x 1024) / 1024);
//   - dimensions computed here from the numbers in example009.dxf, and what OpenSCAD 2021
//     (`openscad` on the PATH) echoes for them;
//   - OpenSCAD 2021's own binary STL of the Debian examples that use DXF, and of their DXF
//     layers extruded: its volume by the divergence theorem and its bounding box, read here.
// Notation: t is the parameter of o + t d; probe rays have unit d, so t is a distance.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <map>
#include <sstream>

#include "MissingTool.h"
#include "TempDir.h"
#include "csg/Scene.h"
#include "csg/Volume.h"
#include "io/DxfFile.h"
#include "io/Evaluate.h"
#include "tests/PartHelpers.h"
#include "tests/SeededRng.h"

using namespace io;

namespace {

using Spans = std::vector<std::pair<double, double>>;
namespace fs = std::filesystem;

const fs::path kExamples = "/usr/share/openscad/examples/Old";

// ---- helpers ----

void writeFile(const fs::path& path, const std::string& bytes) {
    std::ofstream(path, std::ios::binary) << bytes;
}

// A DXF file of these entities (group code / value lines, joined by newlines) in its ENTITIES
// section, with a BLOCKS section first when blocks is not empty.
std::string dxf(const std::string& entities, const std::string& blocks = "") {
    std::string out;
    if (!blocks.empty()) out += "0\nSECTION\n2\nBLOCKS\n" + blocks + "0\nENDSEC\n";
    return out + "0\nSECTION\n2\nENTITIES\n" + entities + "0\nENDSEC\n0\nEOF\n";
}

std::string line(double x1, double y1, double x2, double y2, const std::string& layer = "0") {
    std::ostringstream s;
    s.precision(17);
    s << "0\nLINE\n8\n"
      << layer << "\n10\n"
      << x1 << "\n20\n"
      << y1 << "\n11\n"
      << x2 << "\n21\n"
      << y2 << "\n";
    return s.str();
}

// The square [x0, x0 + a] x [y0, y0 + a] as four LINEs, in a scrambled order and direction.
std::string square(double x0, double y0, double a, const std::string& layer = "0") {
    return line(x0 + a, y0 + a, x0 + a, y0, layer) + line(x0, y0, x0 + a, y0, layer) +
           line(x0, y0 + a, x0, y0, layer) + line(x0 + a, y0 + a, x0, y0 + a, layer);
}

using csg::testing::diagnosticsOf;
using csg::testing::firstDiagnostic;

// The part `scad`, written as main.scad in dir; its echo() lines into *echoes when given.
EvaluateResult run(const fs::path& dir, const std::string& scad, CurveMode curves = CurveMode::Auto,
                   std::vector<std::string>* echoes = nullptr) {
    writeFile(dir / "main.scad", scad);
    EvaluateOptions options;
    options.curves = curves;
    options.echo = [echoes](const std::string& line) {
        if (echoes) echoes->push_back(line);
    };
    return evaluateFile(dir / "main.scad", options);
}

csg::Scene compiled(const EvaluateResult& r) {
    EXPECT_TRUE(r.ok()) << diagnosticsOf(r);
    return csg::Scene::compile(r.ok() ? r.model->root : nullptr);
}

constexpr auto* spans = &csg::testing::spanPairs;

void expectSpans(const Spans& got, const Spans& want, double tol = 1e-12) {
    csg::testing::expectSpanPairs(got, want, tol);
}

DxfDrawing readOk(const std::string& text, DxfOptions options = {}) {
    DxfReadResult r = readDxf(text, options);
    EXPECT_TRUE(r.drawing) << r.line << ": " << r.error;
    return r.drawing ? std::move(*r.drawing) : DxfDrawing();
}

// ---- the reader ----

TEST(DxfReader, SquareOfLinesIsOneClosedPathOnGridNodes) {
    // Ends 3e-4 off the corners snap to them: round(x 1024) is the corner's node.
    const std::string text = dxf(line(0, 0, 10, 0) + line(10.0003, 0.0002, 10, 10) +
                                 line(10, 10, 0, 10) + line(0, 10, 0.0002, -0.0003));
    const DxfDrawing d = readOk(text);
    ASSERT_EQ(d.edges.size(), 4u);
    ASSERT_EQ(d.paths.size(), 1u);
    EXPECT_TRUE(d.paths[0].closed);
    EXPECT_EQ(d.paths[0].points.front(), d.paths[0].points.back());
    for (const csg::Segment2& s : d.edges)
        for (const csg::Vec2 p : {s.start(), s.finish()})
            EXPECT_TRUE((p.x == 0 || p.x == 10) && (p.y == 0 || p.y == 10)) << p.x << " " << p.y;
    EXPECT_EQ(d.outline().segments.size(), 4u);
    EXPECT_EQ(d.outline().rule, csg::FillRule::EvenOdd);
}

TEST(DxfReader, CoordinatesSnapToOpenScadsGrid) {
    // 0.3 -> 307.2 -> 307/1024; 5.0007 -> 5120.7 -> 5121/1024. An end whose own node is new
    // takes an existing node of a neighbouring cell: (0.3004, 5.0004) -> (307.6, 5120.4) rounds
    // to node (308, 5120), which is new, and (307, 5121) is its neighbour.
    const DxfDrawing d = readOk(dxf(line(0.3, 5.0007, 2, 2) + line(0.3004, 5.0004, 2, -2)));
    ASSERT_EQ(d.edges.size(), 2u);
    EXPECT_EQ(d.edges[0].start(), csg::Vec2(307.0 / 1024, 5121.0 / 1024));
    EXPECT_EQ(d.edges[1].start(), d.edges[0].start());
    EXPECT_EQ(readOk(dxf(line(0.3004, 5.0004, 2, -2))).edges[0].start(),
              csg::Vec2(308.0 / 1024, 5120.0 / 1024));
    // The two edges meet at their starts: one open path (2, 2) .. (2, -2), closed by
    // OpenSCAD's line back: a triangle.
    ASSERT_EQ(d.paths.size(), 1u);
    EXPECT_FALSE(d.paths[0].closed);
    EXPECT_EQ(d.paths[0].points.size(), 3u);
    EXPECT_EQ(d.outline().segments.size(), 3u);
}

TEST(DxfReader, OriginThenScaleAndLayers) {
    DxfOptions options;
    options.origin = {1, 2};
    options.scale = 2;
    options.layer = "b";
    const DxfDrawing d = readOk(dxf(square(0, 0, 1, "a") + square(5, 6, 1, "b")), options);
    ASSERT_EQ(d.edges.size(), 4u);
    csg::Bounds2 box;
    for (const csg::Segment2& s : d.edges) box.add(s.start()), box.add(s.finish());
    // (x - 1) 2, (y - 2) 2 of [5, 6] x [6, 7].
    EXPECT_EQ(box.lo, csg::Vec2(8, 8));
    EXPECT_EQ(box.hi, csg::Vec2(10, 10));
}

TEST(DxfReader, CurvesExactOrAsOpenScadsChords) {
    const std::string text =
        dxf("0\nCIRCLE\n8\n0\n10\n1\n20\n2\n40\n4\n"
            "0\nARC\n8\n0\n10\n0\n20\n0\n40\n10\n50\n0\n51\n90\n");
    DxfOptions exact;
    exact.faceted = false;
    const DxfDrawing d = readOk(text, exact);
    ASSERT_EQ(d.edges.size(), 2u);
    EXPECT_EQ(d.edges[0].kind, csg::Segment2::Kind::Arc);
    EXPECT_EQ(d.edges[0].start(), csg::Vec2(5, 2));
    EXPECT_EQ(d.edges[0].finish(), csg::Vec2(5, 2));
    EXPECT_EQ(d.edges[1].start(), csg::Vec2(10, 0));
    EXPECT_EQ(d.edges[1].finish(), csg::Vec2(0, 10));
    // $fn = 6: the circle is 6 chords, the quarter arc ceil(6 / 4) = 2.
    DxfOptions faceted;
    faceted.fragments.fn = 6;
    const DxfDrawing f = readOk(text, faceted);
    EXPECT_EQ(f.edges.size(), 8u);
    // $fa = 12, $fs = 2: r = 4 gets ceil(2 pi 4 / 2) = 13, r = 10 ceil(360 / 12) = 30, 8 of them
    // for a quarter.
    const DxfDrawing g = readOk(text, DxfOptions());
    EXPECT_EQ(g.edges.size(), 13u + 8u);
}

TEST(DxfReader, InsertRotatesScalesAndMovesABlock) {
    // Block "unit": the unit square. INSERT at (10, 0), x scale 2, y scale 3, rotated 90:
    // (x, y) -> R90 (2x, 3y) + (10, 0) = (10 - 3y, 2x): the square [7, 10] x [0, 2].
    const std::string blocks =
        "0\nBLOCK\n8\n0\n2\nunit\n10\n0\n20\n0\n" + square(0, 0, 1) + "0\nENDBLK\n";
    const std::string text =
        dxf("0\nINSERT\n8\n0\n2\nunit\n10\n10\n20\n0\n41\n2\n42\n3\n50\n90\n", blocks);
    const DxfDrawing d = readOk(text);
    ASSERT_EQ(d.edges.size(), 4u);
    csg::Bounds2 box;
    for (const csg::Segment2& s : d.edges) box.add(s.start()), box.add(s.finish());
    EXPECT_EQ(box.lo, csg::Vec2(7, 0));
    EXPECT_EQ(box.hi, csg::Vec2(10, 2));
    // An INSERT of a block nobody defined draws nothing, with a warning at its line.
    const DxfDrawing none = readOk(dxf("0\nINSERT\n8\n0\n2\nnope\n10\n0\n20\n0\n"));
    EXPECT_TRUE(none.edges.empty());
    ASSERT_EQ(none.warnings.size(), 1u);
    EXPECT_EQ(none.warnings[0].line, 6u);
}

TEST(DxfReader, UnsupportedEntitiesAreCountedAsOpenScadCountsThem) {
    const std::string text =
        dxf("0\nSPLINE\n8\n0\n0\nTEXT\n8\n0\n0\nSPLINE\n8\n0\n0\nPOINT\n8\nx\n");
    const DxfDrawing all = readOk(text);
    using Counts = std::vector<std::pair<std::string, uint64_t>>;
    EXPECT_EQ(all.unsupported, (Counts{{"SPLINE", 2}, {"TEXT", 1}, {"POINT", 1}}));
    DxfOptions layerX;
    layerX.layer = "x";
    EXPECT_EQ(readOk(text, layerX).unsupported, (Counts{{"POINT", 1}}));
}

TEST(DxfReader, PolylinesAndBulgesByTheMode) {
    // POLYLINE with VERTEX entities: the square [0, 10]^2, closed (flag 1).
    std::string poly = "0\nPOLYLINE\n8\n0\n66\n1\n70\n1\n";
    for (auto [x, y] : {std::pair{0, 0}, {10, 0}, {10, 10}, {0, 10}})
        poly += "0\nVERTEX\n8\n0\n10\n" + std::to_string(x) + "\n20\n" + std::to_string(y) + "\n";
    poly += "0\nSEQEND\n8\n0\n";
    DxfOptions csgray;
    csgray.only2021 = false;
    EXPECT_EQ(readOk(dxf(poly), csgray).edges.size(), 4u);
    const DxfDrawing asOpenScad = readOk(dxf(poly));
    EXPECT_TRUE(asOpenScad.edges.empty());
    using Counts = std::vector<std::pair<std::string, uint64_t>>;
    EXPECT_EQ(asOpenScad.unsupported, (Counts{{"POLYLINE", 1}, {"VERTEX", 4}, {"SEQEND", 1}}));
}

TEST(DxfReader, MalformedInputIsAnErrorWithItsLine) {
    auto error = [](const std::string& text) {
        const DxfReadResult r = readDxf(text, DxfOptions());
        EXPECT_FALSE(r.drawing);
        return std::to_string(r.line) + ": " + r.error;
    };
    EXPECT_EQ(error("0\nSECTION\n2\nENTITIES\nzero\nLINE\n"),
              "5: expected a group code (an integer), got 'zero'");
    EXPECT_EQ(error("0\nSECTION\n2\nENTITIES\n0\nLINE\n10\n1.5x\n"),
              "8: group 10 needs a finite number, got '1.5x'");
    EXPECT_EQ(error("0\nSECTION\n2\nENTITIES\n0\nLINE\n10\nnan\n"),
              "8: group 10 needs a finite number, got 'nan'");
    EXPECT_EQ(error("0\nSECTION\n2\nENTITIES\n0\nCIRCLE\n70\n1.5\n"),
              "8: group 70 needs an integer, got '1.5'");
    EXPECT_EQ(error(dxf("0\nLINE\n8\n0\n10\n1\n20\n2\n")),
              "6: LINE needs a start and an end (2 x and y coordinates, groups 10/20, 11/21); "
              "it has 1 and 1");
    EXPECT_EQ(error("0\nSECTION\n2\nENTITIES\n0\n"), "5: group code 0 has no value line");
    EXPECT_EQ(error(""), "0: the file is empty (no DXF groups)");
    EXPECT_EQ(error("AutoCAD Binary DXF\r\n\x1a"),
              "1: a binary DXF file (csgray, like OpenSCAD, reads ASCII DXF)");
    EXPECT_EQ(error(dxf("0\nCIRCLE\n8\n0\n10\n1e300\n20\n0\n40\n1\n")),
              "6: CIRCLE reaches beyond +-2^40 (after origin and scale)");
    DxfOptions few;
    few.maxEdges = 100;
    few.fragments.fn = 1000;
    EXPECT_EQ(readDxf(dxf("0\nCIRCLE\n8\n0\n10\n0\n20\n0\n40\n1\n"), few).error,
              "the drawing needs more than 100 edges (CIRCLE with 1000)");
    // CRLF line ends and blank lines after EOF are fine.
    const DxfReadResult crlf =
        readDxf("0\r\nSECTION\r\n2\r\nENTITIES\r\n" +
                    std::string("0\r\nLINE\r\n10\r\n0\r\n20\r\n0\r\n11\r\n1"
                                "\r\n21\r\n1\r\n0\r\nENDSEC\r\n0\r\nEOF\r\n\r\n"),
                DxfOptions());
    ASSERT_TRUE(crlf.drawing) << crlf.error;
    EXPECT_EQ(crlf.drawing->edges.size(), 1u);
}

// Whatever the bytes, the reader answers with a drawing or an error and its line: the Debian
// examples' DXF files with lines dropped, swapped, duplicated or replaced by junk.
TEST(DxfReader, MutatedFilesNeverCrash) {
    if (!fs::exists(kExamples))
        SKIP_OR_FAIL_IN_CI(kExamples.string() + " is not installed (openscad-data)");
    csg::testing::Rng rng(20250405);
    const char* junk[] = {"",        "x",          "-",      "1e999",  "nan",  "0",
                          "SECTION", "ENTITIES",   "BLOCKS", "INSERT", "LINE", "ARC",
                          "ELLIPSE", "LWPOLYLINE", "42",     "1e30",   "-7"};
    int errors = 0, drawings = 0;
    for (const char* name : {"example007.dxf", "example009.dxf", "example013.dxf"}) {
        std::ifstream in(kExamples / name);
        std::vector<std::string> lines;
        for (std::string l; std::getline(in, l);) lines.push_back(l);
        for (int trial = 0; trial < 150; ++trial) {
            std::vector<std::string> m = lines;
            const int edits = rng.integer(1, 8);
            for (int k = 0; k < edits; ++k) {
                const size_t i = size_t(rng.index(int(m.size())));
                switch (rng.index(4)) {
                    case 0:
                        m.erase(m.begin() + long(i));
                        break;
                    case 1:
                        std::swap(m[i], m[size_t(rng.index(int(m.size())))]);
                        break;
                    case 2:
                        m.insert(m.begin() + long(i), m[i]);
                        break;
                    default:
                        m[i] = junk[rng.index(int(std::size(junk)))];
                        break;
                }
            }
            std::string text;
            for (const std::string& l : m) text += l + "\n";
            DxfOptions options;
            options.faceted = rng.chance(0.5);
            options.only2021 = rng.chance(0.5);
            const DxfReadResult r = readDxf(text, options);
            if (r.drawing) {
                ++drawings;
                (void)r.drawing->outline();
            } else {
                ++errors;
                EXPECT_FALSE(r.error.empty());
            }
        }
    }
    EXPECT_GT(errors, 0);
    EXPECT_GT(drawings, 0);
}

// ---- the language, by hand ----

TEST(DxfLanguage, LinearExtrudeFileOfASquare) {
    csg::testing::TempDir dir("csgray_dxf_square");
    writeFile(dir.path / "sq.dxf", dxf(square(0, 0, 10)));
    const EvaluateResult r = run(dir.path, "linear_extrude(file = \"sq.dxf\", height = 5);\n");
    EXPECT_NE(firstDiagnostic(r, Severity::Warning)
                  .find("DEPRECATED: Support for reading files in "
                        "linear_extrude"),
              std::string::npos);
    const csg::Scene scene = compiled(r);
    expectSpans(spans(scene, {-5, 3, 1}, {1, 0, 0}), {{5, 15}});
    expectSpans(spans(scene, {2, 2, -1}, {0, 0, 1}), {{1, 6}});
    // The positional form: file, layer, height.
    expectSpans(spans(compiled(run(dir.path, "linear_extrude(\"sq.dxf\", \"0\", 2);\n")),
                      {2, 2, -1}, {0, 0, 1}),
                {{1, 3}});
}

TEST(DxfLanguage, CircleExactOrFaceted) {
    csg::testing::TempDir dir("csgray_dxf_circle");
    writeFile(dir.path / "c.dxf", dxf("0\nCIRCLE\n8\n0\n10\n1\n20\n2\n40\n4\n"));
    // Exact: through the centre x in [-3, 5]; at x = 3.4, y = 2 +- 3.2 (2.4^2 + 3.2^2 = 16).
    const csg::Scene exact =
        compiled(run(dir.path, "linear_extrude(height = 3) import(\"c.dxf\");\n"));
    expectSpans(spans(exact, {-10, 2, 1}, {1, 0, 0}), {{7, 15}});
    expectSpans(spans(exact, {3.4, -10, 1}, {0, 1, 0}), {{8.8, 15.2}}, 1e-9);
    // $fn = 4: the diamond |x - 1| + |y - 2| <= 4; at y = 4, x in [-1, 3].
    const csg::Scene diamond =
        compiled(run(dir.path, "linear_extrude(height = 3) import(\"c.dxf\", $fn = 4);\n"));
    expectSpans(spans(diamond, {-10, 4, 1}, {1, 0, 0}), {{9, 13}});
}

TEST(DxfLanguage, BulgeIsAnArcExceptAsOpenScad) {
    csg::testing::TempDir dir("csgray_dxf_bulge");
    // The square [0, 10]^2, its top edge (10, 10) -> (0, 10) with bulge b: 4 atan(1) = 180
    // degrees, so a half circle of radius 5 about (5, 10), above the edge for b = 1 (counter-
    // clockwise from (10, 10)), below it for b = -1.
    auto lwpolyline = [](double b) {
        return dxf(
            "0\nLWPOLYLINE\n8\n0\n90\n4\n70\n1\n10\n0\n20\n0\n10\n10\n20\n0\n10\n10\n20\n10"
            "\n42\n" +
            std::to_string(b) + "\n10\n0\n20\n10\n");
    };
    writeFile(dir.path / "up.dxf", lwpolyline(1));
    writeFile(dir.path / "down.dxf", lwpolyline(-1));
    auto scene = [&](const char* file, const char* extra, CurveMode mode) {
        return compiled(
            run(dir.path,
                std::string("linear_extrude(height = 1) import(\"") + file + "\"" + extra + ");\n",
                mode));
    };
    // At x = 8: 10 + 4 above (3^2 + 4^2 = 25), 10 - 4 below.
    expectSpans(spans(scene("up.dxf", "", CurveMode::Auto), {8, -1, 0.5}, {0, 1, 0}), {{1, 15}},
                1e-9);
    expectSpans(spans(scene("up.dxf", "", CurveMode::Auto), {5, -1, 0.5}, {0, 1, 0}), {{1, 16}},
                1e-9);
    expectSpans(spans(scene("down.dxf", "", CurveMode::Exact), {8, -1, 0.5}, {0, 1, 0}), {{1, 7}},
                1e-9);
    // $fn = 8: OpenSCAD's chords of that arc, 4 of 45 degrees, their ends on its 1/1024 grid:
    // at x = 8, the chord from q = snap(5 + 5 cos 45, 10 + 5 sin 45) to (5, 15).
    const auto snap = [](double x) { return std::round(x * 1024) / 1024; };
    const csg::Vec2 q(snap(5 + 2.5 * std::sqrt(2.0)), snap(10 + 2.5 * std::sqrt(2.0)));
    const double y = 15 - (15 - q.y) * (8 - 5) / (q.x - 5);
    expectSpans(spans(scene("up.dxf", ", $fn = 8", CurveMode::Auto), {8, -1, 0.5}, {0, 1, 0}),
                {{1, y + 1}}, 1e-9);
    // --curves openscad: OpenSCAD 2021 reads no bulges, the edge stays straight (and says so).
    const EvaluateResult asOpenScad =
        run(dir.path, "linear_extrude(height = 1) import(\"up.dxf\");\n", CurveMode::OpenScad);
    EXPECT_NE(
        firstDiagnostic(asOpenScad, Severity::Warning).find("bulges (arcs) are read as straight"),
        std::string::npos);
    expectSpans(spans(compiled(asOpenScad), {8, -1, 0.5}, {0, 1, 0}), {{1, 11}});
}

TEST(DxfLanguage, OpenChainsCloseAndNestedLoopsAlternate) {
    csg::testing::TempDir dir("csgray_dxf_evenodd");
    // Two lines (0,0)-(10,0)-(10,10): closed by (10,10)-(0,0), a triangle: at y = 5, x in [5, 10].
    writeFile(dir.path / "l.dxf", dxf(line(0, 0, 10, 0) + line(10, 0, 10, 10)));
    expectSpans(spans(compiled(run(dir.path, "linear_extrude(1) import(\"l.dxf\");\n")),
                      {0, 5, 0.5}, {1, 0, 0}),
                {{5, 10}});
    // Squares of 10 and 4 nested, and one of 2 in the hole: even-odd.
    writeFile(dir.path / "n.dxf", dxf(square(0, 0, 10) + square(3, 3, 4) + square(4, 4, 2)));
    expectSpans(spans(compiled(run(dir.path, "linear_extrude(1) import(\"n.dxf\");\n")),
                      {-1, 5, 0.5}, {1, 0, 0}),
                {{1, 4}, {5, 7}, {8, 11}});
}

TEST(DxfLanguage, ImportLayerOriginScaleAndInsert) {
    csg::testing::TempDir dir("csgray_dxf_import");
    const std::string blocks = "0\nBLOCK\n8\n0\n2\nunit\n" + square(0, 0, 1) + "0\nENDBLK\n";
    writeFile(dir.path / "d.dxf",
              dxf(square(0, 0, 1, "a") +
                      "0\nINSERT\n8\nb\n2\nunit\n10\n10\n20\n0\n41\n2\n42\n3\n50\n90\n",
                  blocks));
    // Layer b: the inserted square [7, 10] x [0, 2]; moved by -[1, 0] and scaled by 2:
    // [12, 18] x [0, 4].
    const csg::Scene b = compiled(
        run(dir.path, "linear_extrude(1) import(\"d.dxf\", \"b\", origin = [1, 0], scale = 2);\n"));
    expectSpans(spans(b, {0, 1, 0.5}, {1, 0, 0}), {{12, 18}});
    // Layer given as the number 0 is layer "0", which has nothing here; no layer: both.
    const EvaluateResult zero = run(dir.path, "linear_extrude(1) import(\"d.dxf\", layer = 0);\n");
    EXPECT_TRUE(zero.ok()) << diagnosticsOf(zero);
    expectSpans(spans(compiled(run(dir.path, "linear_extrude(1) import(\"d.dxf\");\n")),
                      {-1, 0.5, 0.5}, {1, 0, 0}),
                {{1, 2}, {8, 11}});
}

TEST(DxfLanguage, RotateExtrudeFileIsARing) {
    csg::testing::TempDir dir("csgray_dxf_ring");
    writeFile(dir.path / "r.dxf", dxf(square(2, 0, 1)));
    // The square [2, 3] x [0, 1] about z: along x at z = 0.5, |x| in [2, 3].
    expectSpans(spans(compiled(run(dir.path, "rotate_extrude(file = \"r.dxf\");\n")), {-10, 0, 0.5},
                      {1, 0, 0}),
                {{7, 8}, {12, 13}});
    // origin [1, 0]: [1, 2]; scale 2: [4, 6] x [0, 2]; positional file, layer, origin, scale.
    expectSpans(spans(compiled(run(dir.path, "rotate_extrude(\"r.dxf\", origin = [1, 0]);\n")),
                      {-10, 0, 0.5}, {1, 0, 0}),
                {{8, 9}, {11, 12}});
    expectSpans(spans(compiled(run(dir.path, "rotate_extrude(\"r.dxf\", \"\", [0, 0], 2);\n")),
                      {-10, 0, 0.5}, {1, 0, 0}),
                {{4, 6}, {14, 16}});
    // A number first is OpenSCAD 2021's file, not an angle: an error that says so.
    EXPECT_NE(firstDiagnostic(run(dir.path, "rotate_extrude(90) square(1);\n"), Severity::Error)
                  .find("main.scad:1:16: error: rotate_extrude(): 'file' must be a DXF file name"),
              std::string::npos);
}

TEST(DxfLanguage, ErrorsAndWarningsNameTheDxfLine) {
    csg::testing::TempDir dir("csgray_dxf_errors");
    const std::string main = (dir.path / "main.scad").string();
    writeFile(dir.path / "bad.dxf", "0\nSECTION\n2\nENTITIES\n0\nLINE\n10\nwide\n");
    EXPECT_EQ(firstDiagnostic(run(dir.path, "\n  import(\"bad.dxf\");\n"), Severity::Error),
              main + ":2:10: error: import(): " + (dir.path / "bad.dxf").string() +
                  ":8: group 10 needs a finite number, got 'wide'");
    EXPECT_EQ(
        firstDiagnostic(run(dir.path, "linear_extrude(file = \"none.dxf\");\n"), Severity::Error),
        main + ":1:16: error: linear_extrude(): " + (dir.path / "none.dxf").string() +
            ": cannot open the DXF file");
    writeFile(dir.path / "s.dxf", dxf(square(0, 0, 1) + "0\nSPLINE\n8\n0\n0\nSPLINE\n8\n0\n"));
    EXPECT_EQ(firstDiagnostic(run(dir.path, "import(\"s.dxf\");\n"), Severity::Warning),
              main + ":1:1: warning: Unsupported DXF Entity 'SPLINE' (2) in \"s.dxf\".");
    EXPECT_NE(firstDiagnostic(run(dir.path, "import(\"s.dxf\", origin = 5);\n"), Severity::Warning)
                  .find("import(..., origin=5) could not be converted"),
              std::string::npos);
    EXPECT_NE(firstDiagnostic(run(dir.path, "import(\"s.dxf\", scale = \"x\");\n"), Severity::Error)
                  .find("import(): 'scale' must be a finite number"),
              std::string::npos);
    // dxf_dim: OpenSCAD's warnings and undef for a missing file or dimension.
    const EvaluateResult missing =
        run(dir.path, "x = dxf_dim(file = \"none.dxf\", name = \"w\");\necho(x);\n");
    EXPECT_TRUE(missing.ok()) << diagnosticsOf(missing);
    EXPECT_NE(diagnosticsOf(missing).find("Can't open DXF file 'none.dxf'!"), std::string::npos);
    const EvaluateResult noDim =
        run(dir.path, "x = dxf_dim(file = \"s.dxf\", name = \"w\");\necho(x);\n");
    EXPECT_NE(diagnosticsOf(noDim).find("Can't find dimension 'w' in 's.dxf', layer ''!"),
              std::string::npos);
    EXPECT_NE(firstDiagnostic(run(dir.path, "x = dxf_dim(file = \"bad.dxf\");\n"), Severity::Error)
                  .find("dxf_dim(): " + (dir.path / "bad.dxf").string() + ":8: group 10"),
              std::string::npos);
}

TEST(DxfLanguage, DimensionTypesAndCross) {
    csg::testing::TempDir dir("csgray_dxf_dims");
    // DIMENSION groups: 70 type, 1 name, 10-16 / 20-26 points, 50 angle.
    auto dim = [](int type, const char* name, const std::string& points, double angle = 0) {
        return "0\nDIMENSION\n8\nd\n70\n" + std::to_string(type) + "\n1\n" + name + "\n" + points +
               "50\n" + std::to_string(angle) + "\n";
    };
    writeFile(dir.path / "d.dxf",
              dxf(dim(0, "rot", "13\n0\n23\n0\n14\n3\n24\n4\n", 0) +     // |3 cos 0 + 4 sin 0| = 3
                  dim(0, "rot90", "13\n0\n23\n0\n14\n3\n24\n4\n", 90) +  // 4
                  dim(1, "aligned", "13\n1\n23\n1\n14\n4\n24\n5\n") +    // 5
                  dim(3, "dia", "10\n1\n20\n1\n15\n7\n25\n9\n") +        // 10
                  dim(6 | 64, "ordx", "13\n2.5\n23\n7\n") +              // x: 2.5
                  dim(6, "ordy", "13\n2.5\n23\n7\n") +                   // y: 7
                  dim(2, "angle", "10\n5\n20\n5\n15\n0\n25\n0\n13\n0\n23\n0\n14\n0\n24\n1\n") +
                  line(0, 0, 4, 4) + line(0, 4, 4, 0)));
    // angle: atan2 of (dx, dy) as OpenSCAD writes it: 45 for (5, 5), 0 for (0, 1): 45.
    std::vector<std::string> echoes;
    const EvaluateResult r =
        run(dir.path,
            "echo([for (n = [\"rot\", \"rot90\", \"aligned\", \"dia\", \"ordx\", \"ordy\", "
            "\"angle\"]) dxf_dim(file = \"d.dxf\", name = n)]);\n"
            "echo(dxf_dim(file = \"d.dxf\", name = \"aligned\", scale = 2));\n"
            "echo(dxf_cross(file = \"d.dxf\"), dxf_cross(file = \"d.dxf\", origin = [1, 0], "
            "scale = 2));\n",
            CurveMode::Auto, &echoes);
    EXPECT_TRUE(r.diagnostics.empty()) << diagnosticsOf(r);
    EXPECT_EQ(echoes, (std::vector<std::string>{"ECHO: [3, 4, 5, 10, 2.5, 7, 45]", "ECHO: 10",
                                                "ECHO: [2, 2], [2, 4]"}));
    // Unnamed arguments, which OpenSCAD 2021 ignores: csgray takes them in order, and says so.
    echoes.clear();
    const EvaluateResult positional =
        run(dir.path, "echo(dxf_dim(\"d.dxf\", \"aligned\"));\n", CurveMode::Auto, &echoes);
    EXPECT_EQ(echoes, (std::vector<std::string>{"ECHO: 5"}));
    EXPECT_NE(firstDiagnostic(positional, Severity::Warning).find("OpenSCAD 2021 ignores unnamed"),
              std::string::npos);
}

// ---- against OpenSCAD 2021 ----

using csg::testing::haveOpenScad;

// OpenSCAD's binary STL, read here: the volume by the divergence theorem, the bounds and, per
// axis, a vertex at each end of them.
struct Stl {
    double volume = 0;
    csg::Bounds3 box;
    std::array<csg::Vec3, 3> lowest, highest;
    size_t triangles = 0;
};

Stl readBinaryStl(const fs::path& file) {
    std::ifstream in(file, std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    Stl stl;
    if (bytes.size() < 84) return stl;
    uint32_t count = 0;
    std::memcpy(&count, bytes.data() + 80, 4);
    if (bytes.size() != 84 + size_t(count) * 50) return stl;
    stl.triangles = count;
    for (uint32_t i = 0; i < count; ++i) {
        float f[9];
        std::memcpy(f, bytes.data() + 84 + size_t(i) * 50 + 12, sizeof f);
        const csg::Vec3 a(f[0], f[1], f[2]), b(f[3], f[4], f[5]), c(f[6], f[7], f[8]);
        stl.volume += glm::dot(a, glm::cross(b, c)) / 6.0;
        for (const csg::Vec3& p : {a, b, c})
            for (int k = 0; k < 3; ++k) {
                if (p[k] < stl.box.lo[k]) stl.box.lo[k] = p[k], stl.lowest[size_t(k)] = p;
                if (p[k] > stl.box.hi[k]) stl.box.hi[k] = p[k], stl.highest[size_t(k)] = p;
            }
    }
    return stl;
}

// OpenSCAD's mesh of a part: run in the part's directory.
Stl openscadStl(const fs::path& part, const fs::path& out) {
    const std::string command = "cd '" + part.parent_path().string() +
                                "' && openscad --export-format binstl -o '" + out.string() + "' '" +
                                part.string() + "' >'" + out.string() + ".log' 2>&1";
    EXPECT_EQ(std::system(command.c_str()), 0) << command;
    return readBinaryStl(out);
}

// The part's bounding box is OpenSCAD's, to tol: no ray of a 101 x 101 grid along each axis
// finds the part outside OpenSCAD's box, and rays along each axis next to OpenSCAD's extreme
// vertices (offset by eps across the axis, in 8 directions: at the vertex itself a line
// grazes) reach its faces.
void expectSameBounds(const csg::Scene& scene, const Stl& theirs, double tol) {
    const csg::Bounds3 loose = scene.bounds();
    const double eps = 1e-3 * tol;
    for (int axis = 0; axis < 3; ++axis) {
        const int u = (axis + 1) % 3, v = (axis + 2) % 3;
        csg::Vec3 d(0.0);
        d[axis] = 1;
        auto along = [&](csg::Vec3 o) {
            o[axis] = loose.lo[axis] - 1;
            return std::pair{o, spans(scene, o, d)};
        };
        constexpr int kRays = 101;
        for (int i = 0; i < kRays; ++i)
            for (int j = 0; j < kRays; ++j) {
                csg::Vec3 p(0.0);
                p[u] = loose.lo[u] + (loose.hi[u] - loose.lo[u]) * (i + 0.5) / kRays;
                p[v] = loose.lo[v] + (loose.hi[v] - loose.lo[v]) * (j + 0.5) / kRays;
                const auto [o, s] = along(p);
                if (s.empty()) continue;
                EXPECT_GE(o[axis] + s.front().first, theirs.box.lo[axis] - tol) << "axis " << axis;
                EXPECT_LE(o[axis] + s.back().second, theirs.box.hi[axis] + tol) << "axis " << axis;
            }
        double lo = csg::kInfinity, hi = -csg::kInfinity;
        for (int du = -1; du <= 1; ++du)
            for (int dv = -1; dv <= 1; ++dv) {
                csg::Vec3 shift(0.0);
                shift[u] = du * eps;
                shift[v] = dv * eps;
                if (const auto [o, s] = along(theirs.lowest[size_t(axis)] + shift); !s.empty())
                    lo = std::min(lo, o[axis] + s.front().first);
                if (const auto [o, s] = along(theirs.highest[size_t(axis)] + shift); !s.empty())
                    hi = std::max(hi, o[axis] + s.back().second);
            }
        EXPECT_NEAR(lo, theirs.box.lo[axis], tol) << "axis " << axis;
        EXPECT_NEAR(hi, theirs.box.hi[axis], tol) << "axis " << axis;
    }
}

// The part, evaluated with --curves openscad, against OpenSCAD's STL of the same file: the
// volume (rays along z through the part turned by a generic rotation, so that no face is
// parallel to them and each ray's span length varies continuously) within 1e-5 relative, the
// bounding box within 1e-6 of its size.
void expectAgreesWithOpenScad(const fs::path& part, const fs::path& dir) {
    SCOPED_TRACE(part.string());
    const Stl theirs = openscadStl(part, dir / (part.stem().string() + ".stl"));
    ASSERT_GT(theirs.triangles, 0u);
    EvaluateOptions options;
    options.curves = CurveMode::OpenScad;
    const EvaluateResult r = evaluateFile(part, options);
    ASSERT_TRUE(r.ok()) << diagnosticsOf(r);
    const csg::Mat4 turn = glm::rotate(glm::rotate(csg::Mat4(1.0), 0.61, csg::Vec3(1, 0, 0)), 0.37,
                                       csg::Vec3(0.2, 1, 0.3));
    const double volume =
        csg::volume(csg::Scene::compile(csg::transformed(turn, r.model->root)), 1024);
    EXPECT_NEAR(volume / std::abs(theirs.volume), 1.0, 1e-5)
        << "csgray " << volume << ", OpenSCAD " << theirs.volume;
    expectSameBounds(csg::Scene::compile(r.model->root), theirs,
                     1e-6 * glm::length(theirs.box.hi - theirs.box.lo));
    std::printf("%s: volume csgray %.9g, OpenSCAD %.9g (%+.2e)\n", part.filename().c_str(), volume,
                std::abs(theirs.volume), volume / std::abs(theirs.volume) - 1);
}

TEST(DxfOpenScad, DebianExamplesThatUseDxf) {
    if (!haveOpenScad()) SKIP_OR_FAIL_IN_CI("openscad (2021.01, Debian's) is not installed");
    if (!fs::exists(kExamples)) SKIP_OR_FAIL_IN_CI(kExamples.string() + " is not installed");
    csg::testing::TempDir dir("csgray_dxf_examples");
    // 008 and 013 are intersections and differences of extruded layers (013 through INSERTs).
    for (const char* name : {"example008.scad", "example013.scad"})
        expectAgreesWithOpenScad(kExamples / name, dir.path);
    // 015 is 2-D (its module shape() imports example009.dxf scaled by 2): extruded by both.
    writeFile(dir.path / "example015_extruded.scad",
              "use <" + (kExamples / "example015.scad").string() +
                  ">\nlinear_extrude(height = 10) shape();\n");
    expectAgreesWithOpenScad(dir.path / "example015_extruded.scad", dir.path);
    // 007 revolves its layer "dorn", which csgray revolves exactly (not in OpenSCAD's 30
    // sections), and 009 twists: their DXF layers, each extruded, are compared instead.
    const std::pair<const char*, const char*> layers[] = {
        {"example007.dxf", "layer = \"dorn\""},
        {"example007.dxf", "layer = \"cutout1\""},
        {"example007.dxf", "layer = \"cutout2\""},
        {"example009.dxf", "layer = \"body\""},
        {"example009.dxf", "layer = \"plate\""},
        {"example009.dxf", "layer = \"fan_top\""},
        {"example009.dxf", "layer = \"fan_side\", origin = [0, -40]"},
        {"example009.dxf", ""},
    };
    int k = 0;
    for (const auto& [file, args] : layers) {
        const fs::path part = dir.path / ("layer" + std::to_string(k++) + ".scad");
        writeFile(part, "linear_extrude(height = 10) import(\"" + (kExamples / file).string() +
                            "\"" + (*args ? std::string(", ") + args : "") + ");\n");
        expectAgreesWithOpenScad(part, dir.path);
    }
}

// Whether a triangle soup is closed: every edge (by exact coordinates) used once in each
// direction. OpenSCAD 2021 writes open or self-overlapping meshes for some degenerate drawings
// (coincident edges, slivers); their divergence volume means nothing.
bool closedMesh(const fs::path& file) {
    std::ifstream in(file, std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (bytes.size() < 84) return false;
    uint32_t count = 0;
    std::memcpy(&count, bytes.data() + 80, 4);
    if (bytes.size() != 84 + size_t(count) * 50) return false;
    using Corner = std::array<float, 3>;
    std::map<std::pair<Corner, Corner>, int> edges;
    for (uint32_t i = 0; i < count; ++i) {
        Corner c[3];
        std::memcpy(c, bytes.data() + 84 + size_t(i) * 50 + 12, sizeof c);
        for (int k = 0; k < 3; ++k) {
            ++edges[{c[k], c[(k + 1) % 3]}];
            --edges[{c[(k + 1) % 3], c[k]}];
        }
    }
    return std::all_of(edges.begin(), edges.end(), [](const auto& e) { return e.second == 0; });
}

// Seeded soups of lines (and a few arcs) between points of a small lattice, so that ends meet
// three and four at a time, chains branch and repeat, and open chains are closed: where the
// closing lines go depends on OpenSCAD's order of chaining, which csgray must follow for the
// region to be the same. Each drawing, extruded, against OpenSCAD's mesh of it (when that mesh
// is closed): the same volume, or both empty.
TEST(DxfOpenScad, LineSoupsChainAsOpenScadChainsThem) {
    if (!haveOpenScad()) SKIP_OR_FAIL_IN_CI("openscad (2021.01, Debian's) is not installed");
    csg::testing::TempDir dir("csgray_dxf_soups");
    csg::testing::Rng rng(7041);
    int compared = 0, empty = 0;
    for (int trial = 0; trial < 24; ++trial) {
        std::vector<std::pair<int, int>> points(size_t(rng.integer(4, 9)));
        for (auto& p : points) p = {rng.integer(0, 6), rng.integer(0, 6)};
        std::ostringstream entities;
        const int lines = rng.integer(3, 14);
        for (int i = 0; i < lines; ++i) {
            const auto a = points[size_t(rng.index(int(points.size())))];
            const auto b = points[size_t(rng.index(int(points.size())))];
            entities << line(a.first, a.second, b.first, b.second);
            if (rng.chance(0.15)) {
                const auto c = points[size_t(rng.index(int(points.size())))];
                const int angles[] = {0, 30, 45, 90, 180, 270, 360};
                entities << "0\nARC\n8\n0\n10\n"
                         << c.first << "\n20\n"
                         << c.second << "\n40\n"
                         << rng.integer(1, 3) << "\n50\n"
                         << angles[rng.index(7)] << "\n51\n"
                         << angles[rng.index(7)] << "\n";
            }
        }
        const std::string name = "soup" + std::to_string(trial);
        writeFile(dir.path / (name + ".dxf"), dxf(entities.str()));
        const fs::path part = dir.path / (name + ".scad");
        writeFile(part, "linear_extrude(height = 10) import(\"" + name + ".dxf\");\n");
        const fs::path stl = dir.path / (name + ".stl");
        const std::string command = "cd '" + dir.path.string() +
                                    "' && openscad --export-format binstl -o '" + stl.string() +
                                    "' '" + part.string() + "' >/dev/null 2>&1";
        const bool made = std::system(command.c_str()) == 0 && fs::exists(stl);
        if (made && !closedMesh(stl)) continue;
        EvaluateOptions options;
        options.curves = CurveMode::OpenScad;
        const EvaluateResult r = evaluateFile(part, options);
        ASSERT_TRUE(r.ok()) << name << ": " << diagnosticsOf(r);
        const csg::Mat4 turn = glm::rotate(glm::rotate(csg::Mat4(1.0), 0.61, csg::Vec3(1, 0, 0)),
                                           0.37, csg::Vec3(0.2, 1, 0.3));
        const double volume =
            csg::volume(csg::Scene::compile(csg::transformed(turn, r.model->root)), 512);
        if (!made) {  // OpenSCAD: "Current top level object is empty."
            EXPECT_EQ(volume, 0.0) << name;
            ++empty;
            continue;
        }
        const double theirs = std::abs(readBinaryStl(stl).volume);
        EXPECT_NEAR(volume / theirs, 1.0, 1e-4)
            << name << ": csgray " << volume << ", OpenSCAD " << theirs;
        ++compared;
    }
    std::printf("line soups: %d compared, %d empty in both, %d skipped (OpenSCAD's mesh open)\n",
                compared, empty, 24 - compared - empty);
    EXPECT_GE(compared, 12);
}

// The dimensions of example009.dxf: worked out here from the file's numbers as OpenSCAD's
// dxf_dim() does, and as OpenSCAD 2021 itself echoes them. echo() shows 6 digits, so each value
// is echoed with what is left of it after its first 4 decimals, times 1e10: 12 digits in all.
std::vector<double> echoedValues(const std::vector<std::string>& lines) {
    std::vector<double> out;
    for (const std::string& l : lines) {
        double shown = 0, rest = 0;
        if (std::sscanf(l.c_str(), "ECHO: %lf, %lf", &shown, &rest) == 2)
            out.push_back(std::round(shown * 1e4) / 1e4 + rest * 1e-10);
    }
    return out;
}

TEST(DxfOpenScad, Example009Dimensions) {
    if (!fs::exists(kExamples)) SKIP_OR_FAIL_IN_CI(kExamples.string() + " is not installed");
    csg::testing::TempDir dir("csgray_dxf_example009");
    const std::string file = (kExamples / "example009.dxf").string();
    std::string scad;
    for (const char* n : {"bodywidth", "fanwidth", "platewidth", "fanrot"})
        scad += "v = dxf_dim(file = \"" + file + "\", name = \"" + n +
                "\"); echo(v, (v - round(v * 1e4) / 1e4) * 1e10);\n";
    scad += "echo(dxf_cross(file = \"" + file + "\", layer = \"fan_side_center\"));\n";
    // The same file in each; `v` is assigned in the file's one scope, so each line is a
    // file of its own.
    std::vector<std::string> ours;
    std::istringstream lines(scad);
    for (std::string l; std::getline(lines, l);) {
        const EvaluateResult r = run(dir.path, l + "\n", CurveMode::Auto, &ours);
        ASSERT_TRUE(r.diagnostics.empty()) << diagnosticsOf(r);
    }
    ASSERT_EQ(ours.size(), 5u);
    const std::vector<double> values = echoedValues(ours);
    ASSERT_EQ(values.size(), 4u);
    // By hand: bodywidth's points 13/23 = (0, -29) and 14/24 = (0, -51) at 90 degrees: 22;
    // fanwidth (0, -30), (0, -50): 20; platewidth (0, -29), (0, -27): 2; fanrot is angular:
    // |atan2(18 - 5, 0 - 0) - atan2(9.66375... - 2.68437..., 15.18590... - 4.21830...)| in
    // degrees, atan2 taking (dx, dy) as OpenSCAD writes it.
    const double fanrot = 90.0 - std::atan2(9.6637588594768662 - 2.6843774609657962,
                                            15.1859067791779339 - 4.2183074386605375) *
                                     180.0 / csg::kPi;
    EXPECT_EQ(values[0], 22);
    EXPECT_EQ(values[1], 20);
    EXPECT_EQ(values[2], 2);
    EXPECT_NEAR(values[3], fanrot, 1e-10);
    EXPECT_EQ(ours[4], "ECHO: [0, -40]");
    if (!haveOpenScad()) SKIP_OR_FAIL_IN_CI("openscad (2021.01, Debian's) is not installed");
    std::istringstream again(scad);
    std::vector<std::string> theirs;
    int k = 0;
    for (std::string l; std::getline(again, l); ++k) {
        const fs::path part = dir.path / ("theirs" + std::to_string(k) + ".scad");
        writeFile(part, l + "\n");
        const std::string command = "cd '" + dir.path.string() + "' && openscad -o '" +
                                    part.string() + ".echo' '" + part.string() +
                                    "' >/dev/null 2>&1";
        ASSERT_EQ(std::system(command.c_str()), 0) << command;
        std::ifstream in(part.string() + ".echo");
        for (std::string e; std::getline(in, e);) theirs.push_back(e);
    }
    ASSERT_EQ(theirs.size(), 5u);
    const std::vector<double> openscad = echoedValues(theirs);
    ASSERT_EQ(openscad.size(), 4u);
    for (int i = 0; i < 4; ++i) EXPECT_NEAR(values[size_t(i)], openscad[size_t(i)], 1e-10) << i;
    EXPECT_EQ(theirs[4], "ECHO: [0, -40]");
}

}  // namespace
