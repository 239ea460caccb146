// Language features that the libraries OpenSCAD users include (BOSL2, MCAD) need, one test a
// feature. Expected values are derived by hand from OpenSCAD 2021.01's rules and agree with what
// Debian's openscad 2021.01 prints for the same source (its ECHO and WARNING lines).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <unistd.h>

#include "io/Evaluate.h"

using namespace io;

namespace {

struct Outcome {
    EvaluateResult result;
    std::vector<std::string> echoes;
    std::vector<std::string> warnings;  // "line:col message"
};

Outcome run(const std::string& source, const std::string& name = "test.scad") {
    Outcome r;
    EvaluateOptions options;
    options.echo = [&r](const std::string& line) { r.echoes.push_back(line); };
    r.result = evaluateString(source, name, options);
    for (const auto& d : r.result.diagnostics) {
        if (d.severity == Severity::Error) ADD_FAILURE() << formatDiagnostic(d);
        if (d.severity == Severity::Warning)
            r.warnings.push_back(std::to_string(d.line) + ":" + std::to_string(d.col) + " " +
                                 d.message);
    }
    return r;
}

using Lines = std::vector<std::string>;

}  // namespace

// ---- C-style for in a list comprehension with empty parts (BOSL2's linalg.scad) ----

TEST(IoLanguage, CStyleForWithoutInitializerLoopsOverAnOuterName) {
    // BOSL2's list_shape: the loop variable starts as the outer `list`; each update digs one
    // level: [[[1, 2]]] has lengths 1, 1, 2 and then 1 is not a list.
    Outcome r =
        run("function shape(list) = [for (; is_list(list) && len(list) > 0; list = list[0]) "
            "len(list)];\n"
            "echo(shape([[[1, 2]]]), shape([]), shape(5));");
    EXPECT_EQ(r.echoes, Lines{"ECHO: [1, 1, 2], [], []"});
    EXPECT_TRUE(r.warnings.empty());
}

TEST(IoLanguage, CStyleForWithEmptyInitializerAndUpdate) {
    // for (; false; ) never runs its body; for (i = 0; i < 0; ) neither (an empty update would
    // otherwise loop forever).
    Outcome r = run("echo([for (; false; ) 1], [for (i = 0; i < 0; ) i]);");
    EXPECT_EQ(r.echoes, Lines{"ECHO: [], []"});
}

TEST(IoLanguage, CStyleForNeedsItsCondition) {
    // for (;;) is a syntax error in OpenSCAD 2021: the condition is an expression, not optional.
    EvaluateOptions options;
    const EvaluateResult r = evaluateString("x = [for (;;) 1];", "test.scad", options);
    ASSERT_FALSE(r.ok());
    EXPECT_EQ(r.diagnostics.at(0).line, 1u);
    EXPECT_EQ(r.diagnostics.at(0).col, 12u);
}

// ---- use<> written in an included file (BOSL2's color.scad: use <builtins.scad>) ----

TEST(IoLanguage, UseInAnIncludedFileResolvesFromThatFile) {
    // main/part.scad includes ../lib/inc.scad, which uses <helper.scad>: the use is written in
    // lib/, so lib/helper.scad is meant, not main/helper.scad beside the including file.
    const auto root = std::filesystem::temp_directory_path() /
                      ("csgray_io_language_use_" + std::to_string(::getpid()));
    std::filesystem::remove_all(root);
    std::filesystem::create_directories(root / "main");
    std::filesystem::create_directories(root / "lib");
    std::ofstream(root / "lib/inc.scad") << "use <helper.scad>\n";
    std::ofstream(root / "lib/helper.scad") << "function helper() = \"lib\";\n";
    std::ofstream(root / "main/helper.scad") << "function helper() = \"main\";\n";
    Outcome r =
        run("include <../lib/inc.scad>\necho(helper());\n", (root / "main/part.scad").string());
    EXPECT_EQ(r.echoes, Lines{"ECHO: \"lib\""});
    std::filesystem::remove_all(root);
}
