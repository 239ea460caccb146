// surface(f, bbox, solver, tolerance): f is parsed once by the language's own expression
// parser (so "x^2", "2*x*y", "(x*x + y*y)^2 / 4" read exactly as they would in a .scad file),
// and its tree is expanded into an ExactPolynomial; nothing of the string is kept per ray.
//
// Locations: f is parsed as a little source of its own; a position (line 1, col c) in it is
// mapped back to the .scad file as the c-th character after the literal's opening quote. That
// is exact only when f is written as a literal without escapes or line breaks; otherwise the
// error sits at the argument and names the column inside f.
#include "io/SurfaceModule.h"

#include <cmath>
#include <string_view>

#include "io/BoundArgs.h"
#include "io/HeightmapModule.h"
#include "io/Parser.h"
#include "primitives/AlgebraicSurface.h"

namespace io {

namespace {

using csg::ExactPolynomial;

constexpr const char* kForm =
    "surface(f = \"polynomial in x, y, z\", bbox = [[x0, y0, z0], [x1, y1, z1]], "
    "solver = \"auto\", tolerance = 0, polish = \"auto\")";

// The walk holds a left operand while it expands the right one; each held ExactPolynomial is
// 17^3 double-double coefficients (79 KB), so right-nesting is bounded (64: 5 MB). A long
// flat sum, however tall its tree (a fully expanded degree-16 F has 969 terms), holds one.
constexpr int kMaxHeld = 64;

// Where f's text sits in the .scad file, to turn a position inside f into a file location.
struct FText {
    Loc arg;            // the argument (or the call when f is missing)
    bool literal;       // f is a string literal whose characters map 1:1 onto the file
    uint32_t quoteCol;  // the opening quote's column when literal
    Loc at(uint32_t line, uint32_t col) const {
        if (literal && line == 1) return {arg.file, arg.line, quoteCol + col};
        return arg;
    }
    std::string where(uint32_t line, uint32_t col) const {
        if (literal && line == 1) return "";
        return " (at line " + std::to_string(line) + ", column " + std::to_string(col) + " of f)";
    }
};

class PolynomialBuilder {
public:
    PolynomialBuilder(Evaluator& e, const FText& text) : e_(e), text_(text) {}

    ExactPolynomial build(const Expr& x) {
        e_.spend(text_.arg);
        e_.checkStack(text_.arg);
        switch (x.kind) {
            case ExprKind::Number: {
                const double v = static_cast<const NumberExpr&>(x).value;
                if (!std::isfinite(v)) notPolynomial(x, "a number that is not finite");
                return ExactPolynomial::constant(v);
            }
            case ExprKind::Identifier: {
                const std::string& name = static_cast<const IdentifierExpr&>(x).name;
                if (name == "x") return ExactPolynomial::x();
                if (name == "y") return ExactPolynomial::y();
                if (name == "z") return ExactPolynomial::z();
                notPolynomial(x, "'" + name + "' (only x, y, z and numbers may appear)");
            }
            case ExprKind::Unary: {
                const auto& u = static_cast<const UnaryExpr&>(x);
                if (u.op == UnaryOp::Not) notPolynomial(x, "'!'");
                ExactPolynomial v = build(*u.operand);
                return u.op == UnaryOp::Negate ? -v : v;
            }
            case ExprKind::Binary:
                return binary(static_cast<const BinaryExpr&>(x));
            case ExprKind::Call: {
                const auto& c = static_cast<const CallExpr&>(x);
                // Located at the name: the call itself sits at its '('.
                if (c.callee->kind == ExprKind::Identifier)
                    notPolynomial(*c.callee,
                                  "'" + static_cast<const IdentifierExpr&>(*c.callee).name + "'");
                notPolynomial(x, "a function call");
            }
            default:
                notPolynomial(x, describe(x.kind));
        }
    }

private:
    // build(x) while one more operand is held by the caller.
    ExactPolynomial buildHolding(const Expr& x, const Expr& at) {
        if (++held_ > kMaxHeld)
            e_.fail(text_.at(at.loc.line, at.loc.col),
                    "surface(): f nests more than " + std::to_string(kMaxHeld) + " operands deep" +
                        text_.where(at.loc.line, at.loc.col) +
                        " (expand it, or write it with fewer parentheses)");
        ExactPolynomial v = build(x);
        --held_;
        return v;
    }

