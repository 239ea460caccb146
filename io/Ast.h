// The syntax tree of a part, every node with its source location. Expressions and statements
// are small kind-tagged structs (static_cast by kind, no virtual dispatch in the evaluator);
// the tree is immutable after parsing and owned by its File.
#pragma once

#include <memory>
#include <string>
#include <unordered_map>
#include <vector>

#include "io/Lexer.h"

namespace io {

enum class ExprKind : uint8_t {
    Number,
    String,
    Bool,
    Undef,
    Identifier,
    Vector,
    Range,
    Unary,
    Binary,
    Ternary,
    Call,
    Index,
    Member,
    Let,
    Assert,
    Echo,
    FunctionLiteral,
    // List-comprehension elements, only inside a Vector (or nested in each other).
    ForElement,
    ForCElement,
    IfElement,
    LetElement,
    EachElement,
};

struct Expr {
    ExprKind kind;
    Loc loc;
    uint32_t depth = 1;  // height of this subtree, bounded by the parser (no deep recursion)
    Expr(ExprKind k, Loc l) : kind(k), loc(l) {}
    virtual ~Expr() = default;
};
using ExprPtr = std::unique_ptr<Expr>;

// name = value in a call (name empty when positional), in let(), for() and assignments.
struct Argument {
    std::string name;
    ExprPtr value;
    Loc loc;
};
using Arguments = std::vector<Argument>;

// A declared parameter with its optional default value.
struct Parameter {
    std::string name;
    ExprPtr defaultValue;  // null: undef when not passed
    Loc loc;
};
using Parameters = std::vector<Parameter>;

struct NumberExpr : Expr {
    double value;
    NumberExpr(Loc l, double v) : Expr(ExprKind::Number, l), value(v) {}
};
struct StringExpr : Expr {
    std::string value;
    StringExpr(Loc l, std::string v) : Expr(ExprKind::String, l), value(std::move(v)) {}
};
struct BoolExpr : Expr {
    bool value;
    BoolExpr(Loc l, bool v) : Expr(ExprKind::Bool, l), value(v) {}
};
struct IdentifierExpr : Expr {
    std::string name;
    IdentifierExpr(Loc l, std::string n) : Expr(ExprKind::Identifier, l), name(std::move(n)) {}
};
// [a, b, ...] including comprehension elements.
struct VectorExpr : Expr {
    std::vector<ExprPtr> items;
    bool hasComprehension = false;  // any item is a *Element
    explicit VectorExpr(Loc l) : Expr(ExprKind::Vector, l) {}
};
// [begin : end] or [begin : step : end]
struct RangeExpr : Expr {
    ExprPtr begin, step, end;  // step null: 1
    explicit RangeExpr(Loc l) : Expr(ExprKind::Range, l) {}
};
enum class UnaryOp : uint8_t { Negate, Plus, Not };
struct UnaryExpr : Expr {
    UnaryOp op;
    ExprPtr operand;
    UnaryExpr(Loc l, UnaryOp o, ExprPtr e)
        : Expr(ExprKind::Unary, l), op(o), operand(std::move(e)) {}
};
enum class BinaryOp : uint8_t {
    Add,
    Subtract,
    Multiply,
    Divide,
    Modulo,
    Power,
    Less,
    LessEqual,
    Greater,
    GreaterEqual,
    Equal,
    NotEqual,
    And,
    Or,
};
struct BinaryExpr : Expr {
    BinaryOp op;
    ExprPtr left, right;
    BinaryExpr(Loc l, BinaryOp o, ExprPtr a, ExprPtr b)
        : Expr(ExprKind::Binary, l), op(o), left(std::move(a)), right(std::move(b)) {}
};
struct TernaryExpr : Expr {
    ExprPtr condition, ifTrue, ifFalse;
    explicit TernaryExpr(Loc l) : Expr(ExprKind::Ternary, l) {}
};
// callee(args): callee is usually an identifier (a named function) but may be any expression
// that yields a function literal.
struct CallExpr : Expr {
    ExprPtr callee;
    Arguments args;
    explicit CallExpr(Loc l) : Expr(ExprKind::Call, l) {}
};
struct IndexExpr : Expr {
    ExprPtr object, index;
    explicit IndexExpr(Loc l) : Expr(ExprKind::Index, l) {}
};
struct MemberExpr : Expr {
    ExprPtr object;
    std::string member;  // x, y or z
    explicit MemberExpr(Loc l) : Expr(ExprKind::Member, l) {}
};
// let(a = 1, b = a) body — also let/for/if/each list elements reuse these fields.
struct LetExpr : Expr {
    Arguments assignments;
    ExprPtr body;
    LetExpr(ExprKind k, Loc l) : Expr(k, l) {}
};
// assert(args) body / echo(args) body; body may be null (undef).
struct AssertOrEchoExpr : Expr {
    Arguments args;
    ExprPtr body;
    AssertOrEchoExpr(ExprKind k, Loc l) : Expr(k, l) {}
};
struct FunctionLiteralExpr : Expr {
    Parameters params;
    ExprPtr body;
    explicit FunctionLiteralExpr(Loc l) : Expr(ExprKind::FunctionLiteral, l) {}
};
// for (init; condition; update) body  (C-style comprehension)
struct ForCElementExpr : Expr {
    Arguments init, update;
    ExprPtr condition, body;
    explicit ForCElementExpr(Loc l) : Expr(ExprKind::ForCElement, l) {}
};
struct IfElementExpr : Expr {
    ExprPtr condition, ifTrue, ifFalse;  // ifFalse may be null
    explicit IfElementExpr(Loc l) : Expr(ExprKind::IfElement, l) {}
};
struct EachElementExpr : Expr {
    ExprPtr value;
    explicit EachElementExpr(Loc l) : Expr(ExprKind::EachElement, l) {}
};

// ---- statements ----

enum class StmtKind : uint8_t { Assignment, ModuleDef, FunctionDef, Instantiation, If };

struct Stmt {
    StmtKind kind;
    Loc loc;
    Stmt(StmtKind k, Loc l) : kind(k), loc(l) {}
    virtual ~Stmt() = default;
};
using StmtPtr = std::unique_ptr<Stmt>;

struct ModuleDefStmt;
struct FunctionDefStmt;

// The statements of one scope (a file, a module body, a children block, an if branch),
// pre-sorted the way OpenSCAD evaluates them: all assignments first, in order, then the
// instantiations; definitions are visible in the whole scope (the last one of a name wins).
struct Body {
    std::vector<StmtPtr> statements;  // owns everything below
    std::vector<const struct AssignmentStmt*> assignments;
    std::vector<const Stmt*> instantiations;  // Instantiation or If
    std::unordered_map<std::string, const ModuleDefStmt*> modules;
    std::unordered_map<std::string, const FunctionDefStmt*> functions;
    // Where each assigned name sits in `assignments` (a reassignment replaces the value there).
    std::unordered_map<std::string, size_t> assignmentSlots;

