// The grammar: precedence, vectors, ranges, comprehensions, statements, modifiers, includes,
// nesting limits, and syntax errors with their positions.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "io/Parser.h"

using namespace io;

namespace {

struct Parsed {
    SourceFiles sources;
    std::vector<Diagnostic> diagnostics;
    std::unique_ptr<ParsedFile> file;
};

std::unique_ptr<Parsed> parse(std::string text, std::filesystem::path path = "test.scad") {
    auto p = std::make_unique<Parsed>();
    const uint32_t index = p->sources.add(path.string(), path, std::move(text));
    p->file = parseFile(p->sources, index, p->diagnostics);
    return p;
}

// Renders an expression fully parenthesized, to check the tree's shape.
std::string show(const Expr& e) {
    switch (e.kind) {
        case ExprKind::Number: {
            std::string s = std::to_string(static_cast<const NumberExpr&>(e).value);
            return s.substr(0, s.find('.'));
        }
        case ExprKind::Identifier:
            return static_cast<const IdentifierExpr&>(e).name;
        case ExprKind::Unary: {
            const auto& u = static_cast<const UnaryExpr&>(e);
            return std::string("(") +
                   (u.op == UnaryOp::Negate ? "-"
                    : u.op == UnaryOp::Not  ? "!"
                                            : "+") +
                   show(*u.operand) + ")";
        }
        case ExprKind::Binary: {
            const auto& b = static_cast<const BinaryExpr&>(e);
            static const char* ops[] = {"+",  "-", "*",  "/",  "%",  "^",  "<",
                                        "<=", ">", ">=", "==", "!=", "&&", "||"};
            return "(" + show(*b.left) + ops[static_cast<int>(b.op)] + show(*b.right) + ")";
        }
        case ExprKind::Ternary: {
            const auto& t = static_cast<const TernaryExpr&>(e);
            return "(" + show(*t.condition) + "?" + show(*t.ifTrue) + ":" + show(*t.ifFalse) + ")";
        }
        case ExprKind::Call:
            return show(*static_cast<const CallExpr&>(e).callee) + "()";
        case ExprKind::Index: {
            const auto& i = static_cast<const IndexExpr&>(e);
            return show(*i.object) + "[" + show(*i.index) + "]";
        }
        case ExprKind::Member: {
            const auto& m = static_cast<const MemberExpr&>(e);
            return show(*m.object) + "." + m.member;
        }
        default:
            return "?";
    }
}

std::string showAssigned(const std::string& expression) {
    auto p = parse("x = " + expression + ";");
    if (!p->file) return "error: " + p->diagnostics.at(0).message;
    return show(*p->file->body.assignments.at(0)->value);
}

}  // namespace

TEST(IoParser, Precedence) {
    EXPECT_EQ(showAssigned("1 + 2 * 3"), "(1+(2*3))");
    EXPECT_EQ(showAssigned("1 - 2 - 3"), "((1-2)-3)");
    EXPECT_EQ(showAssigned("a || b && c"), "(a||(b&&c))");
    EXPECT_EQ(showAssigned("a == b < c"), "(a==(b<c))");
    EXPECT_EQ(showAssigned("-2 ^ 2"), "(-(2^2))");
    EXPECT_EQ(showAssigned("2 ^ 3 ^ 2"), "(2^(3^2))");
    EXPECT_EQ(showAssigned("2 ^ -1"), "(2^(-1))");
    EXPECT_EQ(showAssigned("!a == b"), "((!a)==b)");
    EXPECT_EQ(showAssigned("a ? b : c ? d : e"), "(a?b:(c?d:e))");
    EXPECT_EQ(showAssigned("f()[1].x * 2"), "(f()[1].x*2)");
}