    ExactPolynomial binary(const BinaryExpr& b) {
        switch (b.op) {
            case BinaryOp::Add:
            case BinaryOp::Subtract: {
                // Left first, in sequence, so a left-leaning chain holds one operand at a time.
                const ExactPolynomial l = build(*b.left);
                const ExactPolynomial r = buildHolding(*b.right, b);
                return b.op == BinaryOp::Add ? l + r : l - r;
            }
            case BinaryOp::Multiply: {
                const ExactPolynomial l = build(*b.left);
                auto p = l.times(buildHolding(*b.right, b));
                if (!p) tooHigh(b);
                return *p;
            }
            case BinaryOp::Divide: {
                const ExactPolynomial l = build(*b.left);
                const ExactPolynomial r = buildHolding(*b.right, b);
                if (r.degree() > 0) notPolynomial(*b.right, "division by a polynomial");
                const double v = r.coefficient(0, 0, 0);
                if (v == 0.0 || !std::isfinite(v)) notPolynomial(*b.right, "division by zero");
                auto p = l.dividedBy(v);
                if (!p) notPolynomial(*b.right, "division by zero");
                return *p;
            }
            case BinaryOp::Power: {
                const ExactPolynomial base = build(*b.left);
                const ExactPolynomial r = buildHolding(*b.right, b);
                if (r.degree() > 0) notPolynomial(*b.right, "an exponent that is not a number");
                const double k = r.coefficient(0, 0, 0);
                // A constant base may take any power (2^0.5 is a number); a polynomial only
                // a whole one.
                if (base.degree() == 0) {
                    const double v = std::pow(base.coefficient(0, 0, 0), k);
                    if (!std::isfinite(v)) notPolynomial(b, "a power that is not finite");
                    return ExactPolynomial::constant(v);
                }
                if (!(k >= 0 && k == std::floor(k)))
                    notPolynomial(*b.right, "the exponent " + formatNumber(k) +
                                                " (a polynomial's exponent is a whole number "
                                                ">= 0)");
                if (k > ExactPolynomial::kMaxDegree) tooHigh(b);
                auto p = base.power(static_cast<int>(k));
                if (!p) tooHigh(b);
                return *p;
            }
            default:
                notPolynomial(b, "the operator " + opName(b.op));
        }
    }

    static std::string opName(BinaryOp op) {
        switch (op) {
            case BinaryOp::Modulo:
                return "'%'";
            case BinaryOp::Less:
                return "'<'";
            case BinaryOp::LessEqual:
                return "'<='";
            case BinaryOp::Greater:
                return "'>'";
            case BinaryOp::GreaterEqual:
                return "'>='";
            case BinaryOp::Equal:
                return "'=='";
            case BinaryOp::NotEqual:
                return "'!='";
            case BinaryOp::And:
                return "'&&'";
            case BinaryOp::Or:
                return "'||'";
            default:
                return "?";
        }
    }

    static std::string describe(ExprKind k) {
        switch (k) {
            case ExprKind::String:
                return "a string";
            case ExprKind::Bool:
                return "true/false";
            case ExprKind::Undef:
                return "undef";
            case ExprKind::Vector:
                return "a vector";
            case ExprKind::Range:
                return "a range";
            case ExprKind::Ternary:
                return "'? :'";
            case ExprKind::Index:
                return "an index '[ ]'";
            case ExprKind::Member:
                return "a member '.'";
            case ExprKind::Let:
                return "'let'";
            case ExprKind::Assert:
                return "'assert'";
            case ExprKind::Echo:
                return "'echo'";
            case ExprKind::FunctionLiteral:
                return "a function literal";
            default:
                return "this construct";
        }
    }

    [[noreturn]] void notPolynomial(const Expr& x, const std::string& what) {
        e_.fail(text_.at(x.loc.line, x.loc.col), "surface(): f is not a polynomial: " + what +
                                                     text_.where(x.loc.line, x.loc.col) +
                                                     "; expected " + kForm);
    }
    [[noreturn]] void tooHigh(const Expr& x) {
        e_.fail(text_.at(x.loc.line, x.loc.col),
                "surface(): f has degree above " + std::to_string(ExactPolynomial::kMaxDegree) +
                    " here" + text_.where(x.loc.line, x.loc.col) + " (the most csgray solves)");
    }

