// text() (io/TextModule.h, io/TextLayout.h). The oracles are independent of csgray's text code:
//   - the font file's own metrics, read here with FreeType unscaled (advance widths, glyph
//     boxes, units per em), turned into OpenSCAD 2021's placement by the formulas of
//     ../shared/OPENSCAD.md section 2 (1 em = size * 100/72; advances and alignment offsets
//     divided by 1.024e5 where outlines are divided by 1e5);
//   - OpenSCAD 2021 itself (`openscad` on the PATH, Debian's 2021.01): its binary STL of
//     linear_extrude(1) text(...), whose vertices and volume csgray's part must reproduce;
//   - straight-line crossings counted by hand for the probe rays, and the convergence of
//     OpenSCAD's chords to csgray's exact Beziers.
// Notation: t is the parameter of o + t d; the rays here have unit d, so t is a distance.
// "Hinting pixel": FreeType hints at 1e5/64 pt and 100 dpi, where one pixel is 64 outline
// units, 64e-5 * size after OpenSCAD's scaling (0.0064 at size 10): hinted heights may move by
// that much from the font's design.
#include <gtest/gtest.h>

#include <ft2build.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>
#include FT_FREETYPE_H
#include FT_OUTLINE_H

#include "csg/Scene.h"
#include "io/Evaluate.h"
#include "io/TextLayout.h"
#include "io/TextModule.h"
#include "tests/BinaryStl.h"
#include "tests/MissingTool.h"
#include "tests/PartHelpers.h"
#include "tests/TempDir.h"
#include "tests/TextFiles.h"

