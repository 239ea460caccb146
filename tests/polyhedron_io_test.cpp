// polyhedron() and import() in the part language (io/MeshModules.h): the cube of OpenSCAD's
// documentation answers rays as worked out by hand in either winding and through the deprecated
// triangles=; OpenSCAD's warnings (out-of-range index, deprecation) and errors (non-finite point,
// missing or malformed file) sit at their file:line:col; STL (ASCII and binary), OFF and OBJ
// files the test writes import as the same cube, found beside the .scad file that holds the
// call; and an STL that OpenSCAD 2021 writes has, through csgray, the volume the divergence
// theorem gives for OpenSCAD's own triangles.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>

#include "MissingTool.h"
#include "TempDir.h"
#include "csg/Scene.h"
#include "csg/Volume.h"
#include "io/Evaluate.h"

using namespace io;

namespace {

const char* const kCubePoints = "[[0,0,0],[1,0,0],[1,1,0],[0,1,0],[0,0,1],[1,0,1],[1,1,1],[0,1,1]]";
// OpenSCAD's documentation cube: each face clockwise seen from outside.
const char* const kCubeFaces = "[[0,1,2,3],[4,5,1,0],[7,6,5,4],[5,6,2,1],[6,7,3,2],[7,4,0,3]]";

std::string firstOf(const EvaluateResult& r, Severity severity) {
    for (const auto& d : r.diagnostics)
        if (d.severity == severity) return formatDiagnostic(d);
    return "<none>";
}

csg::Scene compiled(const EvaluateResult& r) {
    EXPECT_TRUE(r.ok()) << firstOf(r, Severity::Error);
    return csg::Scene::compile(r.ok() ? r.model->root : nullptr);
}

// The spans of one ray as (in, out) pairs.
std::vector<std::pair<double, double>> spans(const csg::Scene& scene, csg::Vec3 o, csg::Vec3 d) {
    csg::QueryContext ctx;
    std::vector<std::pair<double, double>> out;
    for (const csg::Span& s : scene.spans(csg::Ray{o, d, 0.0, csg::kInfinity}, ctx))
        out.push_back({s.in.t, s.out.t});
    return out;
}

// The unit cube, by hand: along z at (0.25, 0.5) from z = -1 it is inside for t in [1, 2]; along
// x at (y, z) = (0.5, 0.75) from x = -2, for t in [2, 3].
void expectUnitCube(const csg::Scene& scene) {
    using Spans = std::vector<std::pair<double, double>>;
    EXPECT_EQ(spans(scene, {0.25, 0.5, -1}, {0, 0, 1}), (Spans{{1.0, 2.0}}));
    EXPECT_EQ(spans(scene, {-2, 0.5, 0.75}, {1, 0, 0}), (Spans{{2.0, 3.0}}));
    EXPECT_TRUE(spans(scene, {1.5, 0.5, -1}, {0, 0, 1}).empty());
    const csg::Bounds3 box = scene.bounds();
    EXPECT_EQ(box.lo, csg::Vec3(0.0));
    EXPECT_EQ(box.hi, csg::Vec3(1.0));
}

void writeFile(const std::filesystem::path& path, const std::string& bytes) {
    std::filesystem::create_directories(path.parent_path());
    std::ofstream(path, std::ios::binary) << bytes;
}

// The cube's 12 triangles, wound counter-clockwise from outside (as STL and OBJ expect).
std::vector<std::array<csg::Vec3, 3>> cubeTriangles() {
    const csg::Vec3 p[8] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                            {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
    const int quads[6][4] = {{0, 3, 2, 1}, {0, 1, 5, 4}, {4, 5, 6, 7},
                             {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};
    std::vector<std::array<csg::Vec3, 3>> out;
    for (const auto& q : quads) {
        out.push_back({p[q[0]], p[q[1]], p[q[2]]});
        out.push_back({p[q[0]], p[q[2]], p[q[3]]});
    }
    return out;
}

std::string asciiStl() {
    std::ostringstream s;
    s << "solid cube\n";
    for (const auto& t : cubeTriangles()) {
        s << " facet normal 0 0 0\n  outer loop\n";
        for (const auto& v : t) s << "   vertex " << v.x << ' ' << v.y << ' ' << v.z << '\n';
        s << "  endloop\n endfacet\n";
    }
    s << "endsolid cube\n";
    return s.str();
}

std::string binaryStl() {
    // A header that starts with "solid" too: the size decides (OpenSCAD's rule).
    std::string bytes = "solid but binary";
    bytes.resize(80, ' ');
    const auto tris = cubeTriangles();
    const uint32_t n = uint32_t(tris.size());
    bytes.append(reinterpret_cast<const char*>(&n), 4);  // little-endian hosts only
    for (const auto& t : tris) {
        float f[12] = {};
        for (int c = 0; c < 3; ++c)
            for (int k = 0; k < 3; ++k) f[3 + 3 * c + k] = float(t[c][k]);
        bytes.append(reinterpret_cast<const char*>(f), sizeof f);
        bytes.append(2, '\0');
    }
    return bytes;
}

std::string offCube() {
    // As OpenSCAD writes OFF: counts on the header's line, quads, clockwise-from-inside order.
    return "OFF 8 6 0\n# a comment\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n0 0 1\n1 0 1\n1 1 1\n0 1 1\n"
           "4 0 3 2 1\n4 0 1 5 4\n4 4 5 6 7\n4 1 2 6 5\n4 2 3 7 6\n4 3 0 4 7\n";
}

std::string objCube() {
    return "# cube\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
           "f 1 4 3 2\nf 1 2 6 5\nf 5 6 7 8\nf 2/1 3/1 7/1 6/1\nf 3 4 8 7\nf 4 1 5 8\n";
}

TEST(PolyhedronIo, CubeByHandInBothWindings) {
    expectUnitCube(compiled(evaluateString(
        std::string("polyhedron(points = ") + kCubePoints + ", faces = " + kCubeFaces + ");",
        "test.scad")));
    // Reversed faces: the same solid.
    expectUnitCube(compiled(evaluateString(std::string("polyhedron(") + kCubePoints +
                                               ", [for (f = " + kCubeFaces +
                                               ") [for (i = [len(f) - 1 : -1 : 0]) f[i]]]);",
                                           "test.scad")));
}

TEST(PolyhedronIo, DeprecatedTriangles) {
    const EvaluateResult r = evaluateString(
        std::string("polyhedron(points = ") + kCubePoints + ",\n  triangles = " + kCubeFaces + ");",
        "test.scad");
    expectUnitCube(compiled(r));
    EXPECT_EQ(firstOf(r, Severity::Warning),
              "test.scad:2:3: warning: DEPRECATED: polyhedron(triangles=[]) will be removed in "
              "future releases. Use polyhedron(faces=[]) instead.");
}

TEST(PolyhedronIo, OutOfRangeIndexIsSkippedWithOpenScadsWarning) {
    // OpenSCAD 2021 on this part: "WARNING: Point index 7 is out of bounds (from faces[3][3])";
    // the face keeps its three good corners and the tetrahedron is closed.
    const EvaluateResult r = evaluateString(
        "polyhedron(points=[[0,0,0],[1,0,0],[0,1,0],[0,0,1]],\n"
        "           faces=[[0,1,2],[0,3,1],[0,2,3],[1,3,2,7]]);",
        "test.scad");
    const csg::Scene scene = compiled(r);
    ASSERT_EQ(r.diagnostics.size(), 1u) << firstOf(r, Severity::Warning);
    EXPECT_EQ(firstOf(r, Severity::Warning),
              "test.scad:2:12: warning: Point index 7 is out of bounds (from faces[3][3]); it is "
              "skipped");
    // Along z at (0.2, 0.3): z from 0 to 0.5.
    const auto s = spans(scene, {0.2, 0.3, -1}, {0, 0, 1});
    ASSERT_EQ(s.size(), 1u);
    EXPECT_DOUBLE_EQ(s[0].first, 1.0);
    EXPECT_NEAR(s[0].second, 1.5, 1e-15);
}

TEST(PolyhedronIo, ErrorsAndWarningsAreLocated) {
    // A non-finite point: an error at the points argument.
    EXPECT_EQ(
        firstOf(evaluateString("x = 1;\npolyhedron(points=[[0,0,0],[1,0,0],[0,1,0],[0,0,1/0]],"
                               " faces=[[0,1,2]]);",
                               "test.scad"),
                Severity::Error)
            .rfind("test.scad:2:12: error: polyhedron(): unable to convert points[3] = ", 0),
        0u);
    // An open mesh: a warning at the call saying what csgray does.
    const EvaluateResult open = evaluateString(
        "\n  polyhedron(points=[[0,0,0],[1,0,0],[0,1,0],[0,0,1]], faces=[[0,1,2],[0,3,1]]);",
        "test.scad");
    EXPECT_TRUE(open.ok());
    EXPECT_EQ(firstOf(open, Severity::Warning)
                  .rfind("test.scad:2:3: warning: polyhedron() is not closed: 4 of its 5 edges", 0),
              0u)
        << firstOf(open, Severity::Warning);
    // No face with area: the empty solid, with a warning.
    const EvaluateResult empty =
        evaluateString("polyhedron(points=[[0,0,0],[1,0,0]], faces=[[0,1,1]]);", "test.scad");
    EXPECT_TRUE(empty.ok());
    EXPECT_EQ(firstOf(empty, Severity::Warning),
              "test.scad:1:1: warning: polyhedron() has no faces of positive area; it is empty");
    // Wrong argument types.
    EXPECT_EQ(
        firstOf(evaluateString("polyhedron(points=5, faces=[]);", "test.scad"), Severity::Error)
            .rfind("test.scad:1:12: error: polyhedron(): 'points' must be a list", 0),
        0u);
}

TEST(PolyhedronIo, ImportsStlOffObjBesideTheirScadFile) {
    csg::testing::TempDir dir("csgray_import");
    writeFile(dir.path / "parts/ascii.stl", asciiStl());
    writeFile(dir.path / "parts/binary.stl", binaryStl());
    writeFile(dir.path / "parts/cube.off", offCube());
    writeFile(dir.path / "parts/cube.obj", objCube());
    writeFile(dir.path / "parts/CUBE.STL", asciiStl());
    // The library imports names relative to itself, not to the main file.
    writeFile(dir.path / "parts/lib.scad", "module part(name) import(name, convexity = 3);\n");
    for (const char* name : {"ascii.stl", "binary.stl", "cube.off", "cube.obj", "CUBE.STL"}) {
        SCOPED_TRACE(name);
        writeFile(dir.path / "main.scad",
                  std::string("use <parts/lib.scad>\npart(\"") + name + "\");\n");
        const EvaluateResult r = evaluateFile(dir.path / "main.scad");
        expectUnitCube(compiled(r));
        EXPECT_TRUE(r.diagnostics.empty()) << firstOf(r, Severity::Warning);
    }
    // Found next to the main file only: used, with OpenSCAD's deprecation warning.
    writeFile(dir.path / "top.stl", asciiStl());
    writeFile(dir.path / "main.scad", "use <parts/lib.scad>\npart(\"top.stl\");\n");
    const EvaluateResult r = evaluateFile(dir.path / "main.scad");
    expectUnitCube(compiled(r));
    EXPECT_NE(firstOf(r, Severity::Warning).find("found in document root"), std::string::npos);
}

// A 3MF as OpenSCAD writes it (lib3mf: a ZIP64 package), imported as the solid it holds.
TEST(PolyhedronIo, ImportsOpenScadsThreeMf) {
    if (std::system("openscad --version >/dev/null 2>&1") != 0)
        SKIP_OR_FAIL_IN_CI("openscad (2021.01, Debian's) is not installed");
    csg::testing::TempDir dir("csgray_import_3mf");
    writeFile(dir.path / "cube.scad", "cube(1);\n");
    const std::string command =
        "cd '" + dir.path.string() + "' && openscad -o parts/cube.3mf cube.scad >/dev/null 2>&1";
    std::filesystem::create_directories(dir.path / "parts");
    ASSERT_EQ(std::system(command.c_str()), 0) << command;
    writeFile(dir.path / "main.scad", "import(\"parts/cube.3mf\");\n");
    const EvaluateResult r = evaluateFile(dir.path / "main.scad");
    expectUnitCube(compiled(r));
    EXPECT_TRUE(r.diagnostics.empty()) << firstOf(r, Severity::Warning);
}

TEST(PolyhedronIo, MissingAndMalformedFilesAreErrorsAtTheImport) {
    csg::testing::TempDir dir("csgray_import_errors");
    writeFile(dir.path / "main.scad", "cube(1);\ntranslate([2, 0, 0]) import(\"nothere.stl\");\n");
    EXPECT_EQ(firstOf(evaluateFile(dir.path / "main.scad"), Severity::Error),
              (dir.path / "main.scad").string() + ":2:29: error: import(): " +
                  (dir.path / "nothere.stl").string() + ": cannot open the mesh");
    writeFile(dir.path / "bad.stl",
              "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0\n");
    writeFile(dir.path / "main.scad", "\n\n  import(file = \"bad.stl\");\n");
    EXPECT_EQ(firstOf(evaluateFile(dir.path / "main.scad"), Severity::Error),
              (dir.path / "main.scad").string() +
                  ":3:10: error: import(): " + (dir.path / "bad.stl").string() +
                  ":5:11: expected a finite number (vertex x y z)");
    writeFile(dir.path / "bad.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 5\n");
    writeFile(dir.path / "main.scad", "import(\"bad.off\");\n");
    EXPECT_EQ(firstOf(evaluateFile(dir.path / "main.scad"), Severity::Error),
              (dir.path / "main.scad").string() +
                  ":1:8: error: import(): " + (dir.path / "bad.off").string() +
                  ":6:7: vertex index 5 names no vertex (3 vertices)");
    // AMF is a format OpenSCAD imports and csgray does not (SVG now loads: svg_import_test).
    writeFile(dir.path / "main.scad", "import(\"part.amf\");\n");
    EXPECT_NE(firstOf(evaluateFile(dir.path / "main.scad"), Severity::Error)
                  .find("main.scad:1:8: error: import(): importing .amf files is not supported"),
              std::string::npos);
    // A drawing.svg that is there loads: a 2 x 3 rectangle, no error.
    writeFile(dir.path / "drawing.svg", "<svg><rect width=\"2\" height=\"3\"/></svg>\n");
    writeFile(dir.path / "main.scad", "import(\"drawing.svg\");\n");
    EXPECT_EQ(firstOf(evaluateFile(dir.path / "main.scad"), Severity::Error), "<none>");
}

// The volume of a closed triangle soup by the divergence theorem: the sum of the signed volumes
// of the tetrahedra from the origin to each triangle.
double divergenceVolume(const std::vector<std::array<csg::Vec3, 3>>& triangles) {
    double v = 0.0;
    for (const auto& t : triangles) v += glm::dot(t[0], glm::cross(t[1], t[2])) / 6.0;
    return std::abs(v);
}

// OpenSCAD's ASCII STL read here by a few lines of its own (not csgray's reader).
std::vector<std::array<csg::Vec3, 3>> readAsciiStl(const std::filesystem::path& file) {
    std::ifstream in(file);
    std::vector<std::array<csg::Vec3, 3>> out;
    std::array<csg::Vec3, 3> t;
    int corner = 0;
    std::string word;
    while (in >> word)
        if (word == "vertex") {
            in >> t[corner].x >> t[corner].y >> t[corner].z;
            if (++corner == 3) out.push_back(t), corner = 0;
        }
    return out;
}

TEST(PolyhedronIo, OpenScadsStlHasOpenScadsVolume) {
    if (std::system("openscad --version >/dev/null 2>&1") != 0)
        SKIP_OR_FAIL_IN_CI("openscad (2021.01, Debian's) is not installed");
    csg::testing::TempDir dir("csgray_openscad_stl");
    // A cube with a 12-sided hole, turned: no face is axis-aligned, and along z the span length
    // depends on x only (the hole runs along y), so the volume's grid integrates it to ~1e-8.
    writeFile(dir.path / "part.scad",
              "rotate([0, 30, 0]) difference() {\n"
              "    cube(10, center = true);\n"
              "    rotate([90, 0, 0]) cylinder(r = 3, h = 20, center = true, $fn = 12);\n"
              "}\n");
    const std::string command =
        "cd '" + dir.path.string() + "' && openscad -o part.stl part.scad >openscad.log 2>&1";
    ASSERT_EQ(std::system(command.c_str()), 0) << "openscad failed on the part";
    const auto triangles = readAsciiStl(dir.path / "part.stl");
    ASSERT_GT(triangles.size(), 20u);
    const double expected = divergenceVolume(triangles);
    // Roughly 1000 less the 12-gon prism's 12 * 9 * sin(30) * 10.
    EXPECT_NEAR(expected, 1000.0 - 540.0 * 0.5 * 1.0, 1.0);
    writeFile(dir.path / "main.scad", "import(\"part.stl\");\n");
    const EvaluateResult r = evaluateFile(dir.path / "main.scad");
    EXPECT_TRUE(r.diagnostics.empty()) << firstOf(r, Severity::Warning);
    const double measured = csg::volume(compiled(r), 4096);
    EXPECT_NEAR(measured / expected, 1.0, 1e-6) << measured << " vs " << expected;
}

}  // namespace