    Evaluator& e_;
    const FText& text_;
    int held_ = 0;
};

csg::Bounds3 bboxArg(Evaluator& e, const BoundArgs& b) {
    const char* what = "[[x0, y0, z0], [x1, y1, z1]] with x0 < x1, y0 < y1, z0 < z1";
    if (b.values[1].isUndef())
        e.fail(b.locs[1], std::string("surface() needs a bounding box bbox; expected ") + kForm);
    const Value& v = b.values[1];
    if (!v.isVector() || v.list().size() != 2) b.bad(e, 1, what);
    csg::Vec3 corner[2];
    for (int c = 0; c < 2; ++c) {
        const Value& p = v.list()[c];
        if (!p.isVector() || p.list().size() != 3) b.bad(e, 1, what);
        for (int k = 0; k < 3; ++k) {
            const Value& n = p.list()[k];
            if (!n.isNumber() || !std::isfinite(n.number())) b.bad(e, 1, what);
            corner[c][k] = n.number();
        }
    }
    for (int k = 0; k < 3; ++k)
        if (!(corner[0][k] < corner[1][k])) b.bad(e, 1, what);
    return {corner[0], corner[1]};
}

}  // namespace

Instance surfaceModule(Evaluator& e, const InstantiationStmt& s, const ContextPtr& ctx,
                       const GeomState& state) {
    // OpenSCAD's heightmap, surface(file = ...), is another module under the same name.
    if (isHeightmapCall(s)) return heightmapModule(e, s, ctx, state);
    const BoundArgs b = bindArgs(e, s, ctx, {"f", "bbox", "solver", "tolerance", "polish"}, kForm);

    // f: parsed by the language's own parser as a source of its own.
    if (b.values[0].isUndef())
        e.fail(s.loc, std::string("surface() needs a polynomial f; expected ") + kForm);
    if (!b.values[0].isString()) b.bad(e, 0, "a string");
    const std::string& f = b.values[0].string();
    FText text{b.locs[0], false, 0};
    if (b.exprs[0] && b.exprs[0]->kind == ExprKind::String &&
        f.find_first_of("\"\\\n\r\t") == std::string::npos) {
        text.literal = true;
        text.arg = b.exprs[0]->loc;
        text.quoteCol = b.exprs[0]->loc.col;
    }
    SourceFiles fSource;
    const uint32_t index = fSource.add("f", {}, f);
    std::vector<Diagnostic> parseErrors;
    ExprPtr tree = parseExpression(fSource, index, parseErrors);
    if (!tree) {
        const Diagnostic d = parseErrors.empty() ? Diagnostic{} : parseErrors[0];
        e.fail(text.at(d.line, d.col), "surface(): f is not an expression: " + d.message +
                                           text.where(d.line, d.col) + "; expected " + kForm);
    }
    const ExactPolynomial poly = PolynomialBuilder(e, text).build(*tree);

    const csg::Bounds3 box = bboxArg(e, b);
    const csg::Solver solver =
        choiceArg(e, b, 2, "solver", csg::kAllSolvers, csg::solverName, csg::Solver::Auto);
    double tolerance = 0.0;
    if (!b.values[3].isUndef()) {
        if (!b.values[3].isNumber() || !(b.values[3].number() >= 0 && b.values[3].number() < 1))
            b.bad(e, 3, "a number in [0, 1) (0: roots to double precision)");
        tolerance = b.values[3].number();
    }

    const csg::Polisher polisher =
        choiceArg(e, b, 4, "polish", csg::kAllPolishers, csg::polisherName, csg::Polisher::Auto);
    const csg::AlgebraicSurface shape =
        csg::AlgebraicSurface::make(poly, box, solver, tolerance, polisher);
    if (const char* why = shape.invalidReason())
        e.fail(b.locs[0], std::string("surface(): ") + why + "; expected " + kForm);
    return csg::leaf(shape, {e.sourceTag(s.loc, e.childPath(state, s.name)), state.material});
}

}  // namespace io
