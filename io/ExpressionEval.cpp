// Expressions with OpenSCAD 2021's semantics: undefined operations give undef (with a
// warning), vectors add element-wise up to the shorter length, vector*vector is a dot product
// or a matrix product, comparisons order numbers, strings, bools and vectors.
#include <algorithm>
#include <cmath>

#include "io/Evaluator.h"
#include "io/ExprPrint.h"

namespace io {

void Context::set(std::string_view name, Value value) {
    for (auto& [n, v] : variables)
        if (n == name) {
            v = std::move(value);
            return;
        }
    variables.emplace_back(std::string(name), std::move(value));
}

const Value* Context::findLocal(std::string_view name) const {
    for (auto it = variables.rbegin(); it != variables.rend(); ++it)
        if (it->first == name) return &it->second;
    return nullptr;
}

// Warnings are capped so a loop over a million bad values cannot flood the output.
constexpr uint32_t kMaxWarnings = 100;

void Evaluator::warn(Loc loc, std::string message) {
    if (++warnings_ > kMaxWarnings) return;
    if (warnings_ == kMaxWarnings) message += " (further warnings suppressed)";
    diagnostics_.push_back(
        {sources_.name(loc.file), loc.line, loc.col, Severity::Warning, std::move(message)});
}

void Evaluator::failWorkLimit(Loc loc) {
    fail(loc, "evaluation takes too long: more than " + std::to_string(options_.maxSteps) +
                  " steps (expressions, loop iterations, list elements); is a loop or a "
                  "recursion unbounded?");
}

void Evaluator::failStack(Loc loc) {
    fail(loc, "nesting too deep: expressions, calls and blocks use up the evaluator's stack");
}

Value Evaluator::makeList(ValueList items, Loc loc) {
    Value list(std::move(items));
    if (list.depth() > kMaxListDepth)
        fail(loc,
             "lists nested too deeply (more than " + std::to_string(kMaxListDepth) + " levels)");
    return list;
}

std::string Evaluator::printed(const Value& v, bool quoted, Loc loc) {
    const WorkBudget available = budget();
    WorkBudget b{std::min(available.left, kMaxStringBytes)};
    std::string text = quoted ? v.repr(b) : v.toString(b);
    if (b.exhausted && available.left > kMaxStringBytes)
        fail(loc, "string too long (more than " + std::to_string(kMaxStringBytes) + " bytes)");
    settle(WorkBudget{available.left - (std::min(available.left, kMaxStringBytes) - b.left),
                      b.exhausted},
           loc);
    return text;
}

Value Evaluator::lookupVariable(const std::string& name, const ContextPtr& ctx, Loc loc,
                                bool silent) {
    // $-names are dynamic, except $children, which OpenSCAD 2021 resolves lexically: a
    // block of children sees the $children of the module it is written in, not of the one
    // that instantiates it, and a function sees none (BOSL2's regular_polyhedron asks for it
    // inside translate() { ... }, which BOSL2 redefines as a module of its own).
    const bool dynamic = !name.empty() && name[0] == '$' && name != "$children";
    for (const Context* c = ctx.get(); c;
         c = dynamic ? c->dynamicParent.get() : c->lexicalParent.get())
        if (const Value* v = c->findLocal(name)) return *v;
    if (!silent) warn(loc, "ignoring unknown variable '" + name + "'");
    return Value();
}

ArgValues Evaluator::evalArgs(const Arguments& args, const ContextPtr& ctx) {
    ArgValues out;
    out.reserve(args.size());
    for (const Argument& a : args) out.push_back({a.name, eval(*a.value, ctx), a.loc});
    return out;
}

ContextPtr Evaluator::letContext(const Arguments& assignments, const ContextPtr& ctx) {
    // Sequential: each assignment sees the ones before it.
    ContextPtr c = Context::make(ctx, ctx, nullptr);
    for (const Argument& a : assignments) c->set(a.name, eval(*a.value, c));
    return c;
}

void Evaluator::echo(const ArgValues& args) {
    std::string line = "ECHO: ";
    bool first = true;
    for (const ArgValue& a : args) {
        if (!first) line += ", ";
        first = false;
        if (!a.name.empty()) line += a.name + " = ";
        line += printed(a.value, true, a.loc);
    }
    if (options_.echo)
        options_.echo(line);
    else
        std::fprintf(stderr, "%s\n", line.c_str());
}

void Evaluator::checkAssert(const AssertOrEchoExpr& e, const ContextPtr& ctx) {
    ArgValues args = evalArgs(e.args, ctx);
    if (args.empty())
        fail(e.loc, "assert() needs a condition; expected assert(condition, message)");
    if (args[0].value.truthy()) return;
    std::string message = "assertion failed";
    if (args.size() > 1) message += ": " + printed(args[1].value, false, e.loc);
    fail(e.loc, message);
}

namespace {

bool isNumberList(const Value& v, WorkBudget& w) {
    if (!v.isVector() || !w.spend(v.list().size())) return false;
    for (const Value& x : v.list())
        if (!x.isNumber()) return false;
    return true;
}

bool isMatrix(const Value& v, WorkBudget& w) {
    if (!v.isVector() || v.list().empty()) return false;
    const size_t columns = v.list()[0].isVector() ? v.list()[0].list().size() : 0;
    if (columns == 0) return false;
    for (const Value& row : v.list())
        if (!isNumberList(row, w) || row.list().size() != columns) return false;
    return true;
}

Value dot(const ValueList& a, const ValueList& b, WorkBudget& w) {
    if (!w.spend(a.size())) return Value();
    double sum = 0.0;
    for (size_t i = 0; i < a.size(); ++i) sum += a[i].number() * b[i].number();
    return Value(sum);
}

// A column of a matrix as a value list.
ValueList column(const ValueList& matrix, size_t c) {
    ValueList out;
    out.reserve(matrix.size());
    for (const Value& row : matrix) out.push_back(row.list()[c]);
    return out;
}

}  // namespace

// The arithmetic of OpenSCAD; undef for combinations it does not define. Each element
// produced or multiplied spends a unit of w (nested vectors may share their rows).
static Value arithmetic(BinaryOp op, const Value& a, const Value& b, WorkBudget& w) {
    if (!w.spend()) return Value();
    if (a.isNumber() && b.isNumber()) {
        const double x = a.number(), y = b.number();
        switch (op) {
            case BinaryOp::Add:
                return x + y;
            case BinaryOp::Subtract:
                return x - y;
            case BinaryOp::Multiply:
                return x * y;
            case BinaryOp::Divide:
                return x / y;
            case BinaryOp::Modulo:
                return std::fmod(x, y);
            case BinaryOp::Power:
                return std::pow(x, y);
            default:
                return Value();
        }
    }
    if ((op == BinaryOp::Add || op == BinaryOp::Subtract) && a.isVector() && b.isVector()) {
        const size_t n = std::min(a.list().size(), b.list().size());
        ValueList out;
        out.reserve(n);
        for (size_t i = 0; i < n && !w.exhausted; ++i)
            out.push_back(arithmetic(op, a.list()[i], b.list()[i], w));
        return out;
    }
    if (op == BinaryOp::Multiply || op == BinaryOp::Divide) {
        // Scalar and vector, element-wise (recursively, so a matrix scales too).
        if (a.isVector() && b.isNumber()) {
            ValueList out;
            out.reserve(a.list().size());
            for (const Value& x : a.list()) {
                if (w.exhausted) break;
                out.push_back(arithmetic(op, x, b, w));
            }
            return out;
        }
        if (a.isNumber() && b.isVector()) {
            ValueList out;
            out.reserve(b.list().size());
            for (const Value& y : b.list()) {
                if (w.exhausted) break;
                out.push_back(arithmetic(op, a, y, w));
            }
            return out;
        }
    }
    if (op == BinaryOp::Multiply && a.isVector() && b.isVector()) {
        const ValueList &x = a.list(), &y = b.list();
        if (isNumberList(a, w) && isNumberList(b, w))
            return x.size() == y.size() ? dot(x, y, w) : Value();
        if (isMatrix(a, w) && isNumberList(b, w)) {  // matrix * column vector
            if (x[0].list().size() != y.size()) return Value();
            ValueList out;
            for (const Value& row : x) out.push_back(dot(row.list(), y, w));
            return out;
        }
        if (isNumberList(a, w) && isMatrix(b, w)) {  // row vector * matrix
            if (x.size() != y.size()) return Value();
            ValueList out;
            for (size_t c = 0; c < y[0].list().size() && !w.exhausted; ++c)
                out.push_back(dot(x, column(y, c), w));
            return out;
        }
        if (isMatrix(a, w) && isMatrix(b, w)) {
            if (x[0].list().size() != y.size()) return Value();
            ValueList out;
            for (const Value& row : x) {
                ValueList r;
                for (size_t c = 0; c < y[0].list().size() && !w.exhausted; ++c)
                    r.push_back(dot(row.list(), column(y, c), w));
                out.push_back(std::move(r));
            }
            return out;
        }
    }
    return Value();
}

// <, <=, >, >= : numbers, strings, bools, and vectors lexicographically; else undef.
static std::optional<int> compare(const Value& a, const Value& b, WorkBudget& w) {
    if (!w.spend() || a.type() != b.type()) return std::nullopt;
    switch (a.type()) {
        case Value::Type::Number:
            if (std::isnan(a.number()) || std::isnan(b.number())) return std::nullopt;
            return a.number() < b.number() ? -1 : a.number() > b.number() ? 1 : 0;
        case Value::Type::Bool:
            return int(a.asBool()) - int(b.asBool());
        case Value::Type::String:
            if (!w.spend(a.string().size())) return std::nullopt;
            return a.string().compare(b.string()) < 0   ? -1
                   : a.string().compare(b.string()) > 0 ? 1
                                                        : 0;
        case Value::Type::Vector: {
            const ValueList &x = a.list(), &y = b.list();
            for (size_t i = 0; i < x.size() && i < y.size(); ++i) {
                auto c = compare(x[i], y[i], w);
                if (!c) return std::nullopt;
                if (*c != 0) return c;
            }
            return x.size() < y.size() ? -1 : x.size() > y.size() ? 1 : 0;
        }
        default:
            return std::nullopt;
    }
}

Value Evaluator::evalBinary(const BinaryExpr& e, const ContextPtr& ctx) {
    if (e.op == BinaryOp::And) return eval(*e.left, ctx).truthy() && eval(*e.right, ctx).truthy();
    if (e.op == BinaryOp::Or) return eval(*e.left, ctx).truthy() || eval(*e.right, ctx).truthy();
    const Value a = eval(*e.left, ctx);
    const Value b = eval(*e.right, ctx);
    WorkBudget w = budget();
    switch (e.op) {
        case BinaryOp::Equal:
        case BinaryOp::NotEqual: {
            const bool equal = a.equals(b, w);
            settle(w, e.loc);
            return e.op == BinaryOp::Equal ? equal : !equal;
        }
        case BinaryOp::Less:
        case BinaryOp::LessEqual:
        case BinaryOp::Greater:
        case BinaryOp::GreaterEqual: {
            const auto c = compare(a, b, w);
            settle(w, e.loc);
            if (!c) {
                if (!(a.isNumber() && b.isNumber()))  // NaN compares silently false
                    warn(e.loc, std::string("undefined operation (") + a.typeName() + " " +
                                    binaryOpSymbol(e.op) + " " + b.typeName() + ")");
                return a.isNumber() && b.isNumber() ? Value(false) : Value();
            }
            switch (e.op) {
                case BinaryOp::Less:
                    return *c < 0;
                case BinaryOp::LessEqual:
                    return *c <= 0;
                case BinaryOp::Greater:
                    return *c > 0;
                default:
                    return *c >= 0;
            }
        }
        default: {
            Value r = arithmetic(e.op, a, b, w);
            settle(w, e.loc);
            if (r.isUndef())
                warn(e.loc, std::string("undefined operation (") + a.typeName() + " " +
                                binaryOpSymbol(e.op) + " " + b.typeName() + ")");
            return r;
        }
    }
}

static Value negate(const Value& v, WorkBudget& w) {
    if (!w.spend()) return Value();
    if (v.isNumber()) return -v.number();
    if (v.isVector()) {
        ValueList out;
        out.reserve(v.list().size());
        for (const Value& x : v.list()) {
            if (w.exhausted) break;
            out.push_back(negate(x, w));
        }
        return out;
    }
    return Value();
}

Value Evaluator::evalRange(const RangeExpr& e, const ContextPtr& ctx) {
    const Value begin = eval(*e.begin, ctx);
    const Value step = e.step ? eval(*e.step, ctx) : Value(1.0);
    const Value end = eval(*e.end, ctx);
    // Not numbers: undef, silently, as in OpenSCAD 2021 (BOSL2's is_range tests [3:4:"a"]).
    if (!begin.isNumber() || !step.isNumber() || !end.isNumber()) return Value();
    Range r{begin.number(), step.number(), end.number()};
    if (!e.step && r.begin > r.end) {
        // OpenSCAD's deprecated [5:1] form counts up from the smaller end.
        warn(e.loc, "ranges of the form [begin:end] with begin greater than end are deprecated");
        std::swap(r.begin, r.end);
    }
    return r;
}

Value Evaluator::evalVector(const VectorExpr& e, const ContextPtr& ctx) {
    ValueList out;
    out.reserve(e.items.size());
    if (!e.hasComprehension) {
        for (const auto& item : e.items) out.push_back(eval(*item, ctx));
        return makeList(std::move(out), e.loc);
    }
    for (const auto& item : e.items) evalElement(*item, ctx, out);
    return makeList(std::move(out), e.loc);
}

// One element of a vector literal, appending zero or more values.
void Evaluator::evalElement(const Expr& e, const ContextPtr& ctx, ValueList& out) {
    switch (e.kind) {
        case ExprKind::ForElement: {
            const auto& f = static_cast<const LetExpr&>(e);
            // for (a = A, b = B) nests: a outermost.
            auto loop = [&](auto& self, size_t index, const ContextPtr& c) -> void {
                if (index == f.assignments.size()) {
                    evalElement(*f.body, c, out);
                    return;
                }
                const Argument& a = f.assignments[index];
                const Value items = eval(*a.value, c);
                forEachItem(items, a.loc, [&](const Value& item) {
                    ContextPtr inner = Context::make(c, c, nullptr);
                    inner->set(a.name, item);
                    self(self, index + 1, inner);
                    return true;
                });
            };
            loop(loop, 0, ctx);
            return;
        }
        case ExprKind::ForCElement: {
            const auto& f = static_cast<const ForCElementExpr&>(e);
            ContextPtr c = letContext(f.init, ctx);
            for (double n = 0;; ++n) {
                if (n > kMaxIterations) fail(e.loc, "for loop runs too long");
                spend(e.loc);
                if (!eval(*f.condition, c).truthy()) break;
                evalElement(*f.body, c, out);
                // The update is sequential, as OpenSCAD 2021 evaluates it: each assignment
                // sees the ones before it (for (i = 0, j = 0; ...; i = i + 1, j = i) makes
                // j the new i), and a name it introduces stays for the following iterations.
                ContextPtr next = Context::make(ctx, ctx, nullptr);
                next->variables = c->variables;
                for (const Argument& a : f.update) next->set(a.name, eval(*a.value, next));
                c = std::move(next);
            }
            return;
        }
        case ExprKind::IfElement: {
            const auto& f = static_cast<const IfElementExpr&>(e);
            if (eval(*f.condition, ctx).truthy())
                evalElement(*f.ifTrue, ctx, out);
            else if (f.ifFalse)
                evalElement(*f.ifFalse, ctx, out);
            return;
        }
        case ExprKind::LetElement: {
            const auto& f = static_cast<const LetExpr&>(e);
            evalElement(*f.body, letContext(f.assignments, ctx), out);
            return;
        }
        case ExprKind::EachElement: {
            // each splices a value into the list: a list's elements, a range's numbers, a
            // string's characters; undef adds nothing, any other value itself.
            const auto& f = static_cast<const EachElementExpr&>(e);
            const auto splice = [&](const Value& v) {
                if (v.isUndef()) return;
                if (!v.isVector() && !v.isRange() && !v.isString()) {
                    out.push_back(v);
                    return;
                }
                forEachItem(v, e.loc, [&](const Value& item) {
                    out.push_back(item);
                    return true;
                });
            };
            if (f.value->kind < ExprKind::ForElement) {
                splice(eval(*f.value, ctx));
                return;
            }
            // Over a comprehension, each value it yields is spliced, as OpenSCAD 2021 does
            // (LcEach::evalRecur): [each for (i = [1:2]) [i, i]] is [1, 1, 2, 2], and BOSL2's
            // vnf_vertex_array collects its faces with `each let(...) faces`.
            ValueList items;
            evalElement(*f.value, ctx, items);
            for (const Value& v : items) splice(v);
            return;
        }
        default:
            out.push_back(eval(e, ctx));
            return;
    }
}

Value Evaluator::eval(const Expr& e, const ContextPtr& ctx) {
    spend(e.loc);
    checkStack(e.loc);
    switch (e.kind) {
        case ExprKind::Number:
            return static_cast<const NumberExpr&>(e).value;
        case ExprKind::String:
            return static_cast<const StringExpr&>(e).value;
        case ExprKind::Bool:
            return static_cast<const BoolExpr&>(e).value;
        case ExprKind::Undef:
            return Value();
        case ExprKind::Identifier:
            return lookupVariable(static_cast<const IdentifierExpr&>(e).name, ctx, e.loc);
        case ExprKind::Vector:
            return evalVector(static_cast<const VectorExpr&>(e), ctx);
        case ExprKind::Range:
            return evalRange(static_cast<const RangeExpr&>(e), ctx);
        case ExprKind::Unary: {
            const auto& u = static_cast<const UnaryExpr&>(e);
            const Value v = eval(*u.operand, ctx);
            if (u.op == UnaryOp::Not) return !v.truthy();
            if (u.op == UnaryOp::Plus) {
                if (v.isNumber() || v.isVector()) return v;
            } else {
                WorkBudget w = budget();
                Value r = negate(v, w);
                settle(w, e.loc);
                if (!r.isUndef()) return r;
            }
            warn(e.loc, std::string("undefined operation (") + (u.op == UnaryOp::Plus ? "+" : "-") +
                            v.typeName() + ")");
            return Value();
        }
        case ExprKind::Binary:
            return evalBinary(static_cast<const BinaryExpr&>(e), ctx);
        case ExprKind::Ternary: {
            const auto& t = static_cast<const TernaryExpr&>(e);
            return eval(eval(*t.condition, ctx).truthy() ? *t.ifTrue : *t.ifFalse, ctx);
        }
        case ExprKind::Call:
            return callFunctionExpr(static_cast<const CallExpr&>(e), ctx);
        case ExprKind::Index: {
            const auto& i = static_cast<const IndexExpr&>(e);
            const Value object = eval(*i.object, ctx);
            const Value index = eval(*i.index, ctx);
            if (!index.isNumber() || std::isnan(index.number())) return Value();
            const double k = std::trunc(index.number());
            if (object.isVector()) {
                if (k < 0 || k >= static_cast<double>(object.list().size())) return Value();
                return object.list()[static_cast<size_t>(k)];
            }
            if (object.isRange()) {
                // OpenSCAD 2021 indexes a range's parts: [b:s:e][0] = b, [1] = s, [2] = e
                // (BOSL2's is_range tests for them).
                const Range& r = object.range();
                return k == 0   ? Value(r.begin)
                       : k == 1 ? Value(r.step)
                       : k == 2 ? Value(r.end)
                                : Value();
            }
            if (object.isString()) {
                // Index by code point, as OpenSCAD does.
                const std::string& s = object.string();
                size_t count = 0;
                for (size_t p = 0; p < s.size();) {
                    size_t len = 1;
                    while (p + len < s.size() &&
                           (static_cast<unsigned char>(s[p + len]) & 0xC0) == 0x80)
                        ++len;
                    if (static_cast<double>(count) == k) return s.substr(p, len);
                    spend(e.loc);  // indexing walks the code points before k
                    ++count;
                    p += len;
                }
            }
            return Value();
        }
        case ExprKind::Member: {
            const auto& m = static_cast<const MemberExpr&>(e);
            const Value object = eval(*m.object, ctx);
            if (object.isVector()) {
                const size_t k = m.member == "x"   ? 0
                                 : m.member == "y" ? 1
                                 : m.member == "z" ? 2
                                                   : 99;
                return k < object.list().size() ? object.list()[k] : Value();
            }
            if (object.isRange()) {
                if (m.member == "begin") return object.range().begin;
                if (m.member == "step") return object.range().step;
                if (m.member == "end") return object.range().end;
            }
            return Value();
        }
        case ExprKind::Let: {
            const auto& l = static_cast<const LetExpr&>(e);
            return eval(*l.body, letContext(l.assignments, ctx));
        }
        case ExprKind::Assert: {
            const auto& a = static_cast<const AssertOrEchoExpr&>(e);
            checkAssert(a, ctx);
            return a.body ? eval(*a.body, ctx) : Value();
        }
        case ExprKind::Echo: {
            const auto& a = static_cast<const AssertOrEchoExpr&>(e);
            echo(evalArgs(a.args, ctx));
            return a.body ? eval(*a.body, ctx) : Value();
        }
        case ExprKind::FunctionLiteral:
            closures_.push_back(ctx);
            return FunctionValue{static_cast<const FunctionLiteralExpr*>(&e), ctx};
        default:
            fail(e.loc, "list comprehension elements are only allowed inside [ ]");
    }
}

}  // namespace io
