// Calling functions: parameter binding with positional, named and default arguments, and
// tail calls run as a loop (as OpenSCAD does), so f(n) = n <= 0 ? a : f(n - 1, ...) may
// recurse a million times without growing the C++ stack.
#include <bit>

#include "io/Evaluator.h"

namespace io {

// The most tail calls one call may chain (OpenSCAD allows about a million).
constexpr uint64_t kMaxTailCalls = 2'000'000;

namespace {

// The dynamic scope a tail call passes on: the $-variables visible from c (nearest wins),
// gathered into one context whose dynamic parent is the caller of the whole loop. Chaining
// c itself instead would lengthen, with every tail call, the chain a $-lookup walks: a
// million calls would take quadratic time. Only $-names are looked up dynamically, so what
// the callee sees is the same.
ContextPtr dynamicScopeOf(const ContextPtr& c, const ContextPtr& loopCaller) {
    ContextPtr scope = Context::make(nullptr, loopCaller, nullptr);
    for (const Context* d = c.get(); d && d != loopCaller.get(); d = d->dynamicParent.get())
        for (const auto& [name, value] : d->variables)
            if (!name.empty() && name[0] == '$' && !scope->findLocal(name)) scope->set(name, value);
    return scope;
}

}  // namespace

Evaluator::DepthGuard::DepthGuard(Evaluator& ev, Loc loc, const std::string& name) : e(ev) {
    if (++e.depth_ > e.options_.maxCallDepth) {
        --e.depth_;
        e.fail(loc, "recursion too deep calling '" + name + "' (more than " +
                        std::to_string(e.options_.maxCallDepth) + " nested calls)");
    }
}

ContextPtr Evaluator::bindParameters(const Parameters& params, const ArgValues& args,
                                     ContextPtr definition, ContextPtr caller, Loc loc,
                                     const std::string& what) {
    ContextPtr c = Context::make(std::move(definition), std::move(caller), nullptr);
    // Which parameters got an argument: a word of bits for the usual few (no allocation per
    // call), a vector beyond 64.
    uint64_t boundBits = 0;
    std::vector<bool> boundMore(params.size() > 64 ? params.size() : 0, false);
    auto markBound = [&](size_t k) {
        if (k < 64)
            boundBits |= uint64_t(1) << k;
        else
            boundMore[k] = true;
    };
    auto isBound = [&](size_t k) {
        return k < 64 ? (boundBits >> k & 1) != 0 : static_cast<bool>(boundMore[k]);
    };
    size_t nextPositional = 0;
    for (const ArgValue& a : args) {
        if (a.name.empty()) {
            if (nextPositional < params.size()) {
                c->set(params[nextPositional].name, a.value);
                markBound(nextPositional++);
            } else {
                warn(a.loc, "too many unnamed arguments supplied to '" + what + "'");
            }
            continue;
        }
        size_t k = 0;
        while (k < params.size() && params[k].name != a.name) ++k;
        if (k < params.size()) {
            c->set(a.name, a.value);
            markBound(k);
        } else if (a.name[0] == '$') {
            c->set(a.name, a.value);
        } else {
            warn(a.loc, "'" + a.name + "' is not a parameter of '" + what + "'");
        }
    }
    (void)loc;
    // Whether an argument went to another parameter of the same name: a name may be declared
    // twice (BOSL2's rounding_edge_mask has r twice), and OpenSCAD 2021 sets all defaults
    // before the arguments, so a given argument wins over the other slot's default.
    auto nameBound = [&](size_t k) {
        for (uint64_t bits = boundBits; bits != 0; bits &= bits - 1)
            if (params[size_t(std::countr_zero(bits))].name == params[k].name) return true;
        for (size_t j = 64; j < params.size(); ++j)
            if (boundMore[j] && params[j].name == params[k].name) return true;
        return false;
    };
    // Defaults see the parameters bound before them.
    for (size_t k = 0; k < params.size(); ++k)
        if (!isBound(k) && !nameBound(k))
            c->set(params[k].name,
                   params[k].defaultValue ? eval(*params[k].defaultValue, c) : Value());
    return c;
}

std::optional<Evaluator::FunctionRef> Evaluator::findFunction(const std::string& name,
                                                              const ContextPtr& ctx) {
    // A pointer to each ContextPtr, not a copy: no reference-count traffic per level.
    for (const ContextPtr* c = &ctx; *c; c = &(*c)->lexicalParent) {
        if (const Value* v = (*c)->findLocal(name); v && v->isFunction())
            return FunctionRef{&v->function().literal->params, v->function().literal->body.get(),
                               v->function().closure};
        if ((*c)->body) {
            auto it = (*c)->body->functions.find(name);
            if (it != (*c)->body->functions.end())
                return FunctionRef{&it->second->params, it->second->body.get(), *c};
        }
        for (const ContextPtr& used : (*c)->usedFiles) {
            auto it = used->body->functions.find(name);
            if (it != used->body->functions.end())
                return FunctionRef{&it->second->params, it->second->body.get(), used};
        }
    }
    return std::nullopt;
}

Value Evaluator::callFunctionExpr(const CallExpr& call, const ContextPtr& ctx) {
    // The name messages give the callee; a pointer, so a call copies no string (this one is
    // longer than std::string's inline buffer).
    static const std::string kLiteralName = "function literal";
    const std::string* name = &kLiteralName;
    std::optional<FunctionRef> user;
    if (call.callee->kind == ExprKind::Identifier) {
        name = &static_cast<const IdentifierExpr&>(*call.callee).name;
        user = findFunction(*name, ctx);
        if (!user) {
            // is_undef(name) looks name up without the unknown-variable warning, as OpenSCAD
            // 2021 does (func.cc, builtin_is_undef): BOSL2 asks is_undef($slop).
            if (*name == "is_undef" && call.args.size() == 1 &&
                call.args[0].value->kind == ExprKind::Identifier) {
                const auto& variable = static_cast<const IdentifierExpr&>(*call.args[0].value);
                return lookupVariable(variable.name, ctx, variable.loc, true).isUndef();
            }
            if (const BuiltinFunction* b = findBuiltinFunction(*name))
                return (*b)(*this, evalArgs(call.args, ctx), call.loc);
            fail(call.loc, "unknown function '" + *name + "'");
        }
    } else {
        const Value v = eval(*call.callee, ctx);
        if (!v.isFunction())
            fail(call.loc, std::string("cannot call a ") + v.typeName() + " (not a function)");
        user = FunctionRef{&v.function().literal->params, v.function().literal->body.get(),
                           v.function().closure};
    }
    return callUserFunction(user->params, user->body, user->definition, evalArgs(call.args, ctx),
                            ctx, call.loc, *name);
}

Value Evaluator::callUserFunction(const Parameters* params, const Expr* body, ContextPtr definition,
                                  ArgValues args, const ContextPtr& caller, Loc loc,
                                  const std::string& name) {
    DepthGuard guard(*this, loc, name);
    ContextPtr callerCtx = caller;
    std::string currentName = name;
    for (uint64_t tailCalls = 0;; ++tailCalls) {
        if (tailCalls > kMaxTailCalls)
            fail(loc, "recursion too deep calling '" + currentName + "' (more than " +
                          std::to_string(kMaxTailCalls) + " tail calls)");
        spend(loc, kCallSteps);
        ContextPtr c = bindParameters(*params, args, definition, callerCtx, loc, currentName);
        const Expr* e = body;
        bool tailCall = false;
        // Walk the body's tail positions; a call there to a user function loops instead of
        // recursing.
        while (!tailCall) {
            switch (e->kind) {
                case ExprKind::Ternary: {
                    const auto& t = static_cast<const TernaryExpr&>(*e);
                    e = eval(*t.condition, c).truthy() ? t.ifTrue.get() : t.ifFalse.get();
                    continue;
                }
                case ExprKind::Let: {
                    const auto& l = static_cast<const LetExpr&>(*e);
                    c = letContext(l.assignments, c);
                    e = l.body.get();
                    continue;
                }
                case ExprKind::Assert:
                case ExprKind::Echo: {
                    const auto& a = static_cast<const AssertOrEchoExpr&>(*e);
                    if (e->kind == ExprKind::Assert)
                        checkAssert(a, c);
                    else
                        echo(evalArgs(a.args, c));
                    if (!a.body) return Value();
                    e = a.body.get();
                    continue;
                }
                case ExprKind::Call: {
                    const auto& call = static_cast<const CallExpr&>(*e);
                    std::optional<FunctionRef> next;
                    std::string nextName = "function literal";
                    if (call.callee->kind == ExprKind::Identifier) {
                        nextName = static_cast<const IdentifierExpr&>(*call.callee).name;
                        next = findFunction(nextName, c);
                    }
                    if (!next) return eval(*e, c);  // a built-in or a computed callee
                    args = evalArgs(call.args, c);
                    params = next->params;
                    body = next->body;
                    definition = next->definition;
                    callerCtx = dynamicScopeOf(c, caller);
                    loc = call.loc;
                    currentName = std::move(nextName);
                    tailCall = true;
                    break;
                }
                default:
                    return eval(*e, c);
            }
        }
    }
}

}  // namespace io
