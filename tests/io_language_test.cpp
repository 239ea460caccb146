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

// ---- $parent_modules and parent_module(n) (BOSL2's utility.scad) ----

TEST(IoLanguage, ParentModulesCountsTheUserModulesBeingInstantiated) {
    // a() b(): b runs as a's child, while a is still on the stack; c() a() b() adds c.
    // Built-in modules (translate, for) are not on the stack.
    Outcome r =
        run("module a() { echo(a = $parent_modules); children(); }\n"
            "module b() echo(b = $parent_modules, p0 = parent_module(0), p1 = parent_module(1));\n"
            "module c() a() b();\n"
            "a() b();\n"
            "c();\n"
            "translate([1, 0, 0]) for (i = [0]) a();\n");
    EXPECT_EQ(r.echoes, (Lines{"ECHO: a = 1", "ECHO: b = 2, p0 = \"b\", p1 = \"a\"", "ECHO: a = 2",
                               "ECHO: b = 3, p0 = \"b\", p1 = \"a\"", "ECHO: a = 1"}));
    EXPECT_TRUE(r.warnings.empty());
}

TEST(IoLanguage, ParentModuleDefaultsToOneAndTruncates) {
    // parent_module() is parent_module(1); 1.7 truncates to 1; a string is undef, silently.
    Outcome r =
        run("module inner() echo(parent_module(), parent_module(1.7), parent_module(0.2), "
            "parent_module(\"x\"));\n"
            "module outer() inner();\n"
            "outer();\n");
    EXPECT_EQ(r.echoes, Lines{"ECHO: \"outer\", \"outer\", \"inner\", undef"});
    EXPECT_TRUE(r.warnings.empty());
}

TEST(IoLanguage, ParentModuleSeesTheCalleeInItsArguments) {
    // A module is on the stack before its arguments are evaluated, defaults and passed ones.
    Outcome r =
        run("module a(x = parent_module(0)) echo(x);\n"
            "module b(y) echo(y);\n"
            "a();\n"
            "b(parent_module(0));\n");
    EXPECT_EQ(r.echoes, (Lines{"ECHO: \"a\"", "ECHO: \"b\""}));
    EXPECT_TRUE(r.warnings.empty());
}

TEST(IoLanguage, ParentModuleOutOfRangeWarnsAsOpenScadDoes) {
    // OpenSCAD's warnings, word for word; NaN and 1e10 become INT_MIN when 2021 converts them
    // to int on x86, so they are "negative". Functions do not push onto the stack.
    Outcome r =
        run("function f() = parent_module(1);\n"
            "module m() echo(parent_module(-1), parent_module(1), f(), parent_module(0/0),\n"
            "                parent_module(1e10), parent_module(0, 1));\n"
            "m();\n"
            "echo(parent_module(0));\n");
    EXPECT_EQ(r.echoes, (Lines{"ECHO: undef, undef, undef, undef, undef, undef", "ECHO: undef"}));
    // A call's diagnostics point at its '('.
    EXPECT_EQ(
        r.warnings,
        (Lines{"2:30 Negative parent module index (-1) not allowed",
               "2:49 Parent module index (1) greater than the number of modules on the stack",
               "1:29 Parent module index (1) greater than the number of modules on the stack",
               "2:72 Negative parent module index (-2147483648) not allowed",
               "3:30 Negative parent module index (-2147483648) not allowed",
               "3:51 parent_module() number of parameters does not match",
               "5:19 Parent module index (0) greater than the number of modules on the stack"}));
}

