// bezier_patch() and bezier_patches() in the part language: the arguments reach the primitive,
// every bad argument is an error at its file:line:col, and a surface used as an operand of a
// difference or intersection is a compile error at the patch's statement.
#include <gtest/gtest.h>

#include "csg/Scene.h"
#include "io/Evaluate.h"

using namespace io;

namespace {

// A flat unit square in z = 0 written as a bicubic net (x = i / 3, y = j / 3).
std::string squarePoints() {
    std::string s = "[";
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j)
            s += "[" + std::to_string(i / 3.0) + ", " + std::to_string(j / 3.0) + ", 0]" +
                 (i == 3 && j == 3 ? "]" : ", ");
    return s;
}

std::string indices(int first) {
    std::string s = "[";
    for (int k = 0; k < 16; ++k) s += std::to_string(first + k) + (k == 15 ? "]" : ", ");
    return s;
}

// The first error, formatted as the command line prints it (evaluation, then compilation).
std::string error(const std::string& source) {
    EvaluateResult r = evaluateString(source, "test.scad");
    for (const auto& d : r.diagnostics)
        if (d.severity == Severity::Error) return formatDiagnostic(d);
    if (!r.ok()) return "<failed without an error>";
    try {
        csg::Scene::compile(r.model->root);
    } catch (const csg::CompileError& e) {
        return formatDiagnostic(diagnosticAt(*r.model, e.source, Severity::Error, e.what()));
    }
    return "<no error>";
}

const csg::PatchSet* patchSetOf(const EvaluateResult& r) {
    if (!r.ok() || !r.model->root) return nullptr;
    return std::get_if<csg::PatchSet>(&r.model->root->primitive);
}

TEST(IoPatch, ArgumentsReachThePrimitive) {
    EvaluateResult r = evaluateString(
        "bezier_patch(points = " + squarePoints() + ", method = \"newton\");", "test.scad");
    const csg::PatchSet* set = patchSetOf(r);
    ASSERT_NE(set, nullptr);
    EXPECT_EQ(set->method, csg::PatchMethod::Newton);
    EXPECT_FALSE(set->solid);
    ASSERT_EQ(set->data->patches.size(), 1u);
    EXPECT_EQ(set->data->patches[0].at(3, 3), csg::Vec3(1, 1, 0));

    // Two patches sharing points; the default method is clip.
    EvaluateResult two = evaluateString("p = " + squarePoints() +
                                            "; bezier_patches(points = concat(p, [for (q = p) q + "
                                            "[1, 0, 0]]), patches = [" +
                                            indices(0) + ", " + indices(16) + "]);",
                                        "test.scad");
    const csg::PatchSet* set2 = patchSetOf(two);
    ASSERT_NE(set2, nullptr) << (two.diagnostics.empty() ? ""
                                                         : formatDiagnostic(two.diagnostics[0]));
    EXPECT_EQ(set2->method, csg::PatchMethod::Clip);
    ASSERT_EQ(set2->data->patches.size(), 2u);
    EXPECT_EQ(set2->data->patches[1].at(3, 3), csg::Vec3(2, 1, 0));
}

TEST(IoPatch, BadArgumentsAreErrorsAtTheirLocation) {
    const std::string p = squarePoints();
    EXPECT_EQ(error("bezier_patch(points = [[0, 0, 0]]);"),
              "test.scad:1:14: error: bezier_patch(): 'points' must be a list of 16 points [x, "
              "y, z], got [[0, 0, 0]]; expected bezier_patch(points = [16 points [x, y, z]], "
              "method = \"clip\", solid = false)")
        << "(the message's exact form is checked once)";
    EXPECT_NE(error("bezier_patch();").find("test.scad:1:1: error: bezier_patch() needs 'points'"),
              std::string::npos);
    EXPECT_NE(error("x = 1;\nbezier_patch(" + p + ", method = \"kajiya\");").find("test.scad:2:"),
              std::string::npos);
    EXPECT_NE(error("bezier_patch(" + p + ", method = \"kajiya\");")
                  .find("unknown method \"kajiya\"; expected one of \"groebner\", "
                        "\"resultant\", \"clip\", \"newton\""),
              std::string::npos);
    EXPECT_NE(error("bezier_patch(" + p + ", solid = 1);").find("'solid' must be true or false"),
              std::string::npos);
    EXPECT_NE(error("bezier_patch([for (i = [0:15]) [i, 0, 1/0]]);")
                  .find("of finite numbers (entry 0 is not)"),
              std::string::npos);
    // bezier_patches: a short patch, an index out of range, a fractional index.
    EXPECT_NE(
        error("bezier_patches(" + p + ", [[0, 1, 2]]);").find("test.scad:1:") != std::string::npos,
        false);
    EXPECT_NE(error("bezier_patches(" + p + ", [[0, 1, 2]]);").find("(patch 0 has 3)"),
              std::string::npos);
    const std::string outOfRange = error("bezier_patches(points = " + p + ",\n    patches = [" +
                                         indices(0) + ", " + indices(1) + "]);");
    EXPECT_NE(outOfRange.find("test.scad:2:5: error: bezier_patches(): 'patches' must be lists "
                              "of whole indices in [0, 15] (patch 1, entry 15 is 16)"),
              std::string::npos)
        << outOfRange;
    EXPECT_NE(error("bezier_patches(" + p +
                    ", [[0.5, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, "
                    "13, 14, 15]]);")
                  .find("entry 0 is 0.5"),
              std::string::npos);
    // solid=true on an open set: nothing enclosed.
    EXPECT_NE(error("bezier_patch(" + p + ", solid = true);").find("enclose no volume"),
              std::string::npos);
}

TEST(IoPatch, ASurfaceInABooleanIsAnErrorAtItsLine) {
    const std::string p = squarePoints();
    EXPECT_NE(error("difference() {\n  cube(2);\n  bezier_patch(" + p + ");\n}")
                  .find("test.scad:3:3: error: a surface (solid=false) cannot be an operand of "
                        "difference"),
              std::string::npos);
    // Inside a module, under an intersection: still the patch's own line.
    EXPECT_NE(error("module m() { union() { sphere(1);\n   bezier_patch(" + p +
                    "); } }\nintersection() { m(); cube(1); }")
                  .find("test.scad:2:4: error: a surface (solid=false) cannot be an operand of "
                        "intersection"),
              std::string::npos);
    // A plain (implicit or explicit) union with solids at the top level is fine.
    EXPECT_EQ(error("union() { cube(1); bezier_patch(" + p + "); }\nsphere(1);"), "<no error>");
    EXPECT_EQ(error("module m() { bezier_patch(" + p + "); cube(1); }\nm();"), "<no error>");
}

}  // namespace
