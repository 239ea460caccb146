// 2-D parts drawn to SVG and DXF (io/DrawingFile.h, csg::contoursOf, `csgray export`). The
// oracles are independent of the code under test:
//   - contours and areas of shapes derived by hand (two squares sharing an edge are one
//     rectangle; a square with a circle on its side has area 100 + 12.5 pi);
//   - the areas read back from the files by this test's own readers (the shoelace formula,
//     and Green's theorem on a DXF ARC's centre, radius and angles);
//   - Debian's OpenSCAD 2021: its SVG of the same part under --curves openscad, and its STL of
//     our SVG and DXF imported and extruded, whose volume is the area less the chords'
//     segments by OpenSCAD's documented arc rules (../shared/OPENSCAD.md section 2).
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <map>
#include <numbers>
#include <sstream>

#include "BinaryStl.h"
#include "CliRunner.h"
#include "MissingTool.h"
#include "csg/Volume.h"
#include "csg/derived/Boundary2D.h"
#include "io/Evaluate.h"
#include "tests/PartHelpers.h"

namespace {

namespace fs = std::filesystem;
using cli::runCsgray;
using cli::ScratchDir;
using csg::BoundaryPiece;
using csg::Contour2D;
using csg::Vec2;
using csg::testing::diagnosticsOf;
using csg::testing::evaluate;
using csg::testing::readFile;
using csg::testing::writeFile;

constexpr double kPi = std::numbers::pi;

std::vector<Contour2D> contoursOfPart(const std::string& text) {
    const io::EvaluateResult r = evaluate(text);
    EXPECT_TRUE(r.ok()) << diagnosticsOf(r);
    if (!r.ok() || !r.model->shape2D) return {};
    const auto contours = csg::contoursOf(csg::boundaryOf(csg::Region2D(*r.model->shape2D)));
    EXPECT_TRUE(contours.has_value());
    return contours.value_or(std::vector<Contour2D>{});
}

// The signed area a contour encloses (Green's theorem; an arc adds its chord's triangle part
// and its circular segment).
double signedArea(const Contour2D& contour) {
    double area = 0.0;
    for (const BoundaryPiece& p : contour) {
        area += 0.5 * (p.a.x * p.b.y - p.b.x * p.a.y);
        if (p.kind == BoundaryPiece::Kind::Arc)
            area += 0.5 * p.radius * p.radius * (p.sweep - std::sin(p.sweep));
    }
    return area;
}

TEST(Contours, SquaresSharingAnEdgeAreOneRectangle) {
    const auto contours = contoursOfPart("square(10); translate([10, 0]) square(10);");
    ASSERT_EQ(contours.size(), 1u);
    ASSERT_EQ(contours[0].size(), 4u);  // the cut at x = 10 merged away
    for (const BoundaryPiece& p : contours[0]) EXPECT_EQ(p.kind, BoundaryPiece::Kind::Line);
    EXPECT_DOUBLE_EQ(signedArea(contours[0]), 200.0);
}

TEST(Contours, SquaresTouchingAtACornerStayTwoContours) {
    const auto contours = contoursOfPart("square(10); translate([10, 10]) square(10);");
    ASSERT_EQ(contours.size(), 2u);
    for (const Contour2D& c : contours) {
        EXPECT_EQ(c.size(), 4u);
        EXPECT_DOUBLE_EQ(signedArea(c), 100.0);  // each counter-clockwise, shape on the left
    }
}

TEST(Contours, AHoleTurnsClockwiseAndAWholeCircleIsOnePiece) {
    const auto contours =
        contoursOfPart("difference() { square(10); translate([5, 5]) circle(2); }");
    ASSERT_EQ(contours.size(), 2u);
    const Contour2D& outer = contours[0].size() == 4 ? contours[0] : contours[1];
    const Contour2D& hole = contours[0].size() == 4 ? contours[1] : contours[0];
    EXPECT_DOUBLE_EQ(signedArea(outer), 100.0);
    ASSERT_EQ(hole.size(), 1u);
    EXPECT_EQ(hole[0].kind, BoundaryPiece::Kind::Arc);
    EXPECT_EQ(hole[0].a, hole[0].b);
    EXPECT_DOUBLE_EQ(hole[0].radius, 2.0);
    EXPECT_NEAR(signedArea(hole), -4.0 * kPi, 1e-12);
}

// ---- the files ----

// The numbers of an SVG path's data, by command: "M x,y L x,y A rx,ry rot large,sweep x,y z".
struct SvgCommand {
    char op;
    std::vector<double> args;
};

std::vector<SvgCommand> svgPath(const std::string& svg) {
    const size_t begin = svg.find(" d=\"");
    EXPECT_NE(begin, std::string::npos) << svg;
    const size_t end = svg.find('"', begin + 4);
    std::string d = svg.substr(begin + 4, end - begin - 4);
    for (char& c : d)
        if (c == ',' || c == '\n') c = ' ';
    std::istringstream in(d);
    std::vector<SvgCommand> out;
    std::string token;
    while (in >> token) {
        if (std::isalpha(static_cast<unsigned char>(token[0])))
            out.push_back({token[0], {}});
        else
            out.back().args.push_back(std::stod(token));
    }
    return out;
}

// The area of an SVG path of lines only (the shoelace formula; y negated back).
double svgPolygonArea(const std::vector<SvgCommand>& path) {
    double area = 0.0;
    Vec2 first{0.0}, last{0.0};
    for (const SvgCommand& c : path) {
        if (c.op == 'z') {
            area += 0.5 * (last.x * first.y - first.x * last.y);
            continue;
        }
        EXPECT_TRUE(c.op == 'M' || c.op == 'L') << c.op;
        const Vec2 p(c.args.at(0), -c.args.at(1));
        if (c.op == 'M')
            first = p;
        else
            area += 0.5 * (last.x * p.y - p.x * last.y);
        last = p;
    }
    return area;
}

// The entities of a DXF file: type and its group values by code.
struct DxfEntity {
    std::string type;
    std::map<int, double> values;
};

std::vector<DxfEntity> dxfEntities(const std::string& text) {
    std::istringstream in(text);
    std::string code, value;
    std::vector<DxfEntity> out;
    bool entities = false;
    while (std::getline(in, code) && std::getline(in, value)) {
        const int c = std::stoi(code);
        if (c == 2 && value == "ENTITIES") entities = true;
        if (c == 0 && value == "ENDSEC") entities = false;
        if (!entities) continue;
        if (c == 0)
            out.push_back({value, {}});
        else if (c != 8 && !out.empty())
            out.back().values[c] = std::stod(value);
    }
    return out;
}

const char* const kSquareAndHalfDisc = "union() { square(10); translate([10, 5]) circle(5); }\n";
const double kSquareAndHalfDiscArea = 100.0 + 12.5 * kPi;

// `csgray export` of dir/p.scad to dir/file (and any further options).
cli::RunResult exportPart(const ScratchDir& dir, const std::string& file,
                          const std::vector<std::string>& options = {}) {
    std::vector<std::string> args = {"export", (dir / "p.scad").string(), "-o",
                                     (dir / file).string()};
    args.insert(args.end(), options.begin(), options.end());
    return runCsgray(args, dir.path());
}

TEST(DrawingExport, DxfHoldsExactLinesAndArcs) {
    ScratchDir dir;
    writeFile(dir / "p.scad", kSquareAndHalfDisc);
    const auto r = exportPart(dir, "p.dxf");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.err.find("1 contour: 3 lines and 1 circular arc"), std::string::npos) << r.err;
    const auto entities = dxfEntities(readFile(dir / "p.dxf"));
    ASSERT_EQ(entities.size(), 4u);
    double area = 0.0;
    int arcs = 0;
    for (const DxfEntity& e : entities) {
        if (e.type == "LINE") {
            area += 0.5 * (e.values.at(10) * e.values.at(21) - e.values.at(11) * e.values.at(20));
            continue;
        }
        ASSERT_EQ(e.type, "ARC");
        ++arcs;
        EXPECT_EQ(e.values.at(10), 10.0);
        EXPECT_EQ(e.values.at(20), 5.0);
        EXPECT_EQ(e.values.at(40), 5.0);
        EXPECT_NEAR(e.values.at(50), 270.0, 1e-12);  // counter-clockwise from the bottom...
        EXPECT_NEAR(e.values.at(51), 90.0, 1e-12);   // ... round the right to the top
        // Green's theorem along the arc, counter-clockwise from t0 to t1: the sector and the
        // centre's part.
        const double cx = e.values.at(10), cy = e.values.at(20), rr = e.values.at(40);
        const double t0 = e.values.at(50) * kPi / 180.0,
                     t1 = (e.values.at(51) + 360.0) * kPi / 180.0;
        area += 0.5 * (rr * rr * (t1 - t0) + cx * rr * (std::sin(t1) - std::sin(t0)) -
                       cy * rr * (std::cos(t1) - std::cos(t0)));
    }
    EXPECT_EQ(arcs, 1);
    EXPECT_NEAR(area, kSquareAndHalfDiscArea, 1e-9);
}