TEST(IoLanguage, ParentModulesIsUnknownAtTheTopLevel) {
    Outcome r = run("echo($parent_modules);");
    EXPECT_EQ(r.echoes, Lines{"ECHO: undef"});
    EXPECT_EQ(r.warnings.size(), 1u);
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

// ---- indexing a range (BOSL2's is_range and valid_range) ----

TEST(IoLanguage, RangeIndicesAreItsBeginStepAndEnd) {
    // [b:s:e][0] = b, [1] = s, [2] = e; any other index is undef. The deprecated [5:1] is
    // stored as [1:1:5]; indices truncate toward zero like a list's (-0.5 -> 0).
    Outcome r =
        run("r = [1:2:9]; echo(r[0], r[1], r[2], r[3], r[-1], r[1.9], r[-0.5]);\n"
            "echo([0:0.5:2][1], is_list([0:1]), [5:1][0]);");
    EXPECT_EQ(r.echoes, (Lines{"ECHO: 1, 2, 9, undef, undef, 2, 1", "ECHO: 0.5, false, 1"}));
    EXPECT_EQ(r.warnings.size(), 1u);  // the deprecated [5:1]
}

// ---- a function value prints as its source (BOSL2's fnliterals tests compare str(f)) ----

TEST(IoLanguage, FunctionValuesPrintAsOpenScadPrintsTheirExpressions) {
    // OpenSCAD 2021's print(): binary and ternary operations in parentheses, unary minus and
    // not without, unary plus dropped, numbers as echo shows them, strings quoted and escaped,
    // a call of anything but a name with its callee in parentheses, a comprehension's for (one
    // node a variable), if, each and a let over a comprehension wrapping what they govern.
    Outcome r =
        run("f1 = function(a, b = 2, c = [1, \"x\\\"y\", undef, true]) "
            "-a + !b * c.x - c[1] ^ 2 % 3 / 4;\n"
            "f2 = function() [for (i = [0:2:10], j = [1:3]) if (i > 1) i else j, each [1, 2], "
            "let(q = 1) q];\n"
            "f3 = function(x) let(y = x, z = 2) assert(y > 0, \"msg\") echo(\"hi\", v = y) "
            "y == z && x != 1 || x <= 0 >= 1;\n"
            "f4 = function(n) [for (i = 0, j = 1; i < n; i = i + 1, j = j * 2) j];\n"
            "f5 = function(g) g(1)(2) + f1(a = 3)[0] + (function(q) q)(4) + +g - -g;\n"
            "f6 = function(x) 1.23456789e10 + 1e-7 + 1000000 + [x:2] + [for (a = [1]) let(b = 2) "
            "for (c = [3]) c] + [each for (i = [1]) i];\n"
            "echo(f1); echo(f2); echo(f3); echo(f4); echo(f5); echo(f6);\n"
            "s = str(function(x) \"q\"); echo(len(s), s == \"function(x) \\\"q\\\"\");\n");
    EXPECT_EQ(
        r.echoes,
        (Lines{"ECHO: function(a, b = 2, c = [1, \"x\\\"y\", undef, true]) ((-a + (!b * c.x)) - "
               "(((c[1] ^ 2) % 3) / 4))",
               "ECHO: function() [for(i = [0 : 2 : 10]) (for(j = [1 : 3]) (if((i > 1)) (i) else "
               "(j))), each ([1, 2]), let(q = 1) q]",
               "ECHO: function(x) let(y = x, z = 2) assert((y > 0), \"msg\") echo(\"hi\", v = y) "
               "(((y == z) && (x != 1)) || ((x <= 0) >= 1))",
               "ECHO: function(n) [for(i = 0, j = 1;(i < n);i = (i + 1), j = (j * 2)) j]",
               "ECHO: function(g) (((((g(1))(2) + f1(a = 3)[0]) + (function(q) q)(4)) + g) - -g)",
               "ECHO: function(x) (((((1.23457e+10 + 1e-7) + 1e+6) + [x : 2]) + [for(a = [1]) "
               "(let(b = 2) (for(c = [3]) (c)))]) + [each (for(i = [1]) (i))])",
               "ECHO: 15, true"}));
}

// ---- inverse trigonometry snaps to whole degrees (BOSL2's f_acos and friends) ----

TEST(IoLanguage, InverseTrigonometryIsExactAtWholeDegrees) {
    // OpenSCAD 2021's degree_trig.cc: asin, acos and atan round to the nearest whole degree
    // when sin, cos or tan of it (exact at 30, 45, 60 and 90) give the argument back exactly;
    // atan2 when within 3e-14 of it. acos(-0.5) in radians times 180/pi is 120.00000000000001.
    // atan(1/sqrt(3)) stays off: 1/sqrt(3) is not tan(30)'s constant 0.57735026918962573.
    Outcome r =
        run("echo(acos(-0.5) == 120, acos(0.5) == 60, asin(0.5) == 30, asin(-0.5) == -30, "
            "atan(sqrt(3)) == 60, asin(sqrt(2) / 2) == 45, acos(sqrt(3) / 2) == 30, "
            "atan2(1, sqrt(3)) == 30, atan2(-1, -1) == -135, atan(1 / sqrt(3)) == 30);\n"
            "echo(acos(0.51) - 59.336170257614036, atan(1 / 0), atan2(0, -1), acos(2));");
    EXPECT_EQ(r.echoes, (Lines{"ECHO: true, true, true, true, true, true, true, true, true, false",
                               "ECHO: 0, 90, 180, nan"}));
}

// ---- each over a comprehension splices every value it yields (BOSL2's vnf_vertex_array) ----

TEST(IoLanguage, EachOverAComprehensionSplicesEachValueItYields) {
    // each for (...) v yields v's items, not v: [1, 1, 2, 2]. `each let(...) a` is each of a's
    // value (a let over a plain expression). each if (c) v splices v. A value that is not a
    // list, range or string is kept; undef adds nothing.
    Outcome r =
        run("echo([each for (i = [1:2]) [i, i]]);\n"
            "echo([for (i = [1:2]) each let(a = [i, i]) a]);\n"
            "echo([each let(b = 2) for (i = [1:2]) [i, b]], [each if (true) [1, [2]]]);\n"
            "echo([each for (i = [0:2]) i == 1 ? undef : i == 2 ? \"xy\" : [0:1]]);\n");
    EXPECT_EQ(r.echoes, (Lines{"ECHO: [1, 1, 2, 2]", "ECHO: [1, 1, 2, 2]",
                               "ECHO: [1, 2, 2, 2], [1, [2]]", "ECHO: [0, 1, \"x\", \"y\"]"}));
}

// ---- a C-style for's update is sequential (BOSL2's path_sweep: v1 = ..., c1 = v1 * v1) ----

TEST(IoLanguage, CStyleForUpdateAssignsInOrder) {
    // j = i sees the new i: [[0, 0], [1, 1], [2, 2]]. A name first assigned in the update
    // (k) is there for the condition and body of the next iterations.
    Outcome r =
        run("echo([for (i = 0, j = 0; i < 3; i = i + 1, j = i) [i, j]]);\n"
            "echo([for (i = 0; i < 2; k = i, i = k + 1) i]);\n");
    EXPECT_EQ(r.echoes, (Lines{"ECHO: [[0, 0], [1, 1], [2, 2]]", "ECHO: [0, 1]"}));
    EXPECT_TRUE(r.warnings.empty());
}

// ---- is_undef(name) and a range of non-numbers are silent (BOSL2's get_slop, is_range) ----

TEST(IoLanguage, IsUndefOfAnUnknownNameDoesNotWarn) {
    // is_undef looks a bare name up silently; any other argument is evaluated as usual.
    Outcome r = run("echo(is_undef($slop), is_undef(nothing), is_undef(nothing + 1));");
    EXPECT_EQ(r.echoes, Lines{"ECHO: true, true, true"});
    EXPECT_EQ(r.warnings.size(), 2u);  // `nothing` unknown, then undef + 1
    EXPECT_EQ(r.warnings.at(0), "1:51 ignoring unknown variable 'nothing'");
}

TEST(IoLanguage, ARangeOfNonNumbersIsUndefWithoutAWarning) {
    Outcome r = run("echo([\"a\":1:2], [1:undef], [3:4:\"a\"]);");
    EXPECT_EQ(r.echoes, Lines{"ECHO: undef, undef, undef"});
    EXPECT_TRUE(r.warnings.empty());
}

// ---- ranges compare as OpenSCAD 2021 compares them (BOSL2's typeof and is_nan) ----

TEST(IoLanguage, RangesAreEqualWhenTheyCountAlikeFromTheSameBeginAndStep) {
    // As many values, then the same begin and step; the end is not compared. Empty ranges are
    // all equal, a NaN one included, so BOSL2's is_nan(x) = x != x is false for [0:nan:inf].
    // A zero step or an infinite end counts without bound; an infinite step counts one.
    Outcome r =
        run("n = 0 / 0; i = 1 / 0;\n"
            "echo([0:2:4] == [0:2:5], [0:1:2.5] == [0:1:2], [0:1:-1] == [5:1:3], "
            "[0:n:1] == [2:1:1], [0:n:i] != [0:n:i]);\n"
            "echo([0:1:0] == [0:5:0], [0:1:2] == [0:1:3], [0:0:1] == [5:1:3], [0:i:5] == [0:i:7], "
            "[0:1:i] == [0:1:5]);\n");
    EXPECT_EQ(r.echoes, (Lines{"ECHO: true, true, true, true, false",
                               "ECHO: false, false, false, true, false"}));
}

// ---- sin, cos and tan are OpenSCAD 2021's, exact at 30, 45, 60 and 90 degrees ----

TEST(IoLanguage, TrigonometryIsOpenScadsDegreeTrigonometry) {
    // degree_trig.cc returns its constants at those angles: sin(45) is the double nearest
    // sqrt(1/2) (sin(pi / 4) is an ulp below it), tan(30) is sqrt(1/3)'s double (1 / sqrt(3)
    // is an ulp above it). BOSL2's glued_circles() counts arc segments from such values.
    Outcome r =
        run("echo(sin(45) == sqrt(0.5), cos(45) == sqrt(0.5), sin(60) == sqrt(3) / 2, "
            "tan(60) == sqrt(3), tan(30) == sqrt(1 / 3), tan(30) == 1 / sqrt(3), "
            "sin(-135) == -sqrt(0.5), tan(135), tan(-180), tan(90), tan(270));");
    EXPECT_EQ(r.echoes, Lines{"ECHO: true, true, true, true, true, false, true, -1, 0, inf, -inf"});
}

// ---- a parameter declared twice takes the argument given to either (BOSL2's masks) ----

TEST(IoLanguage, AParameterDeclaredTwiceTakesTheArgumentGivenToEither) {
    // OpenSCAD 2021 sets every default, in order, and then the arguments: with no argument
    // the last default wins; an argument, by name or by either position, wins over both.
    Outcome r =
        run("module m(a, r, b, r) echo(a = a, r = r, b = b);\n"
            "m(1, 2, 3, 4); m(r = 5); m(1, 2);\n"
            "function f(x, y = 2, x = 3) = [x, y];\n"
            "echo(f(), f(1), f(x = 7), f(1, 2, 4));\n");
    EXPECT_EQ(r.echoes,
              (Lines{"ECHO: a = 1, r = 4, b = 3", "ECHO: a = undef, r = 5, b = undef",
                     "ECHO: a = 1, r = 2, b = undef", "ECHO: [3, 2], [1, 2], [7, 2], [4, 2]"}));
}

// ---- $children is lexical (BOSL2's regular_polyhedron inside its own translate()) ----

TEST(IoLanguage, ChildrenCountIsTheWritingModulesNotTheInstantiatingOnes) {
    // A block of children sees the $children of the module it is written in: outer() has 0
    // (inner() has 1, the block) and user() 1 through two pass()es; a function sees none.
    // Other $-variables stay dynamic: $parent_modules in inner's children is inner's count.
    Outcome r =
        run("module inner() children();\n"
            "module outer() inner() echo(c = $children, p = $parent_modules);\n"
            "outer();\n"
            "module pass() children();\n"
            "module user() pass() pass() echo(u = $children);\n"
            "user() cube();\n"
            "function f() = $children;\n"
            "module m() echo(f = f());\n"
            "m() cube();\n");
    EXPECT_EQ(r.echoes, (Lines{"ECHO: c = 0, p = 2", "ECHO: u = 1", "ECHO: f = undef"}));
    EXPECT_EQ(r.warnings, Lines{"7:16 ignoring unknown variable '$children'"});
}
