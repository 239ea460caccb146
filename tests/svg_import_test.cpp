// SVG drawings (io/SvgFile.h, io/SvgShapes.h, io/SvgModule.h): import("x.svg"). The oracles
// are independent of csgray:
//   - small SVG files written here, whose spans along probe lines and whose areas are worked
//     out by hand: rectangles under transforms and page maps (units, viewBox,
//     preserveAspectRatio, the y flip, center), a circle (pi r^2), a rotated ellipse (its
//     polar radius), a cubic Bezier region (the closed-form integral of y dx), a quadratic with
//     its smooth continuation, arcs (half discs), strokes (their rectangles);
//   - OpenSCAD's chords by hand under --curves openscad (a 40-gon, 20 chords of a Bezier, 14 of
//     a half-circle arc);
//   - OpenSCAD 2021's own STL of the same file (`openscad` on the PATH): its volume by the
//     divergence theorem.
// Notation: t is the parameter of o + t d; probe rays have unit d, so t is a distance. Areas
// are the volumes of linear_extrude(1).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <numbers>
#include <sstream>

#include "BinaryStl.h"
#include "MissingTool.h"
#include "TempDir.h"
#include "csg/Scene.h"
#include "csg/Volume.h"
#include "io/Evaluate.h"
#include "io/SvgFile.h"
#include "tests/PartHelpers.h"

using namespace io;