TEST(DrawingExport, SvgArcsTurnTheWayThePartDoes) {
    ScratchDir dir;
    writeFile(dir / "p.scad", kSquareAndHalfDisc);
    const auto r = exportPart(dir, "p.svg");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const std::string svg = readFile(dir / "p.svg");
    EXPECT_NE(svg.find("width=\"15mm\" height=\"10mm\" viewBox=\"0 -10 15 10\""), std::string::npos)
        << svg;
    // Every arc command ends on the circle (y negated on the page) and sweeps with flag 0
    // (clockwise on the page is counter-clockwise in the part); its ends stay on x >= 10.
    int arcs = 0;
    for (const SvgCommand& c : svgPath(svg)) {
        if (c.op != 'A') continue;
        ++arcs;
        ASSERT_EQ(c.args.size(), 7u);
        EXPECT_EQ(c.args[0], 5.0);
        EXPECT_EQ(c.args[4], 0.0) << "sweep flag";
        EXPECT_NEAR(std::hypot(c.args[5] - 10.0, c.args[6] + 5.0), 5.0, 1e-12);
        EXPECT_GE(c.args[5], 10.0 - 1e-12);
    }
    EXPECT_EQ(arcs, 2);  // a half turn is written as two arcs of at most a third of a turn
}

// csgray's import() reads its own drawings back, arcs exact: the extruded area is the part's,
// to the volume estimate's accuracy (rays along a generic direction; 1e-6 relative here).
TEST(DrawingExport, CsgrayReadsItsOwnDrawingsBack) {
    ScratchDir dir;
    writeFile(dir / "p.scad", kSquareAndHalfDisc);
    for (const char* file : {"p.svg", "p.dxf"}) {
        SCOPED_TRACE(file);
        ASSERT_EQ(exportPart(dir, file).exitCode, 0);
        writeFile(dir / "back.scad", "linear_extrude(1) import(\"" + std::string(file) + "\");\n");
        const io::EvaluateResult r = io::evaluateFile(dir / "back.scad", io::EvaluateOptions{});
        ASSERT_TRUE(r.ok()) << diagnosticsOf(r);
        const csg::Mat4 turn = glm::rotate(glm::rotate(csg::Mat4(1.0), 0.61, csg::Vec3(1, 0, 0)),
                                           0.37, csg::Vec3(0.2, 1, 0.3));
        const double volume =
            csg::volume(csg::Scene::compile(csg::transformed(turn, r.model->root)), 1024);
        EXPECT_NEAR(volume / kSquareAndHalfDiscArea, 1.0, 1e-6);
    }
}