TEST(IoParser, VectorsRangesAndComprehensions) {
    auto p = parse(
        "a = [1, 2, 3,]; b = [0:2]; c = [0:0.5:2]; d = [for (i = [0:3]) if (i % 2) i];"
        "e = [each a, let (k = 1) k]; f = []; g = [for (i = 0; i < 3; i = i + 1) i];");
    ASSERT_TRUE(p->file) << p->diagnostics.at(0).message;
    const auto& as = p->file->body.assignments;
    ASSERT_EQ(as.size(), 7u);
    EXPECT_EQ(static_cast<const VectorExpr&>(*as[0]->value).items.size(), 3u);
    EXPECT_EQ(as[1]->value->kind, ExprKind::Range);
    EXPECT_FALSE(static_cast<const RangeExpr&>(*as[1]->value).step);
    EXPECT_TRUE(static_cast<const RangeExpr&>(*as[2]->value).step);
    const auto& d = static_cast<const VectorExpr&>(*as[3]->value);
    EXPECT_TRUE(d.hasComprehension);
    EXPECT_EQ(d.items[0]->kind, ExprKind::ForElement);
    const auto& e = static_cast<const VectorExpr&>(*as[4]->value);
    EXPECT_EQ(e.items[0]->kind, ExprKind::EachElement);
    EXPECT_EQ(e.items[1]->kind, ExprKind::LetElement);
    EXPECT_TRUE(static_cast<const VectorExpr&>(*as[5]->value).items.empty());
    EXPECT_EQ(static_cast<const VectorExpr&>(*as[6]->value).items[0]->kind, ExprKind::ForCElement);
}

TEST(IoParser, StatementsAreSortedIntoTheirScope) {
    auto p = parse(
        "cube(1); a = 1; module m(x, y = 2) { sphere(x); } function f(v) = v * 2;"
        "if (a) cube(); else { sphere(); } translate([1, 0, 0]) { b = 2; cube(b); }");
    ASSERT_TRUE(p->file) << p->diagnostics.at(0).message;
    const Body& body = p->file->body;
    EXPECT_EQ(body.assignments.size(), 1u);
    EXPECT_EQ(body.instantiations.size(), 3u);
    ASSERT_EQ(body.modules.count("m"), 1u);
    EXPECT_EQ(body.modules.at("m")->params.size(), 2u);
    EXPECT_TRUE(body.modules.at("m")->params[1].defaultValue);
    EXPECT_EQ(body.functions.count("f"), 1u);
    EXPECT_EQ(body.instantiations[1]->kind, StmtKind::If);
    const auto& t = static_cast<const InstantiationStmt&>(*body.instantiations[2]);
    EXPECT_EQ(t.children.assignments.size(), 1u);
    EXPECT_EQ(t.children.instantiations.size(), 1u);
}

TEST(IoParser, ReassignmentKeepsFirstPlaceAndLastValue) {
    auto p = parse("a = 1; b = a; a = 2;");
    ASSERT_TRUE(p->file);
    const auto& as = p->file->body.assignments;
    ASSERT_EQ(as.size(), 2u);
    EXPECT_EQ(as[0]->name, "a");
    EXPECT_EQ(static_cast<const NumberExpr&>(*as[0]->value).value, 2.0);
    EXPECT_EQ(as[1]->name, "b");
}

TEST(IoParser, Modifiers) {
    auto p = parse("#cube(); %sphere(); !cylinder(); *cube(); * # cube();");
    ASSERT_TRUE(p->file);
    const auto& is = p->file->body.instantiations;
    auto modifier = [&](size_t i) {
        return static_cast<const InstantiationStmt&>(*is[i]).modifier;
    };
    EXPECT_EQ(modifier(0), Modifier::Highlight);
    EXPECT_EQ(modifier(1), Modifier::Background);
    EXPECT_EQ(modifier(2), Modifier::Root);
    EXPECT_EQ(modifier(3), Modifier::Disable);
    EXPECT_EQ(modifier(4), Modifier::Disable);
}

TEST(IoParser, BareBlocksJoinTheEnclosingScope) {
    auto p = parse("{ a = 1; cube(a); }");
    ASSERT_TRUE(p->file);
    EXPECT_EQ(p->file->body.assignments.size(), 1u);
    EXPECT_EQ(p->file->body.instantiations.size(), 1u);
}

