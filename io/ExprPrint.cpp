#include "io/ExprPrint.h"

#include "io/Value.h"

namespace io {

namespace {

// "a = 1, 2": OpenSCAD's AssignmentList printing (a name only where one is given).
void appendArguments(std::string& out, const Arguments& args) {
    for (size_t i = 0; i < args.size(); ++i) {
        if (i > 0) out += ", ";
        if (!args[i].name.empty()) out += args[i].name + " = ";
        appendExpr(out, *args[i].value);
    }
}

bool isComprehension(const Expr& e) {
    return e.kind >= ExprKind::ForElement;
}

// body, in parentheses: how OpenSCAD's comprehension nodes print what they wrap.
void appendWrapped(std::string& out, const Expr& body) {
    out += '(';
    appendExpr(out, body);
    out += ')';
}

}  // namespace

const char* binaryOpSymbol(BinaryOp op) {
    switch (op) {
        case BinaryOp::Add:
            return "+";
        case BinaryOp::Subtract:
            return "-";
        case BinaryOp::Multiply:
            return "*";
        case BinaryOp::Divide:
            return "/";
        case BinaryOp::Modulo:
            return "%";
        case BinaryOp::Power:
            return "^";
        case BinaryOp::Less:
            return "<";
        case BinaryOp::LessEqual:
            return "<=";
        case BinaryOp::Greater:
            return ">";
        case BinaryOp::GreaterEqual:
            return ">=";
        case BinaryOp::Equal:
            return "==";
        case BinaryOp::NotEqual:
            return "!=";
        case BinaryOp::And:
            return "&&";
        case BinaryOp::Or:
            return "||";
    }
    return "?";
}

void appendFunctionLiteral(std::string& out, const FunctionLiteralExpr& f) {
    out += "function(";
    for (size_t i = 0; i < f.params.size(); ++i) {
        if (i > 0) out += ", ";
        out += f.params[i].name;
        if (f.params[i].defaultValue) {
            out += " = ";
            appendExpr(out, *f.params[i].defaultValue);
        }
    }
    out += ") ";
    appendExpr(out, *f.body);
}

void appendExpr(std::string& out, const Expr& e) {
    switch (e.kind) {
        case ExprKind::Number:
            out += formatNumber(static_cast<const NumberExpr&>(e).value);
            return;
        case ExprKind::String:
            appendQuoted(out, static_cast<const StringExpr&>(e).value);
            return;
        case ExprKind::Bool:
            out += static_cast<const BoolExpr&>(e).value ? "true" : "false";
            return;
        case ExprKind::Undef:
            out += "undef";
            return;
        case ExprKind::Identifier:
            out += static_cast<const IdentifierExpr&>(e).name;
            return;
        case ExprKind::Vector: {
            const auto& v = static_cast<const VectorExpr&>(e);
            out += '[';
            for (size_t i = 0; i < v.items.size(); ++i) {
                if (i > 0) out += ", ";
                appendExpr(out, *v.items[i]);
            }
            out += ']';
            return;
        }
        case ExprKind::Range: {
            const auto& r = static_cast<const RangeExpr&>(e);
            out += '[';
            appendExpr(out, *r.begin);
            if (r.step) {
                out += " : ";
                appendExpr(out, *r.step);
            }
            out += " : ";
            appendExpr(out, *r.end);
            out += ']';
            return;
        }
        case ExprKind::Unary: {
            const auto& u = static_cast<const UnaryExpr&>(e);
            // OpenSCAD's parser drops a unary plus; - and ! print without parentheses.
            if (u.op == UnaryOp::Negate) out += '-';
            if (u.op == UnaryOp::Not) out += '!';
            appendExpr(out, *u.operand);
            return;
        }
        case ExprKind::Binary: {
            const auto& b = static_cast<const BinaryExpr&>(e);
            out += '(';
            appendExpr(out, *b.left);
            out += ' ';
            out += binaryOpSymbol(b.op);
            out += ' ';
            appendExpr(out, *b.right);
            out += ')';
            return;
        }
        case ExprKind::Ternary: {
            const auto& t = static_cast<const TernaryExpr&>(e);
            out += '(';
            appendExpr(out, *t.condition);
            out += " ? ";
            appendExpr(out, *t.ifTrue);
            out += " : ";
            appendExpr(out, *t.ifFalse);
            out += ')';
            return;
        }
        case ExprKind::Call: {
            const auto& c = static_cast<const CallExpr&>(e);
            if (c.callee->kind == ExprKind::Identifier)
                appendExpr(out, *c.callee);
            else
                appendWrapped(out, *c.callee);
            out += '(';
            appendArguments(out, c.args);
            out += ')';
            return;
        }
        case ExprKind::Index: {
            const auto& i = static_cast<const IndexExpr&>(e);
            appendExpr(out, *i.object);
            out += '[';
            appendExpr(out, *i.index);
            out += ']';
            return;
        }
        case ExprKind::Member: {
            const auto& m = static_cast<const MemberExpr&>(e);
            appendExpr(out, *m.object);
            out += '.';
            out += m.member;
            return;
        }
        case ExprKind::Let: {
            const auto& l = static_cast<const LetExpr&>(e);
            out += "let(";
            appendArguments(out, l.assignments);
            out += ") ";
            appendExpr(out, *l.body);
            return;
        }
        case ExprKind::Assert:
        case ExprKind::Echo: {
            const auto& a = static_cast<const AssertOrEchoExpr&>(e);
            out += e.kind == ExprKind::Assert ? "assert(" : "echo(";
            appendArguments(out, a.args);
            out += ')';
            if (a.body) {
                out += ' ';
                appendExpr(out, *a.body);
            }
            return;
        }
        case ExprKind::FunctionLiteral:
            appendFunctionLiteral(out, static_cast<const FunctionLiteralExpr&>(e));
            return;
        case ExprKind::ForElement: {
            // for (a = A, b = B) is OpenSCAD's for (a = A) for (b = B), one node a variable.
            const auto& f = static_cast<const LetExpr&>(e);
            for (const Argument& a : f.assignments) {
                out += "for(";
                if (!a.name.empty()) out += a.name + " = ";
                appendExpr(out, *a.value);
                out += ") (";
            }
            appendExpr(out, *f.body);
            out.append(f.assignments.size(), ')');
            return;
        }
        case ExprKind::ForCElement: {
            const auto& f = static_cast<const ForCElementExpr&>(e);
            out += "for(";
            appendArguments(out, f.init);
            out += ';';
            appendExpr(out, *f.condition);
            out += ';';
            appendArguments(out, f.update);
            out += ") ";
            appendExpr(out, *f.body);
            return;
        }
        case ExprKind::IfElement: {
            const auto& f = static_cast<const IfElementExpr&>(e);
            out += "if(";
            appendExpr(out, *f.condition);
            out += ") ";
            appendWrapped(out, *f.ifTrue);
            if (f.ifFalse) {
                out += " else ";
                appendWrapped(out, *f.ifFalse);
            }
            return;
        }
        case ExprKind::LetElement: {
            // A let over a comprehension is OpenSCAD's LcLet, which wraps its body; a let over
            // a plain expression is an ordinary let expression.
            const auto& l = static_cast<const LetExpr&>(e);
            out += "let(";
            appendArguments(out, l.assignments);
            out += ") ";
            if (isComprehension(*l.body))
                appendWrapped(out, *l.body);
            else
                appendExpr(out, *l.body);
            return;
        }
        case ExprKind::EachElement:
            out += "each ";
            appendWrapped(out, *static_cast<const EachElementExpr&>(e).value);
            return;
    }
}

}  // namespace io