using csg::testing::haveOpenScad;

// OpenSCAD's file of a part, made in dir.
void openscadExport(const fs::path& dir, const std::string& part, const std::string& out) {
    const std::string command = "cd " + cli::shellQuote(dir.string()) +
                                " && openscad --export-format " +
                                (out.ends_with(".stl") ? "binstl" : out.substr(out.size() - 3)) +
                                " -o " + out + " " + part + " >" + out + ".log 2>&1";
    ASSERT_EQ(std::system(command.c_str()), 0) << command << "\n" << readFile(dir / (out + ".log"));
}

// The circular segments OpenSCAD's chords cut off an arc of radius r turning `degrees` in n
// equal chords.
double chordLoss(double r, double degrees, int n) {
    const double theta = degrees / n * kPi / 180.0;
    return n * 0.5 * r * r * (theta - std::sin(theta));
}

TEST(DrawingExport, OpenScadReadsTheArcsBack) {
    if (!haveOpenScad()) SKIP_OR_FAIL_IN_CI("openscad (2021.01, Debian's) is not installed");
    ScratchDir dir;
    writeFile(dir / "p.scad", kSquareAndHalfDisc);
    for (const char* file : {"p.svg", "p.dxf"}) ASSERT_EQ(exportPart(dir, file).exitCode, 0);
    // SVG: each of the two 90-degree arc commands in floor(90 / 18 + 4) = 9 chords.
    writeFile(dir / "svg.scad", "linear_extrude(1) import(\"p.svg\");\n");
    openscadExport(dir.path(), "svg.scad", "svg.stl");
    EXPECT_NEAR(csg::testing::binaryStlVolume(dir / "svg.stl"),
                kSquareAndHalfDiscArea - 2 * chordLoss(5, 90, 9), 1e-4);
    // DXF: the 180-degree ARC in 180 chords ($fn = 360), whose points OpenSCAD snaps to its
    // 1/1024 grid: moving each of them up to 2^-11 along x and y moves the area up to about
    // 180 * 2^-11 * (2 pi 5 / 360) = 7.7e-3, and some 1/sqrt(180) of that when the roundings
    // are random. A wrong arc (bulging into the square) would lose 2 * 12.5 pi.
    writeFile(dir / "dxf.scad", "linear_extrude(1) import(\"p.dxf\", $fn = 360);\n");
    openscadExport(dir.path(), "dxf.scad", "dxf.stl");
    EXPECT_NEAR(csg::testing::binaryStlVolume(dir / "dxf.stl"),
                kSquareAndHalfDiscArea - chordLoss(5, 180, 180), 2e-3);
}