namespace {

using csg::testing::diagnosticsOf;
using csg::testing::evaluate;
using csg::testing::shellQuote;

using csg::Vec2;
using csg::Vec3;
using io::CurveMode;

// The file Debian's openscad 2021.01 opens for its default font, "Liberation Sans:style=Regular"
// (seen with strace: fonts-liberation2's, which fontconfig prefers to fonts-liberation's
// older 1.07 when both are installed).
const char* const kLiberationSans =
    "/usr/share/fonts/truetype/liberation2/LiberationSans-Regular.ttf";

// OpenSCAD 2021's scale: FreeType's char size 1e5/64 pt at 100 dpi gives an em of
// 1e5 * 100/72 outline units.
constexpr double kEmUnits = 1e5 * 100.0 / 72.0;

using csg::testing::haveOpenScad;

// ---- the font's own metrics, unscaled, through FreeType directly ----

struct GlyphMetrics {
    double advance = 0;  // font design units
    double yMin = 0, yMax = 0;
};

class FontMetrics {
public:
    explicit FontMetrics(const char* file) {
        if (FT_Init_FreeType(&library_) != 0) return;
        if (FT_New_Face(library_, file, 0, &face_) != 0) face_ = nullptr;
    }
    ~FontMetrics() {
        if (face_) FT_Done_Face(face_);
        if (library_) FT_Done_FreeType(library_);
    }
    bool ok() const { return face_ != nullptr; }
    double unitsPerEm() const { return face_->units_per_EM; }
    GlyphMetrics of(char c) const {
        FT_Load_Char(face_, FT_ULong(c), FT_LOAD_NO_SCALE);
        FT_BBox box;
        FT_Outline_Get_CBox(&face_->glyph->outline, &box);
        return {double(face_->glyph->advance.x), double(box.yMin), double(box.yMax)};
    }
    // Where OpenSCAD 2021 puts the next glyph after c at this size: the advance in outline
    // units (rounded to whole units by FreeType and HarfBuzz) divided by 1.024e5.
    double penAdvance(char c, double size) const {
        return of(c).advance / unitsPerEm() * kEmUnits / 1.024e5 * size;
    }
    // A height in the outline's own scale (divided by 1e5).
    double height(double designUnits, double size) const {
        return designUnits / unitsPerEm() * kEmUnits / 1e5 * size;
    }

private:
    FT_Library library_ = nullptr;
    FT_Face face_ = nullptr;
};

// ---- csgray's side ----

void collectLeaves(const csg::Node* node, std::vector<const csg::Extrusion*>& out) {
    if (!node) return;
    if (node->op == csg::Op::Leaf) {
        out.push_back(&std::get<csg::Extrusion>(node->primitive));
        return;
    }
    collectLeaves(node->left.get(), out);
    collectLeaves(node->right.get(), out);
}

// A 2-D text part's glyph leaves, in the tree's order (left to right for left-to-right text),
// with the tree that owns them.
struct Glyphs {
    csg::NodePtr root;
    std::vector<const csg::Extrusion*> leaves;
    size_t size() const { return leaves.size(); }
    const csg::Extrusion* operator[](size_t i) const { return leaves[i]; }
};

Glyphs glyphLeaves(const std::string& source, CurveMode curves = CurveMode::Auto) {
    const io::EvaluateResult r = evaluate(source, curves);
    EXPECT_TRUE(r.ok()) << source << "\n" << diagnosticsOf(r);
    Glyphs glyphs;
    if (!r.ok()) return glyphs;
    glyphs.root = r.model->root;
    collectLeaves(glyphs.root.get(), glyphs.leaves);
    return glyphs;
}

csg::Bounds2 boxOf(const Glyphs& glyphs) {
    csg::Bounds2 box;
    for (const csg::Extrusion* leaf : glyphs.leaves) {
        box.add(leaf->box.lo);
        box.add(leaf->box.hi);
    }
    return box;
}

// The inside length of the prism part's section z = 1/2 along the line x = const, by csgray's
// spans of a ray along y.
double insideLength(const csg::Scene& scene, double x, csg::QueryContext& ctx) {
    const csg::Bounds3 box = scene.bounds();
    double length = 0.0;
    for (const csg::Span& s : scene.spans({{x, box.lo.y - 1.0, 0.5}, {0.0, 1.0, 0.0}}, ctx))
        length += s.out.t - s.in.t;
    return length;
}

// The area of the section z = 1/2 of a prism part (linear_extrude(1) of a shape) from csgray's
// spans, integrated over x by the midpoint rule between consecutive breaks. With the x of
// every outline vertex among the breaks, a polygonal section's inside length is linear in x
// between them and the rule is exact. (csg::volume's square grid of rays along z samples the
// inside as points, which converges slowly on text's many curved edges: 0.27 % off at
// resolution 1024 for "csgray 2021".)
double sectionArea(const csg::Scene& scene, std::vector<double> breaks) {
    std::sort(breaks.begin(), breaks.end());
    breaks.erase(std::unique(breaks.begin(), breaks.end()), breaks.end());
    csg::QueryContext ctx;
    double area = 0.0;
    for (size_t i = 0; i + 1 < breaks.size(); ++i)
        area += (breaks[i + 1] - breaks[i]) *
                insideLength(scene, 0.5 * (breaks[i] + breaks[i + 1]), ctx);
    return area;
}

// n + 1 evenly spaced breaks across the part.
std::vector<double> evenBreaks(const csg::Scene& scene, int n) {
    const csg::Bounds3 box = scene.bounds();
    std::vector<double> breaks;
    for (int i = 0; i <= n; ++i) breaks.push_back(box.lo.x + (box.hi.x - box.lo.x) * i / n);
    return breaks;
}

// The x of every segment end of the part's outlines.
std::vector<double> vertexBreaks(const csg::NodePtr& root) {
    std::vector<const csg::Extrusion*> leaves;
    collectLeaves(root.get(), leaves);
    std::vector<double> breaks;
    for (const csg::Extrusion* leaf : leaves)
        for (const csg::Segment2& s : leaf->outline->segments) breaks.push_back(s.start().x);
    return breaks;
}

// ---- OpenSCAD's side: a binary STL ----

struct Stl {
    std::vector<Vec2> bottom;  // distinct vertices at z = 0
    Vec3 lo{csg::kInfinity}, hi{-csg::kInfinity};
    double volume = 0.0;  // divergence theorem
};

Stl readBinaryStl(const std::filesystem::path& path) {
    Stl stl;
    for (const auto& p : csg::testing::binaryStlTriangles(path)) {
        for (const Vec3& v : p) {
            stl.lo = glm::min(stl.lo, v);
            stl.hi = glm::max(stl.hi, v);
            if (v.z == 0.0) stl.bottom.push_back(Vec2(v));
        }
        stl.volume += glm::dot(p[0], glm::cross(p[1], p[2])) / 6.0;
    }
    std::sort(stl.bottom.begin(), stl.bottom.end(),
              [](Vec2 a, Vec2 b) { return a.x < b.x || (a.x == b.x && a.y < b.y); });
    stl.bottom.erase(std::unique(stl.bottom.begin(), stl.bottom.end()), stl.bottom.end());
    return stl;
}

// OpenSCAD's STL of linear_extrude(1) `shape`; empty when openscad fails.
Stl openScadPrism(const std::string& shape, const std::string& name) {
    csg::testing::TempDir dir("csgray_text_" + name);
    const auto scad = dir.path / "part.scad", stl = dir.path / "part.stl";
    std::ofstream(scad) << "linear_extrude(1) " << shape << ";\n";
    const std::string command = "openscad --export-format binstl -o " + shellQuote(stl.string()) +
                                " " + shellQuote(scad.string()) + " >/dev/null 2>&1";
    if (std::system(command.c_str()) != 0) return {};
    return readBinaryStl(stl);
}

// ---- (a) the default font and OpenSCAD 2021's placement, from the font's metrics ----

TEST(TextLayout, DefaultFontIsTheFileOpenScadOpens) {
    if (!std::filesystem::exists(kLiberationSans))
        SKIP_OR_FAIL_IN_CI(std::string(kLiberationSans) +
                           " is missing (scripts/install-deps.sh: fonts-liberation2)");
    io::TextParams params;
    params.text = "H";
    const io::TextLayout layout = io::layoutText(params);
    EXPECT_EQ(layout.fontFile, kLiberationSans);
    EXPECT_EQ(layout.fontFamily, "Liberation Sans");
    EXPECT_EQ(layout.fontStyle, "Regular");
    EXPECT_TRUE(layout.warnings.empty());
    ASSERT_EQ(layout.glyphs.size(), 1u);
    EXPECT_EQ(layout.glyphs[0].contours.size(), 1u);  // an H is one closed contour
}

// OPENSCAD.md: the H -> H advance at size 10 is 9.7928, 1/1.024 of the design's 10.0278. That
// was measured with a Helvetica-metric substitute (722/1000 em); Liberation Sans's H is
// 1479/2048 em, so its figures are 9.7950 against 10.0301.
TEST(TextLayout, AdvanceBetweenTwoHsIsOpenScad2021s) {
    const FontMetrics font(kLiberationSans);
    if (!font.ok()) SKIP_OR_FAIL_IN_CI(std::string(kLiberationSans) + " is missing");
    const auto leaves = glyphLeaves("text(\"HH\");");
    ASSERT_EQ(leaves.size(), 2u);
    const double advance = leaves[1]->box.lo.x - leaves[0]->box.lo.x;
    // Whole 26.6 units: 10 / 1.024e5 ~ 1e-4 at size 10.
    EXPECT_NEAR(advance, font.penAdvance('H', 10.0), 2e-4);
    EXPECT_NEAR(advance, 9.7928, 3e-3);
    const double designed = font.of('H').advance / font.unitsPerEm() * 10.0 * 100.0 / 72.0;
    EXPECT_NEAR(advance * 1.024, designed, 3e-4);  // the bug: 2.4 % short of the design
    // spacing multiplies the advance; size scales everything.
    const auto spaced = glyphLeaves("text(\"HH\", spacing = 2);");
    ASSERT_EQ(spaced.size(), 2u);
    EXPECT_NEAR(spaced[1]->box.lo.x - spaced[0]->box.lo.x, 2.0 * advance, 1e-12);
    const auto small = glyphLeaves("text(\"HH\", size = 5);");
    ASSERT_EQ(small.size(), 2u);
    EXPECT_NEAR(small[1]->box.lo.x - small[0]->box.lo.x, font.penAdvance('H', 5.0), 1e-4);
    // A space has no outline but advances the pen.
    const auto spaceH = glyphLeaves("text(\" H\");");
    const auto justH = glyphLeaves("text(\"H\");");
    ASSERT_EQ(spaceH.size(), 1u);
    ASSERT_EQ(justH.size(), 1u);
    EXPECT_NEAR(spaceH[0]->box.lo.x - justH[0]->box.lo.x, font.penAdvance(' ', 10.0), 2e-4);
}

// An H stands on the baseline and is as tall as its design (cap height ~0.69 em, 0.955 size),
// to a hinting pixel; a negative size mirrors the text through the origin, as OpenSCAD's
// size * (v + offset + advance) does.
TEST(TextLayout, GlyphHeightsAreTheFontsOwn) {
    const FontMetrics font(kLiberationSans);
    if (!font.ok()) SKIP_OR_FAIL_IN_CI(std::string(kLiberationSans) + " is missing");
    const double pixel = 64e-5 * 10.0;
    const auto h = glyphLeaves("text(\"H\");");
    ASSERT_EQ(h.size(), 1u);
    EXPECT_EQ(h[0]->box.lo.y, 0.0);
    EXPECT_NEAR(h[0]->box.hi.y, font.height(font.of('H').yMax, 10.0), pixel);
    EXPECT_NEAR(h[0]->box.hi.y / 10.0, 0.955, 1e-3);
    const auto g = glyphLeaves("text(\"g\");");
    ASSERT_EQ(g.size(), 1u);
    // A quadratic's control points bound it; the descender's lowest point is an on-curve
    // point of the font, so the box reaches it exactly there.
    EXPECT_NEAR(g[0]->box.lo.y, font.height(font.of('g').yMin, 10.0), pixel);
    const auto mirrored = glyphLeaves("text(\"H\", size = -10);");
    ASSERT_EQ(mirrored.size(), 1u);
    EXPECT_EQ(mirrored[0]->box.lo.x, -h[0]->box.hi.x);
    EXPECT_EQ(mirrored[0]->box.hi.y, -h[0]->box.lo.y);
    EXPECT_EQ(mirrored[0]->box.lo.y, -h[0]->box.hi.y);
}

// halign moves the text by the sum of advances W (not the ink), valign by the grid-fitted
// ascent A or descent D, all in OpenSCAD 2021's 1/1.024e5 scale: so valign = "top" leaves an
// H 0.22 above y = 0 at size 10, not touching it.
TEST(TextLayout, AlignmentOffsetsAreOpenScad2021s) {
    const FontMetrics font(kLiberationSans);
    if (!font.ok()) SKIP_OR_FAIL_IN_CI(std::string(kLiberationSans) + " is missing");
    const double size = 10.0;
    const double width = font.penAdvance('H', size) + font.penAdvance('g', size);
    // Grid-fitted (to 64 units) ascent of the H and descent of the g, in units of 1/1.024e5:
    // within a pixel of the design.
    const double ascent = std::ceil(font.of('H').yMax / font.unitsPerEm() * kEmUnits / 64) * 64;
    const double descent = std::ceil(-font.of('g').yMin / font.unitsPerEm() * kEmUnits / 64) * 64;
    const double pixel = 64e-5 * size / 1.024;
    const csg::Bounds2 left = boxOf(glyphLeaves("text(\"Hg\");"));
    struct Case {
        const char* args;
        Vec2 shift;
    };
    const Case cases[] = {
        {"halign = \"center\"", {-width / 2, 0.0}},
        {"halign = \"right\"", {-width, 0.0}},
        {"valign = \"top\"", {0.0, -ascent / 1.024e5 * size}},
        {"valign = \"bottom\"", {0.0, descent / 1.024e5 * size}},
        {"valign = \"center\"", {0.0, (descent - ascent) / 2 / 1.024e5 * size}},
        {"halign = \"right\", valign = \"top\"", {-width, -ascent / 1.024e5 * size}},
    };
    for (const Case& c : cases) {
        const csg::Bounds2 box = boxOf(glyphLeaves(std::string("text(\"Hg\", ") + c.args + ");"));
        EXPECT_NEAR(box.lo.x - left.lo.x, c.shift.x, 4e-4) << c.args;
        EXPECT_NEAR(box.hi.x - left.hi.x, c.shift.x, 4e-4) << c.args;
        EXPECT_NEAR(box.lo.y - left.lo.y, c.shift.y, 2 * pixel) << c.args;
        EXPECT_NEAR(box.hi.y - left.hi.y, c.shift.y, 2 * pixel) << c.args;
    }
    const csg::Bounds2 top = boxOf(glyphLeaves("text(\"Hg\", valign = \"top\");"));
    EXPECT_GT(top.hi.y, 0.2);  // the 1.024 bug: the H pokes out above the line
    EXPECT_LT(top.hi.y, 0.25);
}

// ---- (b) geometry: exact Beziers, OpenSCAD's chords, the non-zero union ----

TEST(TextGeometry, ChordCountsAreOpenScads) {
    // max(floor(fragments / 8) + 1, 2): size 10 gives 30 fragments, so 4 chords; $fn = 8: 2.
    EXPECT_EQ(io::textChordCount(30), 4);
    EXPECT_EQ(io::textChordCount(8), 2);
    EXPECT_EQ(io::textChordCount(3), 2);
    EXPECT_EQ(io::textChordCount(5), 2);
    EXPECT_EQ(io::textChordCount(16), 3);
    EXPECT_EQ(io::textChordCount(100), 13);
}

// Liberation Sans's O is two contours of TrueType quadratics. Exact (the default without $fn):
// the quadratics themselves, non-zero rule; faceted: only lines, k per quadratic.
TEST(TextGeometry, CurvesAreExactBeziersOrOpenScadsChords) {
    using Kind = csg::Segment2::Kind;
    auto kinds = [](const csg::Extrusion& leaf, Kind kind) {
        return std::count_if(leaf.outline->segments.begin(), leaf.outline->segments.end(),
                             [&](const csg::Segment2& s) { return s.kind == kind; });
    };
    const auto exact = glyphLeaves("text(\"O\");");
    ASSERT_EQ(exact.size(), 1u);
    EXPECT_EQ(exact[0]->outline->rule, csg::FillRule::NonZero);
    EXPECT_STREQ(exact[0]->shape, "text");
    const auto quadratics = kinds(*exact[0], Kind::Quadratic);
    EXPECT_GT(quadratics, 8);
    EXPECT_EQ(kinds(*exact[0], Kind::Cubic), 0);
    EXPECT_EQ(kinds(*exact[0], Kind::Arc), 0);
    const auto lines = kinds(*exact[0], Kind::Line);
    // Two contours, each closed: a segment starts where the one before it ends, bit for bit,
    // except at a contour's start, where the one before ends the previous contour at its start.
    const auto& segments = exact[0]->outline->segments;
    std::vector<size_t> starts;
    for (size_t i = 0; i < segments.size(); ++i)
        if (i == 0 || segments[i].start() != segments[i - 1].finish()) starts.push_back(i);
    ASSERT_EQ(starts.size(), 2u);
    starts.push_back(segments.size());
    for (size_t k = 0; k + 1 < starts.size(); ++k)
        EXPECT_EQ(segments[starts[k + 1] - 1].finish(), segments[starts[k]].start());
    struct Case {
        const char* source;
        CurveMode curves;
        int chords;
    };
    for (const Case& c : {Case{"text(\"O\", $fn = 8);", CurveMode::Auto, 2},
                          Case{"text(\"O\");", CurveMode::OpenScad, 4},
                          Case{"text(\"O\", $fa = 3, $fs = 0.5);", CurveMode::OpenScad, 16},
                          Case{"text(\"O\", $fn = 100);", CurveMode::Auto, 13}}) {
        const auto faceted = glyphLeaves(c.source, c.curves);
        ASSERT_EQ(faceted.size(), 1u);
        EXPECT_EQ(kinds(*faceted[0], Kind::Quadratic), 0) << c.source;
        EXPECT_EQ(kinds(*faceted[0], Kind::Line), lines + c.chords * quadratics) << c.source;
    }
    // --curves exact ignores $fn.
    const auto ignored = glyphLeaves("text(\"O\", $fn = 8);", CurveMode::Exact);
    ASSERT_EQ(ignored.size(), 1u);
    EXPECT_EQ(kinds(*ignored[0], Kind::Quadratic), quadratics);
}

// A probe ray through linear_extrude(1) text("O") at the O's mid-height meets the ring twice
// (the non-zero rule keeps the counter empty); along z through the ring, one span [0, 1];
// through the counter, none.
TEST(TextGeometry, ProbeThroughAnOMeetsItTwice) {
    for (CurveMode curves : {CurveMode::Auto, CurveMode::OpenScad}) {
        const io::EvaluateResult r = evaluate("linear_extrude(1) text(\"O\");", curves);
        ASSERT_TRUE(r.ok()) << diagnosticsOf(r);
        const csg::Scene scene = csg::Scene::compile(r.model->root);
        const csg::Bounds3 box = scene.bounds();
        const double midY = 0.5 * (box.lo.y + box.hi.y), midX = 0.5 * (box.lo.x + box.hi.x);
        csg::QueryContext ctx;
        const auto across = scene.spans({{box.lo.x - 5.0, midY, 0.5}, {1, 0, 0}}, ctx);
        ASSERT_EQ(across.size(), 2u);
        const double left = across[0].out.t - across[0].in.t;
        const double right = across[1].out.t - across[1].in.t;
        EXPECT_NEAR(left, right, 0.1);  // the O's strokes are about equally thick
        EXPECT_GT(left, 0.8);
        EXPECT_LT(left, 2.0);
        const double ringX = box.lo.x + 0.5 * left;
        const auto down = scene.spans({{ringX, midY, -1.0}, {0, 0, 1}}, ctx);
        ASSERT_EQ(down.size(), 1u);
        EXPECT_NEAR(down[0].in.t, 1.0, 1e-12);
        EXPECT_NEAR(down[0].out.t, 2.0, 1e-12);
        EXPECT_TRUE(scene.spans({{midX, midY, -1.0}, {0, 0, 1}}, ctx).empty());
    }
}

// OpenSCAD's chords converge to csgray's exact Beziers (the area error of k chords on a
// curve goes as 1/k^2), and the default faceting is visibly coarser.
TEST(TextGeometry, ExactBeziersAreTheLimitOfOpenScadsChords) {
    auto area = [](const std::string& source) {
        const io::EvaluateResult r = evaluate("linear_extrude(1) " + source);
        EXPECT_TRUE(r.ok()) << diagnosticsOf(r);
        if (!r.ok()) return 0.0;
        const csg::Scene scene = csg::Scene::compile(r.model->root);
        return sectionArea(scene, evenBreaks(scene, 20000));
    };
    const double exact = area("text(\"Qo\");");
    const double fine = area("text(\"Qo\", $fn = 8000);");  // 1001 chords per curve
    const double coarse = area("text(\"Qo\", $fn = 30);");  // OpenSCAD's default 4
    EXPECT_NEAR(fine / exact, 1.0, 1e-5);
    EXPECT_GT(std::abs(coarse / exact - 1.0), 1e-3);
    EXPECT_LT(coarse, exact);  // chords cut the convex bulges
}

// ---- (c) the language: empty text, arguments, messages ----

TEST(TextModule, EmptyOrSpacesIsTheEmptyShape) {
    for (const char* source :
         {"text(\"\");", "text(\"   \");", "text();", "linear_extrude(1) text(\" \");"}) {
        const io::EvaluateResult r = evaluate(source);
        ASSERT_TRUE(r.ok()) << source << "\n" << diagnosticsOf(r);
        EXPECT_EQ(r.model->root, nullptr) << source;
        EXPECT_TRUE(r.diagnostics.empty()) << diagnosticsOf(r);
    }
    // The empty shape takes nothing away.
    const io::EvaluateResult r = evaluate("difference() { square(10); text(\"\"); }");
    ASSERT_TRUE(r.ok()) << diagnosticsOf(r);
    ASSERT_NE(r.model->root, nullptr);
}

TEST(TextModule, BadArgumentsAreErrorsAtTheArgument) {
    struct Case {
        const char* source;
        const char* expected;
    };
    for (const Case& c : {
             Case{"text(42);", "part.scad:1:6: error: text(): 'text' must be a string, got 42"},
             Case{"text(\"a\", size = \"big\");",
                  "part.scad:1:11: error: text(): 'size' must be a finite number"},
             Case{"text(\"a\", spacing = [1]);",
                  "part.scad:1:11: error: text(): 'spacing' must be a finite number"},
             Case{"text(\"a\", font = 3);",
                  "part.scad:1:11: error: text(): 'font' must be a string"},
             Case{"text(\"a\", 10, \"Liberation Sans\", \"ltr\");",
                  "part.scad:1:34: error: too many unnamed arguments to text(): only text, size "
                  "and font may be given by position"},
         }) {
        const io::EvaluateResult r = evaluate(c.source);
        EXPECT_FALSE(r.ok()) << c.source;
        EXPECT_NE(diagnosticsOf(r).find(c.expected), std::string::npos) << c.source << "\n"
                                                                        << diagnosticsOf(r);
    }
}

// OpenSCAD's messages for an unknown alignment (it goes on, aligning left / on the baseline);
// an unknown font is silently replaced by fontconfig's choice, as OpenSCAD does.
TEST(TextModule, OpenScadsWarningsAndFontSubstitution) {
    const io::EvaluateResult r = evaluate("text(\"H\", halign = \"middle\", valign = \"mid\");");
    ASSERT_TRUE(r.ok()) << diagnosticsOf(r);
    const std::string all = diagnosticsOf(r);
    EXPECT_NE(all.find("part.scad:1:11: warning: Unknown value for the halign parameter (use "
                       "\"left\", \"right\" or \"center\"): 'middle'"),
              std::string::npos)
        << all;
    EXPECT_NE(all.find("part.scad:1:30: warning: Unknown value for the valign parameter (use "
                       "\"baseline\", \"bottom\", \"top\" or \"center\"): 'mid'"),
              std::string::npos)
        << all;
    EXPECT_EQ(boxOf(glyphLeaves("text(\"H\", halign = \"middle\");")).lo.x,
              boxOf(glyphLeaves("text(\"H\");")).lo.x);

    io::TextParams params;
    params.text = "H";
    params.font = "No Such Font csgray";
    const io::TextLayout layout = io::layoutText(params);
    EXPECT_TRUE(layout.warnings.empty());
    EXPECT_FALSE(layout.fontFile.empty());
    ASSERT_EQ(layout.glyphs.size(), 1u);
    const io::EvaluateResult quiet = evaluate("text(\"H\", font = \"No Such Font csgray\");");
    ASSERT_TRUE(quiet.ok());
    EXPECT_TRUE(quiet.diagnostics.empty()) << diagnosticsOf(quiet);
}

// A huge $fn is refused before any chord is made, with the reason.
TEST(TextModule, TooManyChordsIsAnErrorNotAnAllocation) {
    const io::EvaluateResult r = evaluate("text(\"O\", $fn = 1e9);");
    EXPECT_FALSE(r.ok());
    EXPECT_NE(diagnosticsOf(r).find("text(): $fn = 1e+9 gives 1000000000 fragments, so "
                                    "125000001 chords per curve"),
              std::string::npos)
        << diagnosticsOf(r);
}

// The font libraries are shared: layouts on several threads at once agree with one alone.
TEST(TextLayout, ConcurrentLayoutsAgree) {
    io::TextParams params;
    params.text = "Concurrency 123";
    const io::TextLayout alone = io::layoutText(params);
    std::vector<io::TextLayout> results(4);
    std::vector<std::thread> threads;
    for (auto& result : results)
        threads.emplace_back([&result, &params] { result = io::layoutText(params); });
    for (auto& t : threads) t.join();
    for (const io::TextLayout& result : results) {
        ASSERT_EQ(result.glyphs.size(), alone.glyphs.size());
        for (size_t i = 0; i < alone.glyphs.size(); ++i) {
            EXPECT_EQ(result.glyphs[i].advance, alone.glyphs[i].advance);
            EXPECT_EQ(result.glyphs[i].contours.size(), alone.glyphs[i].contours.size());
        }
    }
}

// ---- (d) OpenSCAD 2021 itself ----

// The end-to-end figure: linear_extrude(1) text("csgray 2021") under --curves openscad has
// OpenSCAD's bounding box (to 1e-4: OpenSCAD snaps to 2^-16 ~ 1.5e-5 and writes floats) and
// its volume (to 1e-3 relative, as asked; the two differ by OpenSCAD's snapping only).
TEST(TextAgainstOpenScad, CsgrayTwentyTwentyOneBoxAndVolume) {
    if (!haveOpenScad()) SKIP_OR_FAIL_IN_CI("openscad is not installed");
    const std::string shape = "text(\"csgray 2021\")";
    const Stl theirs = openScadPrism(shape, "csgray2021");
    ASSERT_FALSE(theirs.bottom.empty()) << "OpenSCAD's export";
    const io::EvaluateResult r = evaluate("linear_extrude(1) " + shape + ";", CurveMode::OpenScad);
    ASSERT_TRUE(r.ok()) << diagnosticsOf(r);
    const csg::Scene scene = csg::Scene::compile(r.model->root);
    const csg::Bounds3 box = scene.bounds();
    for (int a = 0; a < 3; ++a) {
        EXPECT_NEAR(box.lo[a], theirs.lo[a], 1e-4) << "axis " << a;
        EXPECT_NEAR(box.hi[a], theirs.hi[a], 1e-4) << "axis " << a;
    }
    const double ours = sectionArea(scene, vertexBreaks(r.model->root)) * (box.hi.z - box.lo.z);
    EXPECT_NEAR(ours / theirs.volume, 1.0, 1e-3);
    std::printf("csgray 2021: OpenSCAD's volume %.9g, csgray's %.9g (relative %.2g)\n",
                theirs.volume, ours, ours / theirs.volume - 1.0);
}

struct OpenScadCase {
    const char* name;
    const char* shape;
};

class TextMatchesOpenScad : public ::testing::TestWithParam<OpenScadCase> {};

// Every vertex of OpenSCAD's outline (the z = 0 face of its STL) is a vertex csgray placed, to
// OpenSCAD's snapping (Clipper's 2^-16 grid; the float STL adds 4e-6 at 70), and the areas
// agree to 2e-5 relative (csgray's by its spans, OpenSCAD's is the STL's volume, both moved
// by the snapping; where glyphs overlap OpenSCAD's union adds crossing vertices, so only the
// area is compared there).
TEST_P(TextMatchesOpenScad, VerticesAndArea) {
    if (!haveOpenScad()) SKIP_OR_FAIL_IN_CI("openscad is not installed");
    const OpenScadCase& c = GetParam();
    const Stl theirs = openScadPrism(c.shape, c.name);
    ASSERT_FALSE(theirs.bottom.empty()) << "OpenSCAD's export of " << c.shape;
    const io::EvaluateResult r =
        evaluate(std::string("linear_extrude(1) ") + c.shape + ";", CurveMode::OpenScad);
    ASSERT_TRUE(r.ok()) << diagnosticsOf(r);
    std::vector<const csg::Extrusion*> leaves;
    collectLeaves(r.model->root.get(), leaves);
    std::vector<Vec2> ours;
    for (const csg::Extrusion* leaf : leaves)
        for (const csg::Segment2& s : leaf->outline->segments) ours.push_back(s.start());
    const bool overlapping = std::strstr(c.name, "overlap") != nullptr;
    if (!overlapping) {
        double worst = 0.0;
        for (Vec2 t : theirs.bottom) {
            double nearest = csg::kInfinity;
            for (Vec2 o : ours)
                nearest = std::min(nearest, std::max(std::abs(o.x - t.x), std::abs(o.y - t.y)));
            worst = std::max(worst, nearest);
        }
        EXPECT_LE(worst, 0x1p-16 + 1e-5) << c.shape;
    }
    // Where glyphs overlap, the section's inside length also bends where their outlines cross:
    // even breaks bound that error.
    const csg::Scene scene = csg::Scene::compile(r.model->root);
    std::vector<double> breaks = vertexBreaks(r.model->root);
    if (overlapping) {
        const std::vector<double> even = evenBreaks(scene, 20000);
        breaks.insert(breaks.end(), even.begin(), even.end());
    }
    const double area = sectionArea(scene, breaks);
    EXPECT_NEAR(area / theirs.volume, 1.0, 2e-5) << c.shape;
}

INSTANTIATE_TEST_SUITE_P(
    Cases, TextMatchesOpenScad,
    ::testing::Values(
        OpenScadCase{"kerning", "text(\"AVATAR To Wa\", size = 7)"},
        OpenScadCase{"halign_center", "text(\"Hg\", halign = \"center\")"},
        OpenScadCase{"halign_right_valign_top",
                     "text(\"Hg\", halign = \"right\", valign = \"top\")"},
        OpenScadCase{"valign_center", "text(\"Hg\", valign = \"center\")"},
        OpenScadCase{"valign_bottom", "text(\"Hg\", valign = \"bottom\")"},
        OpenScadCase{"spacing", "text(\"Hg\", spacing = 2)"},
        OpenScadCase{"negative_size", "text(\"Hello\", size = -10)"},
        OpenScadCase{"accents",
                     "text(\"\u00c4\u00d6\u00dc \u00e4\u00f6\u00fc \u00df \u20ac\", size = 5)"},
        OpenScadCase{"fn8", "text(\"Qq@&\", $fn = 8)"},
        OpenScadCase{"fs", "text(\"O\", size = 3, $fs = 0.1)"},
        OpenScadCase{"rtl", "text(\"abc\", direction = \"rtl\")"},
        OpenScadCase{"ttb", "text(\"abc\", direction = \"ttb\")"},
        OpenScadCase{
            "btt_centered",
            "text(\"abc\", direction = \"btt\", halign = \"center\", valign = \"center\")"},
        OpenScadCase{"hebrew", "text(\"\u05e9\u05dc\u05d5\u05dd\")"},
        OpenScadCase{"arabic", "text(\"\u0645\u0631\u062d\u0628\u0627\")"},
        OpenScadCase{"serif_bold", "text(\"Hi\", font = \"Liberation Serif:style=Bold\")"},
        OpenScadCase{"unknown_font", "text(\"Hi\", font = \"No Such Font csgray\")"},
        OpenScadCase{"overlap_italic",
                     "text(\"fi ffl\", font = \"Liberation Serif:style=Bold Italic\")"},
        OpenScadCase{"overlap_spacing", "text(\"Wave\", spacing = 0.5, halign = \"center\")"}),
    [](const ::testing::TestParamInfo<OpenScadCase>& p) { return std::string(p.param.name); });

}  // namespace