    void add(StmtPtr statement);  // files it into the lists above
    bool empty() const { return statements.empty(); }
};

struct AssignmentStmt : Stmt {
    std::string name;
    ExprPtr value;
    AssignmentStmt(Loc l, std::string n, ExprPtr v)
        : Stmt(StmtKind::Assignment, l), name(std::move(n)), value(std::move(v)) {}
};
struct ModuleDefStmt : Stmt {
    std::string name;
    Parameters params;
    Body body;
    ModuleDefStmt(Loc l, std::string n) : Stmt(StmtKind::ModuleDef, l), name(std::move(n)) {}
};
struct FunctionDefStmt : Stmt {
    std::string name;
    Parameters params;
    ExprPtr body;
    FunctionDefStmt(Loc l, std::string n) : Stmt(StmtKind::FunctionDef, l), name(std::move(n)) {}
};
// The modifier characters OpenSCAD puts before an instantiation.
enum class Modifier : uint8_t {
    None,
    Disable /* * */,
    Root /* ! */,
    Highlight /* # */,
    Background /* % */
};
// name(args) child  — child is ';' (empty), one instantiation or a { block }.
struct InstantiationStmt : Stmt {
    std::string name;
    Arguments args;
    Body children;
    Modifier modifier = Modifier::None;
    InstantiationStmt(Loc l, std::string n)
        : Stmt(StmtKind::Instantiation, l), name(std::move(n)) {}
};
struct IfStmt : Stmt {
    ExprPtr condition;
    Body ifTrue, ifFalse;
    Modifier modifier = Modifier::None;
    explicit IfStmt(Loc l) : Stmt(StmtKind::If, l) {}
};

// A parsed file: its top-level scope and the files it uses (use <f>). include <f> is textual
// in OpenSCAD, so included statements are already spliced into body.
struct ParsedFile {
    uint32_t fileIndex = 0;
    Body body;
    std::vector<std::pair<std::string, Loc>> uses;  // path as written, location of 'use'
};

}  // namespace io