// Under --curves openscad a part is OpenSCAD's polygons: its SVG holds the same area as
// OpenSCAD's own SVG of the part (which prints 6 significant digits).
TEST(DrawingExport, FacetedDrawingsMatchOpenScads) {
    if (!haveOpenScad()) SKIP_OR_FAIL_IN_CI("openscad (2021.01, Debian's) is not installed");
    const std::vector<std::string> parts = {
        "difference() { square([10, 6]); translate([5, 3]) circle(2, $fn = 8); }",
        "union() { circle(5); translate([4, 0]) square(6); }",
        "offset(r = 1) polygon([[0, 0], [20, 0], [10, 10]]);",
        "polygon([[0, 0], [20, 0], [20, 20], [0, 20], [5, 5], [15, 5], [15, 15], [5, 15]],\n"
        "        [[0, 1, 2, 3], [4, 5, 6, 7]]);",
        "text(\"csg\", size = 10);",
    };
    ScratchDir dir;
    for (const std::string& part : parts) {
        SCOPED_TRACE(part);
        writeFile(dir / "p.scad", part + "\n");
        const auto r = exportPart(dir, "ours.svg", {"--curves", "openscad"});
        ASSERT_EQ(r.exitCode, 0) << r.err;
        openscadExport(dir.path(), "p.scad", "theirs.svg");
        const double ours = svgPolygonArea(svgPath(readFile(dir / "ours.svg")));
        const double theirs = svgPolygonArea(svgPath(readFile(dir / "theirs.svg")));
        EXPECT_GT(ours, 1.0);
        EXPECT_NEAR(ours / theirs, 1.0, 1e-5) << "csgray " << ours << ", OpenSCAD " << theirs;
    }
}

TEST(DrawingExport, ASolidIsNotDrawn) {
    ScratchDir dir;
    writeFile(dir / "p.scad", "cube(3);\n");
    const auto r = exportPart(dir, "p.svg");
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_NE(r.err.find("p.scad:1:1: error: export: the top level object is not a 2-D object"),
              std::string::npos)
        << r.err;
    EXPECT_FALSE(fs::exists(dir / "p.svg"));
}

TEST(DrawingExport, AnEmptyShapeIsAnEmptyDrawingWithAWarning) {
    ScratchDir dir;
    writeFile(dir / "p.scad", "intersection() { square(1); translate([5, 0]) square(1); }\n");
    const auto r = exportPart(dir, "p.dxf");
    EXPECT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.err.find("the shape is empty"), std::string::npos) << r.err;
    EXPECT_TRUE(dxfEntities(readFile(dir / "p.dxf")).empty());
}

}  // namespace