TEST(IoParser, LocationsOnNodes) {
    auto p = parse("\n  cube(\n    size = 2);");
    ASSERT_TRUE(p->file);
    const auto& c = static_cast<const InstantiationStmt&>(*p->file->body.instantiations[0]);
    EXPECT_EQ(c.loc.line, 2u);
    EXPECT_EQ(c.loc.col, 3u);
    EXPECT_EQ(c.args[0].loc.line, 3u);
    EXPECT_EQ(c.args[0].value->loc.col, 12u);
}

TEST(IoParser, SyntaxErrorsNameThePlace) {
    auto p = parse("cube(1);\ncube(;");
    EXPECT_FALSE(p->file);
    ASSERT_EQ(p->diagnostics.size(), 1u);
    EXPECT_EQ(p->diagnostics[0].line, 2u);
    EXPECT_EQ(p->diagnostics[0].col, 6u);
    EXPECT_EQ(p->diagnostics[0].message, "expected an expression, found ';'");

    p = parse("translate([1,0,0]) {\n cube();\n");
    EXPECT_FALSE(p->file);
    EXPECT_NE(p->diagnostics.at(0).message.find("missing '}'"), std::string::npos);
    EXPECT_EQ(p->diagnostics[0].line, 1u);

    p = parse("a = 1");
    EXPECT_FALSE(p->file);
    EXPECT_EQ(p->diagnostics.at(0).message, "expected ';' after an assignment, found end of file");
}

TEST(IoParser, DeepNestingIsAnErrorNotACrash) {
    std::string deep(100000, '(');
    auto p = parse("x = " + deep + "1;");
    EXPECT_FALSE(p->file);
    EXPECT_NE(p->diagnostics.at(0).message.find("nesting is too deep"), std::string::npos);

    std::string blocks;
    for (int i = 0; i < 5000; ++i) blocks += "union() ";
    p = parse(blocks + "cube();");
    EXPECT_FALSE(p->file);

    // A long flat chain is tall, too: bounded by the expression height limit.
    std::string chain = "x = 1";
    for (int i = 0; i < 20000; ++i) chain += "+1";
    p = parse(chain + ";");
    EXPECT_FALSE(p->file);
    EXPECT_NE(p->diagnostics.at(0).message.find("too deeply nested"), std::string::npos);
}

TEST(IoParser, IncludeSplicesStatementsRelativeToTheIncludingFile) {
    const auto dir = std::filesystem::temp_directory_path() / "csgray_io_parser_include";
    std::filesystem::create_directories(dir / "lib");
    std::ofstream(dir / "lib" / "inc.scad") << "w = 5;\nmodule part() cube(w);\n";
    auto p = parse("include <lib/inc.scad>\npart();\n", dir / "main.scad");
    ASSERT_TRUE(p->file) << p->diagnostics.at(0).message;
    EXPECT_EQ(p->file->body.assignments.size(), 1u);
    EXPECT_EQ(p->file->body.modules.count("part"), 1u);
    // Statements keep their own file's location.
    EXPECT_EQ(p->file->body.assignments[0]->loc.file, 1u);

    p = parse("include <missing.scad>\n", dir / "main.scad");
    EXPECT_FALSE(p->file);
    EXPECT_NE(p->diagnostics.at(0).message.find("cannot include 'missing.scad'"),
              std::string::npos);
    EXPECT_EQ(p->diagnostics[0].line, 1u);
}

TEST(IoParser, NonUtf8IsAnErrorWithLocation) {
    auto p = parse("cube();\nx = \"\xFF\";");
    EXPECT_FALSE(p->file);
    EXPECT_EQ(p->diagnostics.at(0).line, 2u);
    EXPECT_EQ(p->diagnostics[0].col, 6u);
    EXPECT_EQ(p->diagnostics[0].message, "file is not valid UTF-8");
}

TEST(IoParser, EmptyFileIsValid) {
    auto p = parse("");
    ASSERT_TRUE(p->file);
    EXPECT_TRUE(p->file->body.empty());
    p = parse("// only a comment\n");
    ASSERT_TRUE(p->file);
}