namespace {

using Spans = std::vector<std::pair<double, double>>;
namespace fs = std::filesystem;
constexpr double kPi = std::numbers::pi;

void writeFile(const fs::path& path, const std::string& bytes) {
    std::ofstream(path, std::ios::binary) << bytes;
}

// An SVG document of these elements, with these attributes on <svg>.
std::string svg(const std::string& body, const std::string& page = "") {
    return "<svg xmlns=\"http://www.w3.org/2000/svg\"" + (page.empty() ? "" : " " + page) + ">\n" +
           body + "\n</svg>\n";
}

using csg::testing::diagnosticsOf;
using csg::testing::firstDiagnostic;

EvaluateResult run(const fs::path& dir, const std::string& scad,
                   CurveMode curves = CurveMode::Auto) {
    writeFile(dir / "main.scad", scad);
    EvaluateOptions options;
    options.curves = curves;
    return evaluateFile(dir / "main.scad", options);
}

csg::Scene compiled(const EvaluateResult& r) {
    EXPECT_TRUE(r.ok()) << diagnosticsOf(r);
    return csg::Scene::compile(r.ok() ? r.model->root : nullptr);
}

// The drawing `body` (in an <svg> with `page`) imported and extruded to height 1.
csg::Scene drawing(const fs::path& dir, const std::string& body, const std::string& page = "",
                   const std::string& args = "", CurveMode curves = CurveMode::Auto) {
    writeFile(dir / "d.svg", svg(body, page));
    return compiled(run(dir, "linear_extrude(1) import(\"d.svg\"" + args + ");\n", curves));
}

constexpr auto* spans = &csg::testing::spanPairs;

// Spans of the line y = y0 (z = 0.5) from x = -100, as x intervals.
Spans alongX(const csg::Scene& scene, double y0) {
    Spans s = spans(scene, {-100, y0, 0.5}, {1, 0, 0});
    for (auto& [a, b] : s) a -= 100, b -= 100;
    return s;
}
// Spans of the line x = x0 from y = -100, as y intervals.
Spans alongY(const csg::Scene& scene, double x0) {
    Spans s = spans(scene, {x0, -100, 0.5}, {0, 1, 0});
    for (auto& [a, b] : s) a -= 100, b -= 100;
    return s;
}

void expectSpans(const Spans& got, const Spans& want, double tol = 1e-9) {
    csg::testing::expectSpanPairs(got, want, tol);
}

// The area of the drawing (its extrusion's volume): csg::volume's quadrature across a curved
// silhouette errs by ~resolution^-1.5 relative (1e-5 at 2048), so 1e-4 relative is asked.
void expectArea(const csg::Scene& scene, double want, double rel = 1e-4) {
    EXPECT_NEAR(csg::volume(scene, 2048) / want, 1.0, rel) << "want " << want;
}

// ---- shapes, transforms and the page ----

TEST(SvgImport, RectWithoutPageIsInMillimetresWithYFlipped) {
    csg::testing::TempDir dir("csgray_svg_rect");
    // No width, height or viewBox: one user unit is 1 mm, y = 0 - y_svg.
    const csg::Scene s = drawing(dir.path, "<rect x=\"1\" y=\"2\" width=\"3\" height=\"4\"/>");
    expectSpans(alongX(s, -3), {{1, 4}});
    expectSpans(alongY(s, 2), {{-6, -2}});
    expectArea(s, 12, 1e-9);
}

TEST(SvgImport, PageHeightFlipsAndUnitsScale) {
    csg::testing::TempDir dir("csgray_svg_units");
    const std::string rect = "<rect x=\"10\" y=\"5\" width=\"20\" height=\"10\"/>";
    // 100 x 50 mm onto a 100 x 50 viewBox: scale 1, y = 50 - y_svg.
    csg::Scene s =
        drawing(dir.path, rect, "width=\"100mm\" height=\"50mm\" viewBox=\"0 0 100 50\"");
    expectSpans(alongX(s, 40), {{10, 30}});
    expectSpans(alongY(s, 20), {{35, 45}});
    // 4 in x 2 in onto 400 x 200: 0.254 mm a unit; height 50.8 mm.
    s = drawing(dir.path, rect, "width=\"4in\" height=\"2in\" viewBox=\"0 0 400 200\"");
    expectSpans(alongX(s, 50.8 - 2), {{2.54, 7.62}});
    expectSpans(alongY(s, 5), {{50.8 - 15 * 0.254, 50.8 - 5 * 0.254}});
    // Each unit of a 96-unit-wide viewBox page: px (1/96 in), pt (1/72 in), pc (1/6 in), cm,
    // and unitless at dpi 72 (the default) and at dpi 96.
    const std::pair<std::string, double> widths[] = {
        {"96px", 25.4}, {"72pt", 25.4}, {"6pc", 25.4}, {"2.54cm", 25.4}, {"72", 25.4}};
    for (const auto& [w, mm] : widths) {
        SCOPED_TRACE(w);
        s = drawing(dir.path, "<rect x=\"0\" y=\"0\" width=\"96\" height=\"1\"/>",
                    "width=\"" + w + "\" height=\"" + w + "\" viewBox=\"0 0 96 96\"");
        expectSpans(alongX(s, mm - 0.1), {{0, mm}});
    }
    s = drawing(dir.path, "<rect x=\"0\" y=\"0\" width=\"96\" height=\"1\"/>",
                "width=\"72\" height=\"72\" viewBox=\"0 0 96 96\"", ", dpi = 96");
    expectSpans(alongX(s, 19.05 - 0.1), {{0, 19.05}});  // 72 / 96 in
    // Unitless with no viewBox: user units are millimetres, the height 72 / 72 in.
    s = drawing(dir.path, "<rect x=\"0\" y=\"0\" width=\"5\" height=\"1\"/>",
                "width=\"72\" height=\"72\"");
    expectSpans(alongX(s, 25.4 - 0.5), {{0, 5}});
}

TEST(SvgImport, PreserveAspectRatio) {
    csg::testing::TempDir dir("csgray_svg_aspect");
    // A 100 x 50 mm page on a 10 x 10 viewBox: scales 10 and 5.
    const std::string fill = "<rect x=\"0\" y=\"0\" width=\"10\" height=\"10\"/>";
    const std::string page = "width=\"100mm\" height=\"50mm\" viewBox=\"0 0 10 10\"";
    // Default xMidYMid meet: scale 5, centred in x (100/2 - 25 = 25).
    csg::Scene s = drawing(dir.path, fill, page);
    expectSpans(alongX(s, 25), {{25, 75}});
    expectSpans(alongY(s, 50), {{0, 50}});
    // none: each axis its own scale.
    s = drawing(dir.path, fill, page + " preserveAspectRatio=\"none\"");
    expectSpans(alongX(s, 25), {{0, 100}});
    // xMinYMin slice: scale 10, y = 50 - 10 y_svg.
    s = drawing(dir.path, fill, page + " preserveAspectRatio=\"xMinYMin slice\"");
    expectSpans(alongX(s, 0), {{0, 100}});
    expectSpans(alongY(s, 50), {{-50, 50}});
    // A viewBox origin shifts: x = 5 (x_svg - 2).
    s = drawing(
        dir.path, "<rect x=\"2\" y=\"0\" width=\"4\" height=\"10\"/>",
        "width=\"100mm\" height=\"50mm\" viewBox=\"2 0 10 10\" preserveAspectRatio=\"xMinYMid\"");
    expectSpans(alongX(s, 25), {{0, 20}});
}

TEST(SvgImport, TransformsComposeInsideOut) {
    csg::testing::TempDir dir("csgray_svg_transform");
    // scale(2, 3), then rotate(90) (x, y) -> (-y, x), then translate(10, 0): [7, 10] x [0, 4];
    // flipped: y in [-4, 0].
    const csg::Scene s = drawing(
        dir.path,
        "<g transform=\"translate(10,0)\"><g transform=\"rotate(90)\">"
        "<rect transform=\"scale(2 3)\" x=\"0\" y=\"0\" width=\"2\" height=\"1\"/></g></g>");
    expectSpans(alongX(s, -1), {{7, 10}});
    expectSpans(alongY(s, 8), {{-4, 0}});
    expectArea(s, 12, 1e-9);
    // The same in one list, and as a matrix.
    expectSpans(alongX(drawing(dir.path,
                               "<rect transform=\"translate(10) rotate(90) scale(2,3)\" "
                               "width=\"2\" height=\"1\"/>"),
                       -1),
                {{7, 10}});
    expectSpans(alongX(drawing(dir.path,
                               "<rect transform=\"matrix(0 2 -3 0 10 0)\" width=\"2\" "
                               "height=\"1\"/>"),
                       -1),
                {{7, 10}});
    // skewX(45): (x + y, y); the unit square's row at y_svg = 0.5 is x in [0.5, 1.5].
    expectSpans(
        alongX(drawing(dir.path, "<rect transform=\"skewX(45)\" width=\"1\" height=\"1\"/>"), -0.5),
        {{0.5, 1.5}});
    // rotate(180, 5, 5) about (5, 5): [0, 2] x [0, 1] goes to [8, 10] x [9, 10].
    expectSpans(alongX(drawing(dir.path,
                               "<rect transform=\"rotate(180 5 5)\" width=\"2\" "
                               "height=\"1\"/>"),
                       -9.5),
                {{8, 10}});
}

TEST(SvgImport, CircleAndRotatedEllipseAreExact) {
    csg::testing::TempDir dir("csgray_svg_circle");
    // r = 5 at the origin: the chord at |y| = 3 is [-4, 4]; area 25 pi.
    csg::Scene s = drawing(dir.path, "<circle cx=\"0\" cy=\"0\" r=\"5\"/>");
    expectSpans(alongX(s, 3), {{-4, 4}});
    expectSpans(alongY(s, 0), {{-5, 5}});
    expectArea(s, 25 * kPi);
    // rx 4, ry 2 turned 30 degrees: the x axis meets it at polar angle 30 from its major axis,
    // radius 1 / sqrt(cos^2 / 16 + sin^2 / 4); area pi 4 2.
    s = drawing(dir.path,
                "<ellipse transform=\"rotate(30)\" cx=\"0\" cy=\"0\" rx=\"4\" ry=\"2\"/>");
    const double r = 1 / std::sqrt(0.75 / 16 + 0.25 / 4);
    expectSpans(alongX(s, 0), {{-r, r}});
    expectArea(s, 8 * kPi);
}

TEST(SvgImport, BezierRegionsHaveTheirClosedFormAreas) {
    csg::testing::TempDir dir("csgray_svg_bezier");
    // (0,0) (0,10) (10,10) (10,0): x = 30u^2 - 20u^3, y = 30u(1 - u); the integral of y dx is
    // 1800 * integral of u^2 (1 - u)^2 = 60.
    csg::Scene s = drawing(dir.path, "<path d=\"M0 0 C 0 10 10 10 10 0 Z\"/>");
    expectArea(s, 60);
    // Its row at y_svg = 6: u (1 - u) = 0.2.
    const double u1 = (1 - std::sqrt(0.2)) / 2, u2 = (1 + std::sqrt(0.2)) / 2;
    auto x = [](double u) { return 30 * u * u - 20 * u * u * u; };
    expectSpans(alongX(s, -6), {{x(u1), x(u2)}});
    // Relative c and the smooth s: the same curve twice, side by side.
    s = drawing(dir.path, "<path d=\"m0 0 c0 10 10 10 10 0 s 10 -10 10 0 z\"/>");
    // s reflects the control (10,10) about (10,0) to (10,-10); its own control and end are
    // (20,-10) and (20,0): the lobe mirrored below the axis, area 60 again.
    expectArea(s, 120);
    // Q (0,0) (5,10) (10,0) encloses 2/3 of its control triangle (50): 100/3; T reflects the
    // control to (15,-10): the same lobe mirrored below the axis.
    s = drawing(dir.path, "<path d=\"M0 0 Q 5 10 10 0 T 20 0 Z\"/>");
    expectArea(s, 200.0 / 3);
    expectSpans(alongY(s, 5), {{-5, 0}});  // the peak y_svg = 5 (control height / 2), flipped
}

TEST(SvgImport, ArcsAreExactHalfDiscs) {
    csg::testing::TempDir dir("csgray_svg_arc");
    // From (0,0) to (10,0), r = 5, sweep 1: the half disc with y_svg <= 0, so y >= 0.
    csg::Scene s = drawing(dir.path, "<path d=\"M 0 0 A 5 5 0 0 1 10 0 Z\"/>");
    expectSpans(alongY(s, 5), {{0, 5}});
    expectSpans(alongX(s, 3), {{1, 9}});
    expectArea(s, 12.5 * kPi);
    // A radius too small grows to fit (5); sweep 0 takes the other half.
    s = drawing(dir.path, "<path d=\"M 0 0 A 1 1 0 0 0 10 0 Z\"/>");
    expectSpans(alongY(s, 5), {{-5, 0}});
    // Rounded rect corners: 10 x 10 with r = 2 loses (4 - pi) r^2 / ... = 4 (4 - pi).
    s = drawing(dir.path, "<rect width=\"10\" height=\"10\" rx=\"2\"/>");
    expectArea(s, 100 - 4 * (4 - kPi));
    expectSpans(alongX(s, -1), {{2 - std::sqrt(3.0), 8 + std::sqrt(3.0)}});
}

TEST(SvgImport, OpenPathsAndLinesAreStroked) {
    csg::testing::TempDir dir("csgray_svg_stroke");
    // Width 2, square caps (the default): [-1, 11] x [-1, 1].
    csg::Scene s =
        drawing(dir.path, "<line x1=\"0\" y1=\"0\" x2=\"10\" y2=\"0\" stroke-width=\"2\"/>");
    expectSpans(alongX(s, 0.5), {{-1, 11}});
    expectSpans(alongY(s, 5), {{-1, 1}});
    expectArea(s, 24, 1e-9);
    // An open path alike; butt caps from the style: [0, 10] x [-1, 1].
    s = drawing(dir.path, "<path d=\"M 0 0 H 10\" style=\"stroke-width:2;stroke-linecap:butt\"/>");
    expectArea(s, 20, 1e-9);
    // A polyline, width 1, square caps, a miter join (its ratio sqrt 2 is within Clipper's
    // limit 2, so the corner is sharp): the bands [0, 16] x [0, 1] and [15, 16] x [0, 16],
    // 16 each, overlapping in 1 (the bounds [0, 16] put every edge on the volume's grid).
    s = drawing(dir.path, "<polyline points=\"0.5,0.5 15.5,0.5 15.5,15.5\"/>");
    expectArea(s, 31, 1e-9);
    expectSpans(alongY(s, 15.5), {{-16, 0}});
    // Ends within 0.1 of each other: closed, so filled, not stroked: the quadrilateral
    // (0,0) (10,0) (10,10) (0,0.05), by the shoelace formula (100 + 0.5) / 2.
    s = drawing(dir.path, "<path d=\"M0 0 L10 0 L10 10 L0 0.05\"/>");
    expectArea(s, 50.25);
}

TEST(SvgImport, EachShapeEvenOddShapesUnited) {
    csg::testing::TempDir dir("csgray_svg_union");
    // One path of two nested squares: a hole.
    csg::Scene s = drawing(dir.path, "<path d=\"M0 0 H10 V10 H0 Z M2 2 H8 V8 H2 Z\"/>");
    expectSpans(alongX(s, -5), {{0, 2}, {8, 10}});
    // The same squares as two elements: united, no hole.
    s = drawing(dir.path,
                "<rect width=\"10\" height=\"10\"/><rect x=\"2\" y=\"2\" width=\"6\" "
                "height=\"6\" fill=\"none\"/>");
    expectSpans(alongX(s, -5), {{0, 10}});
    // Nothing in defs is drawn; text is not drawn (with a warning).
    s = drawing(dir.path,
                "<defs><rect width=\"50\" height=\"50\"/></defs><rect width=\"1\" "
                "height=\"1\"/><text x=\"0\" y=\"0\">hi</text>");
    expectSpans(alongX(s, -0.5), {{0, 1}});
}

TEST(SvgImport, CenterCentresTheBoundingBox) {
    csg::testing::TempDir dir("csgray_svg_center");
    const csg::Scene s = drawing(dir.path, "<rect x=\"3\" y=\"4\" width=\"10\" height=\"20\"/>", "",
                                 ", center = true");
    expectSpans(alongX(s, 0), {{-5, 5}});
    expectSpans(alongY(s, 0), {{-10, 10}});
    // A curve's box is its own, not its control points': the Bezier above spans x [0, 10],
    // y_svg [0, 7.5].
    const csg::Scene c =
        drawing(dir.path, "<path d=\"M0 0 C 0 10 10 10 10 0 Z\"/>", "", ", center = true");
    expectSpans(alongY(c, 0), {{-3.75, 3.75}});
    expectSpans(alongX(c, 3.75 - 1e-9), {{-5, 5}}, 1e-6);  // just inside the chord
}

// ---- OpenSCAD's chords ----

TEST(SvgImport, CurvesAsOpenScadsChords) {
    csg::testing::TempDir dir("csgray_svg_chords");
    // Circle: 40 points; area 40/2 r^2 sin 9 degrees.
    csg::Scene s = drawing(dir.path, "<circle r=\"10\"/>", "", "", CurveMode::OpenScad);
    expectArea(s, 20 * 100 * std::sin(kPi / 20));
    // The Bezier: the polygon through its points at u = k / 20 (shoelace, by hand formulas).
    s = drawing(dir.path, "<path d=\"M0 0 C 0 10 10 10 10 0 Z\"/>", "", "", CurveMode::OpenScad);
    double twice = 0;
    for (int k = 0; k < 20; ++k) {
        auto at = [](double u) { return std::pair{30 * u * u - 20 * u * u * u, 30 * u * (1 - u)}; };
        const auto [x0, y0] = at(k / 20.0);
        const auto [x1, y1] = at((k + 1) / 20.0);
        twice += x0 * y1 - x1 * y0;
    }
    expectArea(s, std::abs(twice) / 2);
    // The half-circle arc: floor(180 / 18 + 4) = 14 chords.
    s = drawing(dir.path, "<path d=\"M 0 0 A 5 5 0 0 1 10 0 Z\"/>", "", "", CurveMode::OpenScad);
    expectArea(s, 14 * 12.5 * std::sin(kPi / 14));
}

// ---- errors and warnings ----

TEST(SvgImport, ErrorsNameTheSvgLine) {
    csg::testing::TempDir dir("csgray_svg_errors");
    const std::string main = (dir.path / "main.scad").string();
    const std::string bad = (dir.path / "bad.svg").string();
    writeFile(dir.path / "bad.svg", "<svg>\n<g>\n<rect/>\n</svg>\n");
    EXPECT_EQ(firstDiagnostic(run(dir.path, "\n  import(\"bad.svg\");\n"), Severity::Error),
              main + ":2:10: error: import(): " + bad +
                  ":2: malformed XML: the element here is closed by the end tag of another");
    // A drawing whose one element is wrong: the error at the import, then the SVG's line.
    const auto expectError = [&](const std::string& body, const std::string& message) {
        writeFile(dir.path / "bad.svg", svg(body));
        EXPECT_EQ(firstDiagnostic(run(dir.path, "import(\"bad.svg\");\n"), Severity::Error),
                  main + ":1:8: error: import(): " + bad + message);
    };
    expectError("<path d=\"M 0 0 L 10\"/>",
                ":2: path d: the path data ends where a number of 'L' is due");
    expectError("\n<path d=\"L 0 0\"/>",
                ":3: path d: path data must begin with a moveto (M or m), not 'L'");
    expectError("<polygon points=\"0,0 1e99,0 1,1\"/>",
                ":2: polygon points: the number 1e99 is beyond +-2^40");
    expectError("<rect transform=\"skewX(90)\" width=\"1\" height=\"1\"/>",
                ":2: transform \"skewX(90)\" is not finite");
    EXPECT_EQ(firstDiagnostic(run(dir.path, "import(\"none.svg\");\n"), Severity::Error),
              main + ":1:8: error: import(): " + (dir.path / "none.svg").string() +
                  ": cannot open the SVG file");
    // Warnings where OpenSCAD reads the file otherwise than it means, and goes on.
    writeFile(dir.path / "w.svg", svg("<rect x=\"1mm\" width=\"1\" height=\"1\"/>\n"
                                      "<line x2=\"1\" stroke-width=\"2px\"/>\n<text>hi</text>\n"
                                      "<path d=\"M0 0 a1 1 0 0 1 2 0 a1 1 0 012 0z\"/>"));
    const EvaluateResult w = run(dir.path, "import(\"w.svg\", center = 1, dpi = 0);\n");
    EXPECT_TRUE(w.ok()) << diagnosticsOf(w);
    const std::string all = diagnosticsOf(w);
    const std::string ws = (dir.path / "w.svg").string();
    for (const std::string& want :
         {main + ":1:17: warning: import(): center = 1 is not a boolean; false is used, as in "
                 "OpenSCAD",
          main + ":1:29: warning: import(): dpi = 0 is below 0.001; 72 is used, as in OpenSCAD",
          main + ":1:1: warning: import(): " + ws +
              ":2: rect x=\"1mm\" is not a plain number; it is read as 0, as OpenSCAD 2021 reads "
              "it",
          main + ":1:1: warning: import(): " + ws +
              ":3: stroke-width \"2px\" is not a plain number; it is read as 1, as OpenSCAD 2021 "
              "reads it",
          main + ":1:1: warning: import(): " + ws + ":4: SVG text is not drawn (nor by OpenSCAD)",
          main + ":1:1: warning: import(): " + ws +
              ":5: arc flags written without a separator (column 28 of the path data) are read "
              "as SVG defines them; OpenSCAD 2021 misreads them"})
        EXPECT_NE(all.find(want + "\n"), std::string::npos) << want << "\n---\n" << all;
    // Past 20 warnings a count.
    std::string many;
    for (int k = 0; k < 30; ++k) many += "<rect x=\"1mm\" width=\"1\" height=\"1\"/>\n";
    writeFile(dir.path / "many.svg", svg(many));
    const std::string manyDiagnostics = diagnosticsOf(run(dir.path, "import(\"many.svg\");\n"));
    EXPECT_NE(manyDiagnostics.find("many.svg:21: rect x="), std::string::npos);
    EXPECT_EQ(manyDiagnostics.find("many.svg:22: rect x="), std::string::npos);
    EXPECT_NE(manyDiagnostics.find("warning: import(): " + (dir.path / "many.svg").string() +
                                   ": ... and 10 more warnings\n"),
              std::string::npos)
        << manyDiagnostics;
    // layer/origin/scale are DXF's.
    EXPECT_NE(diagnosticsOf(run(dir.path, "import(\"w.svg\", scale = 2);\n"))
                  .find("import(): 'scale' applies to DXF files only; ignored"),
              std::string::npos);
}

TEST(SvgImport, ReaderNeverMakesNaNAndCapsWork) {
    // A few hostile inputs straight to the reader: each is a drawing or an error, never NaN.
    const char* inputs[] = {
        "",
        "<svg",
        "<svg/>",
        "<svg><path d=\"M0 0 A 0 0 0 0 1 1 1 A 1 1 0 0 1 1 1 Z\"/></svg>",
        "<svg viewBox=\"0 0 0 0\" width=\"10\"><rect width=\"1\" height=\"1\"/></svg>",
        "<svg><path d=\"M0 0 1 1 2 0\" stroke-width=\"1e12\" stroke-linejoin=\"round\"/></svg>",
        "<svg><g transform=\"scale(1e12)\"><g transform=\"scale(1e12)\"><g "
        "transform=\"scale(1e12)\"><rect width=\"1e12\" height=\"1\"/></g></g></g></svg>",
        "<svg><path d=\"M0 0 L 1 1 M 0 0 Z z z L 3 3 q 1 1 2 2 t 1 1 s 1 1 1 1\"/></svg>",
    };
    for (const char* text : inputs) {
        SCOPED_TRACE(text);
        SvgOptions options;
        options.maxSegments = 100000;
        const SvgReadResult r = readSvg(text, options);
        EXPECT_NE(r.drawing.has_value(), !r.error.empty());
        if (!r.drawing) continue;
        for (const csg::Outline& o : r.drawing->shapes)
            for (const csg::Segment2& seg : o.segments)
                for (const csg::Vec2& p : seg.p) EXPECT_TRUE(std::isfinite(p.x + p.y));
    }
    // A wide round stroke would need ~10^8 points: refused by the cap, not made.
    SvgOptions options;
    options.maxSegments = 1000000;
    const SvgReadResult r = readSvg(
        "<svg><line x2=\"1\" stroke-width=\"1e9\" stroke-linecap=\"round\"/></svg>", options);
    EXPECT_FALSE(r.drawing);
    EXPECT_EQ(r.error, "a stroke would have more than 1000000 segments");
    EXPECT_EQ(r.line, 1u);
    // A polyline going back and forth on one line 10^4 times: 2 10^8 pairs of edges may
    // cross, which Clipper's union would take minutes over; refused at once.
    std::string zigzag = "<svg>\n<polyline points=\"";
    for (int k = 0; k < 10000; ++k) zigzag += "0,0 10,0 ";
    const SvgReadResult z = readSvg(zigzag + "\"/></svg>", SvgOptions());
    EXPECT_FALSE(z.drawing);
    EXPECT_EQ(z.error,
              "a stroked path doubles back on itself too often to stroke (more than 100000000 "
              "pairs of its 19999 edges may cross)");
    EXPECT_EQ(z.line, 2u);
    // A spiral of 1600 turns: no crossings, but each scanline of Clipper's sweep meets ~3000
    // edges, 300000 times; refused at once too.
    std::ostringstream spiral;
    spiral << "<svg><polyline points=\"";
    for (int k = 0; k < 300000; ++k)
        spiral << 50 + (1 + k / 4000.0) * std::cos(k / 30.0) << ","
               << 50 + (1 + k / 4000.0) * std::sin(k / 30.0) << " ";
    spiral << "\"/></svg>";
    const SvgReadResult w = readSvg(spiral.str(), SvgOptions());
    EXPECT_EQ(w.error,
              "a stroked path winds round too often to stroke (its 299999 edges span more than "
              "100000000 scanlines in all)");
}

// ---- against OpenSCAD 2021 ----

using csg::testing::haveOpenScad;

double stlVolume(const fs::path& file) {
    return std::abs(csg::testing::binaryStlVolume(file));
}

// A drawing of every element kind, under a page map and transforms, extruded by both: with
// --curves openscad the same chords and the same Clipper strokes, so the volumes differ only
// by OpenSCAD's 2^-16 grid (a vertex moves at most 2^-17 per axis, the area at most perimeter
// x 2^-17 x sqrt 2: ~245 mm of outline here, 1e-5 of the area at worst, far less as the
// rounding cancels), its float STL (6e-8 per coordinate) and csgray's quadrature (the part
// turned generically, as dxf_test does: ~1e-6 at resolution 1024). 2e-5 relative is asked;
// measured +1.1e-6 and +1.8e-6 (centred).
// The volume of linear_extrude(1) import(file `args`) by csgray (--curves openscad) and by
// OpenSCAD, run in dir.
void expectOpenScadsVolume(const fs::path& dir, const std::string& file, const std::string& args) {
    SCOPED_TRACE(file + args);
    const std::string scad = "linear_extrude(1) import(\"" + file + "\"" + args + ");\n";
    writeFile(dir / "part.scad", scad);
    const std::string command = "cd '" + dir.string() +
                                "' && openscad --export-format binstl -o part.stl part.scad "
                                ">part.log 2>&1";
    ASSERT_EQ(std::system(command.c_str()), 0) << command;
    const double theirs = stlVolume(dir / "part.stl");
    ASSERT_GT(theirs, 0);
    const EvaluateResult r = run(dir, scad, CurveMode::OpenScad);
    ASSERT_TRUE(r.ok()) << diagnosticsOf(r);
    // Turned generically, so that no edge is parallel to the rays (dxf_test's way).
    const csg::Mat4 turn = glm::rotate(glm::rotate(csg::Mat4(1.0), 0.61, csg::Vec3(1, 0, 0)), 0.37,
                                       csg::Vec3(0.2, 1, 0.3));
    const double ours =
        csg::volume(csg::Scene::compile(csg::transformed(turn, r.model->root)), 1024);
    EXPECT_NEAR(ours / theirs, 1.0, 2e-5) << "csgray " << ours << ", OpenSCAD " << theirs;
    std::printf("%s%s: volume csgray %.9g, OpenSCAD %.9g (%+.2e)\n", file.c_str(), args.c_str(),
                ours, theirs, ours / theirs - 1);
}

TEST(SvgOpenScad, ExtrudedDrawingHasOpenScadsVolume) {
    if (!haveOpenScad()) SKIP_OR_FAIL_IN_CI("openscad (2021.01, Debian's) is not installed");
    csg::testing::TempDir dir("csgray_svg_openscad");
    writeFile(dir.path / "all.svg",
              svg("<rect x=\"10\" y=\"10\" width=\"20\" height=\"10\"/>\n"
                  "<circle cx=\"60\" cy=\"25\" r=\"10\"/>\n"
                  "<g transform=\"translate(70,5) rotate(30)\"><ellipse cx=\"5\" cy=\"5\" "
                  "rx=\"6\" ry=\"3\"/></g>\n"
                  "<path d=\"M 5 40 C 15 30 25 50 35 40 Z\"/>\n"
                  "<path d=\"M 40 45 L 90 45\" stroke-width=\"2\"/>\n"
                  "<path d=\"M 40 5 A 5 5 0 0 1 50 5 Z M 52 5 q 3 6 6 0 t 6 0 z\"/>\n"
                  "<rect x=\"80\" y=\"30\" width=\"15\" height=\"15\" rx=\"3\"/>\n"
                  "<polyline points=\"5,5 8,12 12,5\" stroke-linejoin=\"round\"/>\n"
                  "<g transform=\"skewX(20) scale(0.5)\"><polygon points=\"20,60 40,60 30,80\"/>"
                  "</g>",
                  "width=\"100mm\" height=\"50mm\" viewBox=\"0 0 200 100\""));
    expectOpenScadsVolume(dir.path, "all.svg", "");
    expectOpenScadsVolume(dir.path, "all.svg", ", center = true");
    // libsvg's own readings: the <svg> transform ignored; an open subpath after a Z filled, not
    // stroked; one before a moveto stroked, one whose ends are 0.05 apart filled; round and
    // bevel joins, round and butt caps; S and T after C and Q; a skewY; an arc's large flag;
    // relative subpaths after z (a hole, even-odd).
    writeFile(dir.path / "quirks.svg",
              svg("<path d=\"M0 0 L10 0 L10 10 Z M20 0 L30 0 L30 10\"/>\n"
                  "<path d=\"M40 0 L50 0 L50 10 M60 0 L70 0 L70 10 L60 0.05 M80 0 L 90 5\" "
                  "stroke-width=\"1.5\" stroke-linejoin=\"round\" stroke-linecap=\"round\"/>\n"
                  "<path d=\"M0 20 C 0 30 10 30 10 20 S 20 10 20 20 Q 25 30 30 20 T 40 20 Z\"/>\n"
                  "<g transform=\"skewY(10)\"><g transform=\"translate(50 30)\"><rect width=\"20\" "
                  "height=\"10\" rx=\"4\" ry=\"2\"/></g></g>\n"
                  "<polyline points=\"5,50 15,60 25,50 35,60\" stroke-width=\"3\" "
                  "stroke-linejoin=\"bevel\" stroke-linecap=\"butt\"/>\n"
                  "<path d=\"M50 60 a 10 5 30 1 0 20 0 z\"/>\n"
                  "<path d=\"M 70 80 h 10 v 10 h -10 z m 2 2 h 6 v 6 h -6 z\"/>",
                  "width=\"100\" height=\"100\" viewBox=\"0 0 100 100\" transform=\"scale(3)\""));
    expectOpenScadsVolume(dir.path, "quirks.svg", "");
    expectOpenScadsVolume(dir.path, "quirks.svg", ", dpi = 96");
}

}  // namespace
